// Fixed-step velocity Verlet (kick-drift-kick, one force evaluation per step, the new forces
// evaluated at the half-step velocities: second order for position-dependent forces, first
// order in the velocity-dependent ones; extrapolating the velocity instead costs stability).
// Stable for h < 2 / omega_max. Constant cost per step and no allocation after construction: the
// scheme for real-time use. Components without a velocity state (prescribed angles, energy
// accumulators) use the trapezoidal rule on their derivatives.
#include <cmath>
#include <cstring>
#include <vector>

#include "integrators/integrators.h"
#include "run/time_grid.h"

namespace chaindrive {

namespace {

class FixedVerlet : public Integrator {
 public:
  FixedVerlet(OdeSystem& sys, const FixedStepOptions& s) : sys_(sys) {
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
    if (!(s.step > 0.0)) throw std::invalid_argument("fixed-verlet needs a positive fixed step");
    grid_.unit = s.step;
  }
  std::string name() const override { return "fixed-verlet"; }

  void reset(double t0, const double* y0) override {
    std::memcpy(y_.data(), y0, sizeof(double) * y_.size());
    grid_.start = t0;
    k_ = 0;
    eval(t0, y_.data(), f_.data());
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

 private:
  void eval(double t, const double* y, double* f) {
    const int flag = sys_.rhs(t, y, f);
    if (flag != 0) throw IntegrationError(t, sys_.lastError().kind, "right-hand side failed: " + sys_.lastError().reason);
  }
  // One step of length h ending at the grid time tNext (formed from the index, not accumulated):
  //   v_1/2 = v + h/2 a(t, x, v),   x+ = x + h v_1/2,   v+ = v_1/2 + h/2 a(t + h, x+, v_1/2);
  //   other components (no velocity state): y+ = y + h/2 (f + f+)
  void step(double h, double tNext) {
    double* y = y_.data();
    const double hh = 0.5 * h;
    for (int i : velocities_) y[i] += hh * f_[i];             // kick
    for (const auto& p : positions_) y[p.first] += h * y[p.second];  // drift
    // prescribed angles and accumulators: predictor with the old derivative, corrected below
    for (int i : others_) y[i] += h * f_[i];
    eval(tNext, y, fNew_.data());
    for (int i : velocities_) y[i] += hh * fNew_[i];          // kick
    for (int i : others_) y[i] += hh * (fNew_[i] - f_[i]);    // trapezoidal
    f_.swap(fNew_);
    ++stats_.steps;
    ++stats_.rhsEvaluations;
    stats_.lastStep = h;
    Failure why;
    if (!sys_.healthy(tNext, y, why)) throw IntegrationError(tNext, why);
  }

  OdeSystem& sys_;
  std::vector<double> y_, f_, fNew_;
  std::vector<std::pair<int, int>> positions_;
  std::vector<int> velocities_, others_;
  TimeGrid grid_;     // t0 (the last reset) + k h
  long long k_ = 0;   // grid index of the state y_
  IntegratorStats stats_;
};

}  // namespace

std::unique_ptr<Integrator> makeFixedVerlet(OdeSystem& sys, const FixedStepOptions& s) {
  return std::make_unique<FixedVerlet>(sys, s);
}

}  // namespace chaindrive
