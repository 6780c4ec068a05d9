// What the fixed-step mechanical schemes share: the state split into positions (with the index
// of their velocity), velocities and other components (no velocity state: prescribed angles,
// energy accumulators), whole steps on the time grid from the last reset, and the derivative
// of the current state carried from step to step (one force evaluation per step).
#pragma once

#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "integrators/ode_system.h"
#include "run/time_grid.h"

namespace chaindrive {

class FixedStepScheme : public Integrator {
 public:
  FixedStepScheme(OdeSystem& sys, const FixedStepOptions& s, const std::string& name) : sys_(sys) {
    if (!(s.step > 0.0)) throw std::invalid_argument(name + " needs a positive fixed step");
    const int n = sys.size();
    y_.assign(n, 0.0);
    f_.assign(n, 0.0);
    fNew_.assign(n, 0.0);
    for (int i = 0; i < n; ++i) {
      const int v = sys.velocityOf(i);
      if (v >= 0) positions_.push_back({i, v});
      else if (sys.isVelocity(i)) velocities_.push_back(i);
      else others_.push_back(i);
    }
    grid_.unit = s.step;
  }

  void reset(double t0, const double* y0) override {
    std::memcpy(y_.data(), y0, sizeof(double) * y_.size());
    grid_.start = t0;
    k_ = 0;
    check(t0, sys_.rhs(t0, y_.data(), f_.data()), "right-hand side failed: ");
    ++stats_.rhsEvaluations;
  }

  void advance(double tout, double* y) override {
    // whole steps of exactly h on the grid from the last reset: the step times are t0 + k h,
    // whatever way the caller formed tout
    const long long target = grid_.indexOf(tout);
    for (; k_ < target; ++k_) step(grid_.unit, grid_.time(k_ + 1));
    std::memcpy(y, y_.data(), sizeof(double) * y_.size());
  }

  double fixedStep() const override { return grid_.unit; }
  IntegratorStats stats() const override { return stats_; }

 protected:
  /// One step of length h to the grid time tNext: y_ and f_ (its derivative) advanced.
  virtual void step(double h, double tNext) = 0;

  void check(double t, int flag, const char* what) {
    if (flag != 0) throw IntegrationError(t, sys_.lastError().kind, what + sys_.lastError().reason);
  }
  /// Counts the step and checks the state it reached.
  void finishStep(double h, double tNext) {
    f_.swap(fNew_);
    ++stats_.steps;
    ++stats_.rhsEvaluations;
    stats_.lastStep = h;
    Failure why;
    if (!sys_.healthy(tNext, y_.data(), why)) throw IntegrationError(tNext, why);
  }

  OdeSystem& sys_;
  std::vector<double> y_, f_, fNew_;  // f_: derivative of y_; fNew_: the step's new one
  std::vector<std::pair<int, int>> positions_;
  std::vector<int> velocities_, others_;
  TimeGrid grid_;     // t0 (the last reset) + k h
  long long k_ = 0;   // grid index of the state y_
  IntegratorStats stats_;
};

}  // namespace chaindrive
