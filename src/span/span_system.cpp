#include "span/span_system.h"

#include <ctime>
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Dense>

#include "dynamics/body_forces.h"
#include "dynamics/health.h"
#include "math/elementary.h"

namespace chaindrive::span {

SpanSystem::SpanSystem(const SpanModel& m, const InputSignal& in, const HealthLimits& health)
    : model_(m), in_(in), data_(m), health_(health) {
  const int n = m.nStates;
  velocityOf_.assign(n, -1);
  isVelocity_.assign(n, 0);
  for (std::size_t r = 0; r < m.stateAngle.size(); ++r)
    if (m.stateRate[r] >= 0) {
      velocityOf_[m.stateAngle[r]] = m.stateRate[r];
      isVelocity_[m.stateRate[r]] = 1;
    }
  for (int c = 0; c <= n; ++c) columns_.push_back(static_cast<int64_t>(c) * n);
  for (int c = 0; c < n; ++c)
    for (int r = 0; r < n; ++r) rows_.push_back(r);
  yWork_.assign(n, 0.0);
  f0_.assign(n, 0.0);
  f1_.assign(n, 0.0);
}

int SpanSystem::rhs(double t, const double* y, double* ydot) noexcept {
  spanForward(model_, data_, in_, t, y, ydot);
  if (data_.seatUnsolved) {
    lastError_ = {FailureKind::NonFinite, "the tension guide's seat on its chain found no balance (spanModel.guideSeat)"};
    return 1;
  }
  for (int i = 0; i < model_.nStates; ++i)
    if (!std::isfinite(ydot[i])) {
      lastError_ = {FailureKind::NonFinite, "non-finite derivative"};
      return 1;
    }
  return 0;
}

int SpanSystem::jacobian(double t, const double* y, double* values) noexcept {
  const int n = model_.nStates;
  spanForward(model_, data_, in_, t, y, f0_.data());
  for (int c = 0; c < n; ++c) {
    if (c >= model_.chainImpulse.first) {  // (nothing depends on the step means' accumulators)
      std::fill_n(values + static_cast<std::size_t>(c) * n, n, 0.0);
      continue;
    }
    std::copy(y, y + n, yWork_.begin());
    const double h = 1e-7 * std::max(1.0, std::fabs(y[c]));
    yWork_[c] += h;
    spanForward(model_, data_, in_, t, yWork_.data(), f1_.data());
    for (int r = 0; r < n; ++r) values[static_cast<std::size_t>(c) * n + r] = (f1_[r] - f0_[r]) / h;
  }
  return 0;
}

void SpanSystem::toleranceScales(double* scale) const {
  for (std::size_t r = 0; r < model_.stateAngle.size(); ++r) {
    scale[model_.stateAngle[r]] = 1e-2;
    if (model_.stateRate[r] >= 0) scale[model_.stateRate[r]] = 10.0;
  }
  scale[model_.stateInputWork] = 1.0;
  scale[model_.stateDissipated] = 1.0;
  if (model_.stateChamberOil >= 0) scale[model_.stateChamberOil] = chamberOilScale(model_.links->tensioner.hydraulic);
  impulseToleranceScales(model_.chainImpulse, static_cast<int>(model_.stateAngle.size()), scale);
}

bool SpanSystem::healthy(double t, const double* y, Failure& why) noexcept {
  // finite state; no span stretched beyond the blow-up deformation per link; every pivoting
  // guide inside the angle range of its table
  if (!finiteState(y, model_.nStates, why)) return false;
  if (model_.stateChamberOil >= 0 && !chamberFilled(y[model_.stateChamberOil], t, why)) return false;
  const Model& lm = *model_.links;
  for (std::size_t i = 0; i < model_.spans.size(); ++i) {
    const double perLink = std::fabs(data_.spans[i].stretch) / model_.spans[i].links;
    if (perLink > health_.blowUpDeformation * lm.chain.pitch) {
      why = {FailureKind::BlowUp, "blow-up at t = " + std::to_string(t) + " s: span " + model_.spans[i].name +
                                      " stretched by " + std::to_string(perLink * 1e3) + " mm per link"};
      return false;
    }
  }
  for (const GuideTable& g : model_.tables) {
    const double a = y[model_.stateAngle[g.rotor]];
    if (a < g.angleMin() || a > g.angleMax()) {
      why = {FailureKind::BlowUp, "blow-up at t = " + std::to_string(t) + " s: guide '" + lm.rotors[g.rotor].name +
                                      "' at " + std::to_string(a * 57.29577951308232) +
                                      " deg, outside its angle range"};
      return false;
    }
  }
  return true;
}

std::vector<double> nominalSpanState(const SpanModel& m, double crankSpeed) {
  const Model& lm = *m.links;
  std::vector<double> y(m.nStates, 0.0);
  const std::vector<double> rates = nominalRotorRates(lm, crankSpeed);
  for (std::size_t r = 0; r < lm.rotors.size(); ++r) {
    y[m.stateAngle[r]] = lm.rotors[r].initialAngle;
    if (m.stateRate[r] >= 0) y[m.stateRate[r]] = rates[r];
  }
  if (m.stateChamberOil >= 0) setChamberAtRest(m, lm.tensioner.hydraulic.supplyPressure, y);
  return y;
}

void setChamberAtRest(const SpanModel& m, double supplyPressure, std::vector<double>& y) {
  y[m.stateChamberOil] = chamberOilAtRest(*m.links, y[m.stateAngle[m.links->tensioner.rotor]], supplyPressure);
}

namespace {

// Newton's method on the torques of the free rotors over their angles (forward differences).
struct StaticSolve {
  static constexpr double kMaxStep = 0.005;  // [rad]
  const SpanModel& m;
  SpanData d;
  HeldInputs held;
  std::vector<int> free;  // rotors
  StaticSolve(const SpanModel& sm, const InputValues& in) : m(sm), d(sm), held(*sm.links) {
    held.values = in;
    d.quasiStatic = true;
    for (std::size_t r = 0; r < m.stateRate.size(); ++r)
      if (m.stateRate[r] >= 0) free.push_back(static_cast<int>(r));
  }
  Eigen::VectorXd residual(const std::vector<double>& y) {
    evaluateSpanForces(m, d, held, 0.0, y.data());
    Eigen::VectorXd r(free.size());
    for (std::size_t i = 0; i < free.size(); ++i) r[i] = d.rotorGen[free[i]];
    return r;
  }
  int run(std::vector<double>& y, const PreloadOptions& opt, double& rMax) {
    const double tol = opt.forceTolerance * m.links->chain.pitch;
    const int n = static_cast<int>(free.size());
    for (int it = 0; it < opt.maxIterations; ++it) {
      const Eigen::VectorXd r = residual(y);
      rMax = r.cwiseAbs().maxCoeff();
      if (!std::isfinite(rMax)) return -1;
      if (rMax <= tol) return it;
      Eigen::MatrixXd J(n, n);
      for (int c = 0; c < n; ++c) {
        std::vector<double> yp = y;
        yp[m.stateAngle[free[c]]] += 1e-7;
        J.col(c) = (residual(yp) - r) / 1e-7;
      }
      // steps of at most kMaxStep keep the guides inside their tables, where the torques are smooth
      Eigen::VectorXd dq = J.fullPivLu().solve(-r);
      const double largest = dq.cwiseAbs().maxCoeff();
      if (largest > kMaxStep) dq *= kMaxStep / largest;
      for (int c = 0; c < n; ++c) y[m.stateAngle[free[c]]] += dq[c];
    }
    rMax = residual(y).cwiseAbs().maxCoeff();
    return opt.maxIterations;
  }
};

}  // namespace

std::vector<double> spanInitialState(const SpanModel& m, const InputValues& inputs, const PreloadOptions& opt,
                                     PreloadReport& report) {
  const std::clock_t t0 = std::clock();
  std::vector<double> y = nominalSpanState(m, inputs.crankSpeed);
  // the chamber at rest, as the link model's (statics/preload.cpp): its pressure held in the
  // solve, its content then the one that holds it at the solved pose
  const bool chamber = m.stateChamberOil >= 0;
  if (chamber) setChamberAtRest(m, inputs.supplyPressure, y);
  report = PreloadReport{};
  if (!opt.enabled) {
    report.converged = true;
    report.message = "preload disabled";
    return y;
  }
  StaticSolve solve(m, inputs);
  if (chamber) holdChamberAtRest(m.links->tensioner, inputs.supplyPressure, solve.d.chamber);
  // the solve at the nominal rates of the sprockets and at rest for the guides
  double rMax = 0.0;
  const int it = solve.run(y, opt, rMax);
  if (it < 0) throw std::runtime_error("span preload diverged (non-finite torque)");
  if (chamber) setChamberAtRest(m, inputs.supplyPressure, y);
  report.iterations = it;
  report.residual = rMax / m.links->chain.pitch;
  report.converged = it < opt.maxIterations;
  report.cpuSeconds = static_cast<double>(std::clock() - t0) / CLOCKS_PER_SEC;
  report.message = report.converged ? "span static equilibrium in " + std::to_string(it) + " Newton iterations"
                                    : "span static equilibrium not reached (torque residual " +
                                          std::to_string(rMax) + " N m)";
  return y;
}

}  // namespace chaindrive::span
