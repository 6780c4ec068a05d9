// The links' iteration matrix against central differences of the generalized forces at a running
// state: its stiffness (M - W at a = 0, b = 1) and its damping (a = 1, b = 0) over the link ring.
#include <gtest/gtest.h>

#include <cmath>

#include "dynamics/dynamics.h"
#include "dynamics/iteration_matrix.h"
#include "test_util.h"

using namespace chaindrive;
using chaindrive::test::runningState;

namespace {

// d(link generalized forces)/d(state component `offset` of every link) by central differences,
// as a dense 3n x 3n matrix (columns: link coordinates or velocities).
Eigen::MatrixXd differenced(const Model& m, const InputSignal& in, std::vector<double> y, int offset) {
  const int n = m.chain.links;
  Data d(m);
  Eigen::MatrixXd out(3 * n, 3 * n);
  for (int col = 0; col < 3 * n; ++col) {
    double& x = y[m.linkState(col / 3, offset + col % 3)];  // the ring's order: per link x, y, gamma
    const double x0 = x, eps = offset == 0 ? (col % 3 == 2 ? 1e-8 : 1e-9) : 1e-6;
    Eigen::VectorXd plus(3 * n);
    x = x0 + eps;
    generalizedForces(m, d, in, 0.0, y.data());
    for (int r = 0; r < 3 * n; ++r) plus[r] = d.gen[m.linkGen(r / 3, r % 3)];
    x = x0 - eps;
    generalizedForces(m, d, in, 0.0, y.data());
    for (int r = 0; r < 3 * n; ++r) out(r, col) = (plus[r] - d.gen[m.linkGen(r / 3, r % 3)]) / (2.0 * eps);
    x = x0;
  }
  return out;
}

// The ring's blocks in dense form.
Eigen::MatrixXd dense(const Model& m, const Data& d, double a, double b) {
  const int n = m.chain.links;
  CyclicBlockTridiagonal3 w(n);
  linkIterationMatrix(m, d, a, b, w);
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(3 * n, 3 * n);
  for (int i = 0; i < n; ++i) {
    out.block<3, 3>(3 * i, 3 * i) += w.diagonal(i);
    out.block<3, 3>(3 * i, 3 * ((i + 1) % n)) += w.upper(i);
    out.block<3, 3>(3 * i, 3 * ((i + n - 1) % n)) += w.lower(i);
  }
  return out;
}

}  // namespace

TEST(IterationMatrix, MatchesDifferencesOfTheLinkForces) {
  const Model m = assemble(defaultDriveDescription());
  HeldInputs in(m);
  in.values.crankSpeed = 314.159;
  const std::vector<double> y = runningState(m, in);
  Data d(m);
  generalizedForces(m, d, in, 0.0, y.data());
  int closed = 0;
  for (int i = 0; i < d.nContacts; ++i) closed += d.contacts[i].gap < 0.0;
  ASSERT_GT(closed, 5) << "the state should have closed contacts";
  const int n = m.chain.links;
  Eigen::MatrixXd mass = Eigen::MatrixXd::Zero(3 * n, 3 * n);
  for (int i = 0; i < n; ++i) mass.block<3, 3>(3 * i, 3 * i) = Eigen::Vector3d(m.chain.mass, m.chain.mass, m.chain.inertia).asDiagonal();
  const Eigen::MatrixXd stiffness = mass - dense(m, d, 0.0, 1.0), damping = mass - dense(m, d, 1.0, 0.0);
  const Eigen::MatrixXd fdStiffness = differenced(m, in, y, 0), fdDamping = differenced(m, in, y, 3);
  // the link-to-link part of the differences is what W models (rotor couplings are explicit)
  const double kErr = (stiffness - fdStiffness).norm() / fdStiffness.norm();
  const double cErr = (damping - fdDamping).norm() / fdDamping.norm();
  std::printf("relative Frobenius difference: stiffness %.3e, damping %.3e (%d closed contacts)\n", kErr, cErr, closed);
  EXPECT_LT(kErr, 2e-3);
  EXPECT_LT(cErr, 2e-3);
}
