// Fixed-step velocity Verlet (kick-drift-kick, one force evaluation per step, the new forces
// evaluated at the half-step velocities: second order for position-dependent forces, first
// order in the velocity-dependent ones; extrapolating the velocity instead costs stability).
// Stable for h < 2 / omega_max. Constant cost per step and no allocation after construction: the
// scheme for real-time use. Components without a velocity state (prescribed angles, energy
// accumulators) use the trapezoidal rule on their derivatives.
//
// fixed-verlet-implicit-damping: the same with each kick linearly implicit in the damping of its
// own component (OdeSystem::dampedKicks, r = -d(acceleration)/d(velocity) in the stiff part): v +=
// h/2 a / (1 + h/2 r), i.e. v+ = v + h/2 (a + r v - r v+) with the damping at the new velocity. Explicit damping shrinks Verlet's stable step from 2 / omega to about
// 2 (sqrt(1 + zeta^2) - zeta) / omega (zeta: the mode's damping ratio); on the chain drive, whose
// stiffest modes are the links turning and shifting against their joints and seated rollers
// (about 4.9e5 rad/s, damped by the joints and the contacts' Hunt-Crossley and regularised
// friction terms), that is 3.2 instead of about 4 us. The damping treated implicitly, the step
// grows towards the undamped limit; off the diagonal (a link's damping through its neighbours)
// it stays explicit. First order in the damping, as Verlet is.
#include <string>

#include "integrators/fixed_step.h"
#include "integrators/integrators.h"

namespace chaindrive {

namespace {

class FixedVerlet : public FixedStepScheme {
 public:
  FixedVerlet(OdeSystem& sys, const FixedStepOptions& s, VerletDamping damping)
      : FixedStepScheme(sys, s, nameOf(damping)), damping_(damping) {
    if (damping != VerletDamping::Explicit && !sys.hasDampedKicks())
      throw std::invalid_argument(nameOf(damping) + " needs a system with damped kicks: the link fidelity with "
                                  "compliant contacts");
    kick_.assign(damping != VerletDamping::Explicit ? y_.size() : 0, 0.0);
    sys.setDerivativesOnly(damping == VerletDamping::Explicit);
  }
  std::string name() const override { return nameOf(damping_); }

  void reset(double t0, const double* y0) override {
    FixedStepScheme::reset(t0, y0);
    if (damping_ != VerletDamping::Explicit) sys_.dampedKicks(0.5 * grid_.unit, damping_ == VerletDamping::Constant, kick_.data());
  }

 private:
  static std::string nameOf(VerletDamping d) {
    return d == VerletDamping::Explicit   ? "fixed-verlet"
           : d == VerletDamping::Constant ? "fixed-verlet-implicit-constant-damping"
                                          : "fixed-verlet-implicit-damping";
  }

  // One step of length h ending at the grid time tNext (formed from the index, not accumulated):
  //   v_1/2 = v + h/2 a(t, x, v),   x+ = x + h v_1/2,   v+ = v_1/2 + h/2 a(t + h, x+, v_1/2);
  //   other components (no velocity state): y+ = y + h/2 (f + f+)
  // (with implicit damping each kick's h/2 is h/2 / (1 + h/2 r) of its evaluation's rates r)
  void step(double h, double tNext) override {
    double* y = y_.data();
    const double hh = 0.5 * h;
    const double* f = f_.data();
    const double* fNew = fNew_.data();
    if (damping_ == VerletDamping::Explicit && velocitiesArePartners_) {  // (the same, in one pass)
      positions_.forEachRun([&](int i, int v, int n) { kickAndDrift(y + i, y + v, f + v, hh, h, n); });
    } else {
      kick(y, f, hh);
      positions_.forEachRun([&](int i, int v, int n) { addScaled(y + i, y + v, h, n); });  // drift
    }
    // prescribed angles and accumulators: predictor with the old derivative, corrected below
    others_.forEachRun([&](int i, int, int n) { addScaled(y + i, f + i, h, n); });
    check(tNext, sys_.rhs(tNext, y, fNew_.data()), "right-hand side failed: ");
    if (damping_ == VerletDamping::All) sys_.dampedKicks(hh, false, kick_.data());
    kick(y, fNew, hh);
    others_.forEach([&](int i, int) { y[i] += hh * (fNew[i] - f[i]); });  // trapezoidal
    finishStep(h, tNext);
  }

  void kick(double* y, const double* a, double hh) const {
    if (damping_ != VerletDamping::Explicit)
      velocities_.forEachRun([&](int i, int, int n) { addScaledBy(y + i, a + i, kick_.data() + i, n); });
    else
      velocities_.forEachRun([&](int i, int, int n) { addScaled(y + i, a + i, hh, n); });
  }

  VerletDamping damping_;
  std::vector<double> kick_;  // the kicks' factors (All: at the last evaluation's damping rates)
};

}  // namespace

std::unique_ptr<Integrator> makeFixedVerlet(OdeSystem& sys, const FixedStepOptions& s, VerletDamping damping) {
  return std::make_unique<FixedVerlet>(sys, s, damping);
}

}  // namespace chaindrive
