// The default drive's hydraulic tensioner in the drive: its chamber's start state, its Jacobian
// entries, every method that runs it, and the oil supply's pressure acting through it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "dynamics/body_forces.h"
#include "dynamics/dynamics.h"
#include "dynamics/hydraulic_tensioner.h"
#include "dynamics/jacobian.h"
#include "math/elementary.h"
#include "run/simulation.h"
#include "test_util.h"

using namespace chaindrive;
using chaindrive::test::constantLoads;
using chaindrive::test::defaultModel;
using chaindrive::test::named;
using chaindrive::test::runningState;

namespace {

const HydraulicTensionerDesc& device() { return defaultModel()->tensioner.hydraulic; }

// The tensioner's chamber pressure and check-valve flow every 0.1 ms of a run at 3000 rpm.
struct ChamberSeries {
  std::vector<double> pressure, checkFlow, force;
};

ChamberSeries chamberRun(const SimulationOptions& opt, double tEnd, double supplyPressure = 3e5) {
  const auto m = defaultModel();
  auto in = std::make_unique<HeldInputs>(*m);
  in->values.crankSpeed = 3000.0 * 2.0 * kPi / 60.0;
  in->values.supplyPressure = supplyPressure;
  Simulation sim(m, opt, std::move(in));
  sim.start(0.0);
  ChamberSeries s;
  for (int k = 1; k * 1e-4 <= tEnd + 1e-12; ++k) {
    sim.advanceTo(1e-4 * k);
    const Outputs& o = sim.outputs();
    s.pressure.push_back(o.chamberPressure);
    s.checkFlow.push_back(o.tensionerFlows.check);
    s.force.push_back(o.tensionerForce);
  }
  return s;
}

double mean(const std::vector<double>& x) {
  double sum = 0.0;
  for (double v : x) sum += v;
  return sum / static_cast<double>(x.size());
}

}  // namespace

// The start state holds the chamber at rest: the oil content that fills it to the supply less the
// check valve's cracking pressure at the preloaded pose, and the plunger pushes with its spring
// and that pressure on its area (the pressure back from the content through the law's table,
// within its interpolation error of about 2e-8).
TEST(HydraulicDrive, StartsWithTheChamberAtRest) {
  const auto m = defaultModel();
  ASSERT_TRUE(m->tensioner.hydraulicChamber());
  SimulationOptions opt;
  Simulation sim(m, opt, constantLoads(*m, 3000.0));
  sim.start(0.0);
  const double rest = chamberRestPressure(device(), 3e5);
  EXPECT_NEAR(rest, 3e5 - device().checkValve.crackingPressure, 1e-9);
  const TensionerModel& t = m->tensioner;
  const double angle = sim.state()[m->rotors[t.rotor].stateAngle];
  EXPECT_EQ(sim.state()[m->stateChamberOil],
            chamberOilAt(t, m->rotors[t.rotor].axis, math::cos(angle), math::sin(angle), rest));
  const Outputs& o = sim.outputs();
  EXPECT_NEAR(o.chamberPressure, rest, 1e-7 * rest);
  const double spring = t.preload - t.stiffness * o.tensionerStroke;
  EXPECT_NEAR(o.tensionerForce, spring + rest * plungerArea(device()), 1e-7 * o.tensionerForce);
}

// The chamber's entries of the sparse Jacobian (its row over the guide's angle and the oil
// content; the guide's acceleration over the content) agree with central differences of the
// whole right-hand side; the content's rate does not depend on the guide's rate.
TEST(HydraulicDrive, JacobianEntriesMatchCentralDifferences) {
  const Model& m = *defaultModel();
  HeldInputs in(m);
  in.values.crankSpeed = 314.159;
  std::vector<double> y = runningState(m, in);
  Data d(m);
  JacobianAssembler jac(m);
  std::vector<double> values(jac.nnz());
  jac.assemble(m, d, in, 0.0, y.data(), values.data());
  const RotorModel& guide = m.rotors[m.tensioner.rotor];
  const int c = m.stateChamberOil;
  const double hc = 1e-8 * device().chamberVolume;  // (about 10 Pa)
  const auto& cp = jac.columnPointers();
  const auto& ri = jac.rowIndices();
  auto entry = [&](int row, int col) {
    for (int64_t k = cp[col]; k < cp[col + 1]; ++k)
      if (ri[k] == row) return values[k];
    ADD_FAILURE() << "no entry (" << row << ", " << col << ") in the pattern";
    return 0.0;
  };
  std::vector<double> fp(m.nStates), fm(m.nStates);
  auto central = [&](int row, int col, double h) {
    std::vector<double> yp(y), ym(y);
    yp[col] += h;
    ym[col] -= h;
    forwardCompliant(m, d, in, 0.0, yp.data(), fp.data());
    forwardCompliant(m, d, in, 0.0, ym.data(), fm.data());
    return (fp[row] - fm[row]) / (2.0 * h);
  };
  const struct {
    int row, col;
    double h;
  } checks[] = {{c, guide.stateAngle, 1e-8}, {c, c, hc}, {guide.stateRate, c, hc}};
  for (const auto& k : checks) {
    const double fd = central(k.row, k.col, k.h), jv = entry(k.row, k.col);
    EXPECT_NEAR(jv, fd, 1e-3 * std::fabs(fd)) << "row " << k.row << " col " << k.col;
  }
  EXPECT_EQ(central(c, guide.stateRate, 1e-5), 0.0);
}

