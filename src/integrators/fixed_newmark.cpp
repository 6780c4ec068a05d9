// Fixed-step implicit-explicit Newmark (Hughes and Liu's predictor-corrector form, one
// linearization per step): the system's stiff part (OdeSystem::solveStiff) is integrated
// implicitly with Newmark's average-acceleration family, the rest explicitly at the predictor.
//   predictor   x~ = x + h v + h^2 (1/2 - beta) a,   v~ = v + h (1 - gamma) a
//   forces      a~ = A(t + h, x~, v~)                              (one evaluation per step)
//   corrector   (I - gamma h dA/dv - beta h^2 dA/dx) a+ = a~        (the stiff part's solve)
//               x+ = x~ + beta h^2 a+,   v+ = v~ + gamma h a+
// For the linearized stiff part the scheme is unconditionally stable: gamma = 1/2 (beta 1/4)
// keeps every mode's amplitude, gamma > 1/2 with beta = (gamma + 1/2)^2 / 4 damps modes the
// step cannot resolve (first order in that damping). The explicit part is stable while
// omega h < 2, as with Verlet, which this is for beta = 0, gamma = 1/2 and no stiff part.
// Components without a velocity state use the trapezoidal rule. Constant cost per step and no
// allocation after construction.
#include <string>

#include "integrators/fixed_step.h"
#include "integrators/integrators.h"

namespace chaindrive {

namespace {

class FixedNewmark : public FixedStepScheme {
 public:
  FixedNewmark(OdeSystem& sys, const FixedStepOptions& s, const NewmarkOptions& o)
      : FixedStepScheme(sys, s, "fixed-newmark"), gamma_(o.gamma), beta_(0.25 * (o.gamma + 0.5) * (o.gamma + 0.5)) {
    if (!sys.hasStiffSolve())
      throw std::invalid_argument("fixed-newmark needs a system with a stiff part: the link fidelity with compliant contacts");
    if (!(o.gamma >= 0.5 && o.gamma <= 1.0))
      throw std::invalid_argument("fixed-newmark: gamma must be in [0.5, 1], got " + std::to_string(o.gamma));
  }
  std::string name() const override { return "fixed-newmark"; }

 private:
  void step(double h, double tNext) override {
    double* y = y_.data();
    double* a = fNew_.data();
    const double* f = f_.data();
    const double h2 = h * h;
    positions_.forEach([&](int i, int v) { y[i] += h * y[v] + (0.5 - beta_) * h2 * f[v]; });
    velocities_.forEach([&](int i, int) { y[i] += (1.0 - gamma_) * h * f[i]; });
    others_.forEach([&](int i, int) { y[i] += h * f[i]; });
    check(tNext, sys_.rhs(tNext, y, a), "right-hand side failed: ");
    check(tNext, sys_.solveStiff(gamma_ * h, beta_ * h2, a), "stiff solve failed: ");
    positions_.forEach([&](int i, int v) { y[i] += beta_ * h2 * a[v]; });
    velocities_.forEach([&](int i, int) { y[i] += gamma_ * h * a[i]; });
    others_.forEach([&](int i, int) { y[i] += 0.5 * h * (a[i] - f[i]); });
    ++stats_.jacobianEvaluations;
    finishStep(h, tNext);
  }

  double gamma_, beta_;
};

}  // namespace

std::unique_ptr<Integrator> makeFixedNewmark(OdeSystem& sys, const FixedStepOptions& fixed,
                                             const NewmarkOptions& newmark) {
  return std::make_unique<FixedNewmark>(sys, fixed, newmark);
}

}  // namespace chaindrive
