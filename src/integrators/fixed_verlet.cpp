// Fixed-step velocity Verlet (kick-drift-kick, one force evaluation per step, the new forces
// evaluated at the half-step velocities: second order for position-dependent forces, first
// order in the velocity-dependent ones; extrapolating the velocity instead costs stability).
// Stable for h < 2 / omega_max. Constant cost per step and no allocation after construction: the
// scheme for real-time use. Components without a velocity state (prescribed angles, energy
// accumulators) use the trapezoidal rule on their derivatives.
#include "integrators/fixed_step.h"
#include "integrators/integrators.h"

namespace chaindrive {

namespace {

class FixedVerlet : public FixedStepScheme {
 public:
  FixedVerlet(OdeSystem& sys, const FixedStepOptions& s) : FixedStepScheme(sys, s, "fixed-verlet") {}
  std::string name() const override { return "fixed-verlet"; }

 private:
  // One step of length h ending at the grid time tNext (formed from the index, not accumulated):
  //   v_1/2 = v + h/2 a(t, x, v),   x+ = x + h v_1/2,   v+ = v_1/2 + h/2 a(t + h, x+, v_1/2);
  //   other components (no velocity state): y+ = y + h/2 (f + f+)
  void step(double h, double tNext) override {
    double* y = y_.data();
    const double hh = 0.5 * h;
    const double* f = f_.data();
    const double* fNew = fNew_.data();
    velocities_.forEachRun([&](int i, int, int n) { addScaled(y + i, f + i, hh, n); });  // kick
    positions_.forEachRun([&](int i, int v, int n) { addScaled(y + i, y + v, h, n); });  // drift
    // prescribed angles and accumulators: predictor with the old derivative, corrected below
    others_.forEachRun([&](int i, int, int n) { addScaled(y + i, f + i, h, n); });
    check(tNext, sys_.rhs(tNext, y, fNew_.data()), "right-hand side failed: ");
    velocities_.forEachRun([&](int i, int, int n) { addScaled(y + i, fNew + i, hh, n); });  // kick
    others_.forEach([&](int i, int) { y[i] += hh * (fNew[i] - f[i]); });  // trapezoidal
    finishStep(h, tNext);
  }
};

}  // namespace

std::unique_ptr<Integrator> makeFixedVerlet(OdeSystem& sys, const FixedStepOptions& s) {
  return std::make_unique<FixedVerlet>(sys, s);
}

}  // namespace chaindrive
