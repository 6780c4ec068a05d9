// The integrators by method: each built from its own option groups of IntegratorSettings.
#include <stdexcept>

#include "integrators/integrators.h"

namespace chaindrive {

std::unique_ptr<Integrator> makeIntegrator(OdeSystem& sys, const IntegratorSettings& s) {
  switch (s.method) {
    case IntegratorMethod::CvodeBdfKlu: return makeCvodeBdf(sys, s.adaptive, s.bdf, true);
    case IntegratorMethod::CvodeBdfBand: return makeCvodeBdf(sys, s.adaptive, s.bdf, false);
    case IntegratorMethod::ArkodeErk: return makeArkodeErk(sys, s.adaptive, s.erk, nullptr);
    case IntegratorMethod::ArkodeErkFixed: return makeArkodeErk(sys, s.adaptive, s.erk, &s.fixed);
    case IntegratorMethod::FixedVerlet: return makeFixedVerlet(sys, s.fixed, VerletDamping::Explicit);
    case IntegratorMethod::FixedVerletImplicitDamping: return makeFixedVerlet(sys, s.fixed, VerletDamping::All);
    case IntegratorMethod::FixedVerletImplicitJointDamping:
      return makeFixedVerlet(sys, s.fixed, VerletDamping::Joints);
    case IntegratorMethod::FixedNewmark: return makeFixedNewmark(sys, s.fixed, s.newmark);
  }
  throw std::invalid_argument("integrator method " + std::to_string(static_cast<int>(s.method)) + " is unknown");
}

}  // namespace chaindrive