// Every method that integrates the chamber runs the default drive: the link model with each
// fixed-step and adaptive integrator and with time stepping, the span model; the pressure stays
// between the cavitation floor and the relief valve's full lift, and the check valve never lets
// oil flow back.
TEST(HydraulicDrive, EveryMethodRunsTheChamber) {
  struct Case {
    const char* fidelity;
    const char* method;
    const char* contacts;
    double step;
  };
  const Case cases[] = {{"link", "fixed-verlet", "compliant", 2.5e-6},
                        {"link", "fixed-verlet-implicit-joint-damping", "compliant", 1e-4 / 28},
                        {"link", "fixed-newmark", "compliant", 5e-6},
                        {"link", "arkode-erk", "compliant", 0.0},
                        {"link", "cvode-bdf-klu", "compliant", 0.0},
                        {"link", "fixed-verlet", "time-stepping", 2.5e-6},
                        {"span", "fixed-verlet", "compliant", 2e-5},
                        {"span", "arkode-erk", "compliant", 0.0}};
  const double floor = device().oil.vapourPressure - device().oil.atmosphericPressure;
  const double ceiling = device().reliefValve.crackingPressure + device().reliefValve.fullLiftPressure;
  for (const Case& c : cases) {
    SimulationOptions opt;
    opt.fidelity = named<Fidelity>(c.fidelity);
    opt.integrator.method = named<IntegratorMethod>(c.method);
    opt.contactMethod = named<ContactMethod>(c.contacts);
    if (c.step > 0.0) opt.integrator.fixed.step = c.step;
    const double tEnd = std::string(c.method) == "cvode-bdf-klu" ? 2e-3 : 1e-2;
    const ChamberSeries s = chamberRun(opt, tEnd);
    const std::string what = std::string(c.fidelity) + " " + c.method + " " + c.contacts;
    ASSERT_FALSE(s.pressure.empty()) << what;
    for (std::size_t k = 0; k < s.pressure.size(); ++k) {
      ASSERT_TRUE(std::isfinite(s.pressure[k]) && std::isfinite(s.force[k])) << what << " at sample " << k;
      EXPECT_GE(s.pressure[k], floor) << what;
      EXPECT_LE(s.pressure[k], ceiling) << what;
      EXPECT_GE(s.checkFlow[k], 0.0) << what;
    }
    std::printf("%-50s chamber %.2f .. %.2f bar, tensioner force %.1f .. %.1f N\n", what.c_str(),
                *std::min_element(s.pressure.begin(), s.pressure.end()) * 1e-5,
                *std::max_element(s.pressure.begin(), s.pressure.end()) * 1e-5,
                *std::min_element(s.force.begin(), s.force.end()), *std::max_element(s.force.begin(), s.force.end()));
  }
}

// The engine's oil pressure acts through the check valve: a higher supply pressure fills the
// chamber higher and the plunger pushes harder.
TEST(HydraulicDrive, SupplyPressureRaisesTheChamberAndTheForce) {
  SimulationOptions opt;
  const ChamberSeries low = chamberRun(opt, 0.03, 2e5), high = chamberRun(opt, 0.03, 5e5);
  EXPECT_GT(mean(high.pressure), mean(low.pressure) + 2e5);
  EXPECT_GT(mean(high.force), mean(low.force));
  std::printf("supply 2 bar: chamber %.2f bar, force %.1f N; 5 bar: %.2f bar, %.1f N (means over 30 ms)\n",
              mean(low.pressure) * 1e-5, mean(low.force), mean(high.pressure) * 1e-5, mean(high.force));
}
