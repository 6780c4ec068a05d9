// The element-wise Jacobian agrees with a central difference of the whole right-hand side.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "dynamics/data.h"
#include "dynamics/dynamics.h"
#include "dynamics/jacobian.h"
#include "assembly/model.h"
#include "statics/preload.h"
#include "test_util.h"

using namespace chaindrive;
using chaindrive::test::runningState;

TEST(Jacobian, MatchesCentralDifferencesOfTheRightHandSide) {
  const Model m = assemble(defaultDriveDescription());
  HeldInputs in(m);
  in.values.crankSpeed = 314.159;
  in.values.loadTorque[m.rotorIndex("camshaftIntake")] = 3.0;
  in.values.loadTorque[m.rotorIndex("camshaftExhaust")] = 3.0;
  std::vector<double> y = runningState(m, in);
  Data d(m);
  JacobianAssembler jac(m);
  std::vector<double> values(jac.nnz());
  jac.assemble(m, d, in, 0.0, y.data(), values.data());
  ASSERT_GT(d.nContacts, 5);
  // compare column by column for a sample of columns: every state of a few links and all rotors
  std::vector<int> cols;
  for (int link : {0, 1, 37, 64, 119})
    for (int k = 0; k < 6; ++k) cols.push_back(m.linkState(link, k));
  for (const auto& r : m.rotors) {
    cols.push_back(r.stateAngle);
    if (r.stateRate >= 0) cols.push_back(r.stateRate);
  }
  std::vector<double> fp(m.nStates), fm(m.nStates);
  const auto& cp = jac.columnPointers();
  const auto& ri = jac.rowIndices();
  double worst = 0.0;
  for (int c : cols) {
    const int comp = c / m.chain.links;  // the link component of a link state (model.h)
    const double h = c < 6 * m.chain.links ? (comp < 2 ? 1e-9 : comp == 2 ? 1e-8 : comp < 5 ? 1e-6 : 1e-5) : 1e-8;
    std::vector<double> yp(y), ym(y);
    yp[c] += h;
    ym[c] -= h;
    forwardCompliant(m, d, in, 0.0, yp.data(), fp.data());
    forwardCompliant(m, d, in, 0.0, ym.data(), fm.data());
    std::vector<double> dense(m.nStates, 0.0);
    for (int64_t k = cp[c]; k < cp[c + 1]; ++k) dense[ri[k]] = values[k];
    double colMax = 0.0;
    for (int r = 0; r < m.stateInputWork; ++r) colMax = std::max(colMax, std::fabs((fp[r] - fm[r]) / (2 * h)));
    for (int r = 0; r < m.stateInputWork; ++r) {
      const double fd = (fp[r] - fm[r]) / (2 * h);
      const double err = std::fabs(fd - dense[r]) / std::max(colMax, 1e-300);
      worst = std::max(worst, err);
      EXPECT_LT(err, 1e-3) << "row " << r << " col " << c << ": fd " << fd << " jac " << dense[r];
    }
  }
  std::printf("largest relative Jacobian error over the sampled columns: %.3e\n", worst);
}
