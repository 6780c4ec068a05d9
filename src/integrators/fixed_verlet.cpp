// Fixed-step velocity Verlet (kick-drift-kick, one force evaluation per step, the new forces
// evaluated at the half-step velocities: second order for position-dependent forces, first
// order in the velocity-dependent ones; extrapolating the velocity instead costs stability).
// Stable for h < 2 / omega_max. Constant cost per step and no allocation after construction: the
// scheme for real-time use. Components without a velocity state (prescribed angles, energy
// accumulators) use the trapezoidal rule on their derivatives.
//
// The kicks with the damping implicit. Explicit damping shrinks Verlet's stable step from
// 2 / omega to about 2 (sqrt(1 + zeta^2) - zeta) / omega (zeta: the mode's damping ratio); on the
// chain drive, whose stiffest modes are neighbouring links turning and shifting against each
// other through their joints and seated rollers (about 4.9e5 rad/s, zeta about 0.3 from the
// joints' dampers), that is 3.2 instead of 4 us. The implicit kick v+ = v + h/2 (I + h/2 C)^-1 a
// (C: the damping over the masses, a: the accelerations at v) lifts that limit; the variants
// approximate its solve:
// - fixed-verlet-implicit-joint-damping (the real-time method): the joints' damping, constant
//   without clearance, by one Jacobi sweep from h/2 a: v+ = v + h/2 (I + h/2 D)^-1 (a - h/2 (C - D) a)
//   (OdeSystem::dampedKicks for the diagonal D, dampOffDiagonal for the rest). Exact to first order
//   in h C for every motion, the rigid ones (C a = 0) unchanged; on neighbours moving against
//   each other the kick shrinks as the implicit one does, which keeps the step stable beyond
//   4.5 us on the default drive (plain Verlet: 3.2 us) with the cycle statistics within the
//   reference's scatter (docs/benchmark_realtime.md). The contacts' damping stays explicit.
// - fixed-verlet-implicit-damping: the joints' and contacts' damping by its diagonal alone,
//   v+ = v + h/2 (I + h/2 D)^-1 a, re-evaluated every step. It slows every motion's kick by
//   1 / (1 + h/2 D), rigid ones too, the tension waves of the spans included: stable to 3.8 us
//   but with the cycle statistics off (a result kept for the study's chart).
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
    sys.setDerivativesOnly(damping != VerletDamping::All);  // (All reads each evaluation's damping rates)
  }
  std::string name() const override { return nameOf(damping_); }

  void reset(double t0, const double* y0) override {
    shareRuns();
    FixedStepScheme::reset(t0, y0);
    if (damping_ == VerletDamping::Explicit) return;
    sys_.dampedKicks(0.5 * grid_.unit, damping_ == VerletDamping::Joints, kick_.data());
    if (damping_ == VerletDamping::Joints && !sys_.dampOffDiagonal(0.5 * grid_.unit, f_.data()))
      throw std::invalid_argument(nameOf(damping_) + " needs a constant damping (joints without clearance)");
  }

 private:
  static std::string nameOf(VerletDamping d) {
    return d == VerletDamping::Explicit ? "fixed-verlet"
           : d == VerletDamping::Joints ? "fixed-verlet-implicit-joint-damping"
                                        : "fixed-verlet-implicit-damping";
  }

  // One step of length h ending at the grid time tNext (formed from the index, not accumulated):
  //   v_1/2 = v + h/2 a(t, x, v),   x+ = x + h v_1/2,   v+ = v_1/2 + h/2 a(t + h, x+, v_1/2);
  //   other components (no velocity state): y+ = y + h/2 (f + f+)
  // (with the damping implicit each kick's h/2 is h/2 / (1 + h/2 r) per component, r the damping
  // rates: constant for the joints' variant, whose accelerations are swept off the diagonal once
  // after every evaluation, the evaluation's own for All)
  void step(double h, double tNext) override {
    if (pool_) return stepOnThreads(h, tNext);
    double* y = y_.data();
    const double hh = 0.5 * h;
    const double* f = f_.data();
    const double* fNew = fNew_.data();
    if (damping_ == VerletDamping::Explicit && velocitiesArePartners_) {  // (the same, in one pass)
      positions_.forEachRun([&](int i, int v, int n) { kickAndDrift(y + i, y + v, f + v, hh, h, n); });
    } else if (velocitiesArePartners_) {
      const double* factor = kick_.data();
      positions_.forEachRun([&](int i, int v, int n) { kickAndDriftBy(y + i, y + v, f + v, factor + v, h, n); });
    } else {
      kick(y, f, hh);
      positions_.forEachRun([&](int i, int v, int n) { addScaled(y + i, y + v, h, n); });  // drift
    }
    // prescribed angles and accumulators: predictor with the old derivative, corrected below
    others_.forEachRun([&](int i, int, int n) { addScaled(y + i, f + i, h, n); });
    check(tNext, sys_.rhs(tNext, y, fNew_.data()), "right-hand side failed: ");
    if (damping_ == VerletDamping::All) sys_.dampedKicks(hh, false, kick_.data());
    if (damping_ == VerletDamping::Joints) sys_.dampOffDiagonal(hh, fNew_.data());
    kick(y, fNew, hh);
    others_.forEach([&](int i, int) { y[i] += hh * (fNew[i] - f[i]); });  // trapezoidal
    finishStep(h, tNext);
  }

  // The same step where the system evaluates on several threads: its kicks and drifts on the
  // threads that own the components (the same operations on each, so the same bits), the others
  // (no velocity state) on the calling thread.
  void stepOnThreads(double h, double tNext) {
    double* y = y_.data();
    const double hh = 0.5 * h;
    const double *f = f_.data(), *fNew = fNew_.data(), *factor = kick_.data();
    auto kickAndDrifts = [&](int t) {
      for (const Run& r : pairRuns_[static_cast<std::size_t>(t)])
        if (damping_ == VerletDamping::Explicit) kickAndDrift(y + r.i, y + r.v, f + r.v, hh, h, r.n);
        else kickAndDriftBy(y + r.i, y + r.v, f + r.v, factor + r.v, h, r.n);
      if (t == 0) others_.forEachRun([&](int i, int, int n) { addScaled(y + i, f + i, h, n); });
    };
    pool_->run(kickAndDrifts);
    check(tNext, sys_.rhs(tNext, y, fNew_.data()), "right-hand side failed: ");
    if (damping_ == VerletDamping::Joints) sys_.dampOffDiagonal(hh, fNew_.data());
    auto kicks = [&](int t) {
      for (const Run& r : velocityRuns_[static_cast<std::size_t>(t)])
        if (damping_ == VerletDamping::Explicit) addScaled(y + r.i, fNew + r.i, hh, r.n);
        else addScaledBy(y + r.i, fNew + r.i, factor + r.i, r.n);
      if (t == 0) others_.forEach([&](int i, int) { y[i] += hh * (fNew[i] - f[i]); });  // trapezoidal
    };
    pool_->run(kicks);
    finishStep(h, tNext);
  }

  // Where the system evaluates on several threads (and its velocities are its positions' partners,
  // All's damping rates aside): each thread's runs of positions (with their velocities) and of
  // velocities, split where the owner changes.
  void shareRuns() {
    StagePool* pool = sys_.stagePool();
    pool_ = pool && pool->size() > 1 && velocitiesArePartners_ && damping_ != VerletDamping::All ? pool : nullptr;
    if (!pool_) return;
    pairRuns_.assign(static_cast<std::size_t>(pool_->size()), {});
    velocityRuns_.assign(pairRuns_.size(), {});
    auto split = [&](std::vector<std::vector<Run>>& into, int i, int v, int n) {
      for (int c = 0; c < n;) {
        const int owner = sys_.ownerOf(i + c);
        int e = c + 1;
        while (e < n && sys_.ownerOf(i + e) == owner) ++e;
        into[static_cast<std::size_t>(owner)].push_back(Run{i + c, v + c, e - c});
        c = e;
      }
    };
    positions_.forEachRun([&](int i, int v, int n) { split(pairRuns_, i, v, n); });
    velocities_.forEachRun([&](int i, int, int n) { split(velocityRuns_, i, i, n); });
  }

  void kick(double* y, const double* a, double hh) const {
    if (damping_ != VerletDamping::Explicit)
      velocities_.forEachRun([&](int i, int, int n) { addScaledBy(y + i, a + i, kick_.data() + i, n); });
    else
      velocities_.forEachRun([&](int i, int, int n) { addScaled(y + i, a + i, hh, n); });
  }

  VerletDamping damping_;
  std::vector<double> kick_;  // the kicks' factors (All: at the last evaluation's damping rates)
  struct Run {
    int i, v, n;  // components i .. i + n - 1, their velocities from v
  };
  StagePool* pool_ = nullptr;  // (shareRuns: the system's, where its evaluations run on threads)
  std::vector<std::vector<Run>> pairRuns_, velocityRuns_;  // (threads)
};

}  // namespace

std::unique_ptr<Integrator> makeFixedVerlet(OdeSystem& sys, const FixedStepOptions& s, VerletDamping damping) {
  return std::make_unique<FixedVerlet>(sys, s, damping);
}

}  // namespace chaindrive
