#include "span/span_modes.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Dense>

#include "integrators/stable_step.h"

namespace chaindrive::span {

namespace {

// A guide table's slope dl/dpsi [m/rad] at the drawn pose (psi = 0), linear between its nodes.
double slopeAtDrawnPose(const GuideTable& t) {
  if (t.slope.empty()) return 0.0;
  const double u = std::clamp((0.0 - t.angle0) / t.dAngle, 0.0, static_cast<double>(t.slope.size() - 1));
  const std::size_t i = std::min(static_cast<std::size_t>(u), t.slope.size() - 1);
  if (i + 1 >= t.slope.size()) return t.slope[i];
  const double f = u - static_cast<double>(i);
  return (1.0 - f) * t.slope[i] + f * t.slope[i + 1];
}

}  // namespace

SpanModeStep spanModeStep(const SpanModel& sm) {
  // the free rotors' rows
  const int nRotors = static_cast<int>(sm.rotorInertia.size());
  std::vector<int> row(nRotors, -1);
  int n = 0;
  for (int r = 0; r < nRotors; ++r)
    if (sm.stateRate[r] >= 0) row[r] = n++;
  SpanModeStep s;
  s.step = std::numeric_limits<double>::infinity();
  if (n == 0) return s;
  // K = sum over spans of k b b^T with b the stretch's lever at each free rotor; scaled by the
  // inertias on both sides (M^-1/2 K M^-1/2, symmetric)
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
  double dampingOverStiffness = 0.0, stiffest = -1.0;
  for (const Span& sp : sm.spans) {
    Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
    double ownRate = 0.0;  // the span alone against its rotors: k sum b_r^2 / J_r
    auto lever = [&](int rotor, double arm) {
      if (rotor < 0 || row[rotor] < 0) return;
      b[row[rotor]] += arm / std::sqrt(sm.rotorInertia[rotor]);
      ownRate += arm * arm / sm.rotorInertia[rotor];
    };
    lever(sp.from.rotor, -sp.from.radius);
    lever(sp.to.rotor, sp.to.radius);
    if (sp.table >= 0) lever(sm.tables[sp.table].rotor, slopeAtDrawnPose(sm.tables[sp.table]));
    K += sp.stiffness * b * b.transpose();
    if (sp.stiffness > 0.0) dampingOverStiffness = std::max(dampingOverStiffness, sp.damping / sp.stiffness);
    if (sp.stiffness * ownRate > stiffest) {
      stiffest = sp.stiffness * ownRate;
      s.stiffestSpan = sp.name;
      s.spanStiffness = sp.stiffness;
    }
  }
  const double lambda = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(K, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff();
  if (!(lambda > 0.0)) return s;
  s.omega = std::sqrt(lambda);
  s.step = verletStableStep(s.omega, dampingOverStiffness * lambda);
  return s;
}

}  // namespace chaindrive::span
