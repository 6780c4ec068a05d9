// The span model as an ODE system for the integrators (integrators/ode_system.h), and its start
// state: the static equilibrium of the free rotors at the nominal motion.
#pragma once

#include <cstdint>
#include <vector>

#include "statics/preload.h"
#include "dynamics/health.h"
#include "integrators/ode_system.h"
#include "span/span_dynamics.h"

namespace chaindrive::span {

class SpanSystem : public OdeSystem {
 public:
  SpanSystem(const SpanModel& m, const InputSignal& in, const HealthLimits& health);
  int size() const override { return model_.nStates; }
  int rhs(double t, const double* y, double* ydot) noexcept override;
  // a dense Jacobian by forward differences: the system is small
  bool hasJacobian() const override { return true; }
  int64_t jacobianNonzeros() const override { return static_cast<int64_t>(rows_.size()); }
  const int64_t* jacobianColumnPointers() const override { return columns_.data(); }
  const int64_t* jacobianRowIndices() const override { return rows_.data(); }
  int jacobian(double t, const double* y, double* values) noexcept override;
  int halfBandwidth() const override { return model_.nStates; }
  void toleranceScales(double* scale) const override;
  int velocityOf(int i) const override { return velocityOf_[i]; }
  bool isVelocity(int i) const override { return isVelocity_[i] != 0; }
  bool healthy(double t, const double* y, Failure& why) noexcept override;
  const Failure& lastError() const override { return lastError_; }
  SpanData& data() { return data_; }

 private:
  const SpanModel& model_;
  const InputSignal& in_;
  SpanData data_;
  HealthLimits health_;
  Failure lastError_;
  std::vector<int> velocityOf_;
  std::vector<char> isVelocity_;
  std::vector<int64_t> columns_, rows_;
  std::vector<double> yWork_, f0_, f1_;
};

/// Rotors at their assembled angles and nominal rates, the chamber at rest, accumulators zero.
std::vector<double> nominalSpanState(const SpanModel& m, double crankSpeed);

/// Sets the chamber's oil content of y (a model with a hydraulic chamber) to the one at rest at
/// the supply pressure [Pa] (dynamics/hydraulic_tensioner.h: chamberRestPressure) and y's guide angle.
void setChamberAtRest(const SpanModel& m, double supplyPressure, std::vector<double>& y);

/// The start state: rotors at their assembled angles and nominal speeds, the free rotors (free
/// sprockets, pivoting guides) moved to the static equilibrium of the span forces (without
/// damping, with the centrifugal part and guide friction of the nominal motion), the load
/// torques and the tensioner, by Newton's method. Throws std::runtime_error if it fails.
std::vector<double> spanInitialState(const SpanModel& m, const InputValues& inputs, const PreloadOptions& opt,
                                     PreloadReport& report);

}  // namespace chaindrive::span
