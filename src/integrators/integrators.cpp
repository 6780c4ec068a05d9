// The integrators by name: each built from its own option groups of IntegratorSettings.
#include <stdexcept>

#include "integrators/integrators.h"

namespace chaindrive {

std::vector<std::string> integratorNames() {
  return {"cvode-bdf-klu",  "cvode-bdf-band",
          "arkode-erk",     "arkode-erk-fixed",
          "fixed-verlet",   "fixed-verlet-implicit-damping",
          "fixed-verlet-implicit-joint-damping",
          "fixed-newmark"};
}

std::unique_ptr<Integrator> makeIntegrator(OdeSystem& sys, const IntegratorSettings& s) {
  if (s.method == "cvode-bdf-klu") return makeCvodeBdf(sys, s.adaptive, s.bdf, true);
  if (s.method == "cvode-bdf-band") return makeCvodeBdf(sys, s.adaptive, s.bdf, false);
  if (s.method == "arkode-erk") return makeArkodeErk(sys, s.adaptive, s.erk, nullptr);
  if (s.method == "arkode-erk-fixed") return makeArkodeErk(sys, s.adaptive, s.erk, &s.fixed);
  if (s.method == "fixed-verlet") return makeFixedVerlet(sys, s.fixed, VerletDamping::Explicit);
  if (s.method == "fixed-verlet-implicit-damping") return makeFixedVerlet(sys, s.fixed, VerletDamping::All);
  if (s.method == "fixed-verlet-implicit-joint-damping")
    return makeFixedVerlet(sys, s.fixed, VerletDamping::Joints);
  if (s.method == "fixed-newmark") return makeFixedNewmark(sys, s.fixed, s.newmark);
  std::string known;
  for (const auto& n : integratorNames()) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("integrator '" + s.method + "' is unknown; known: " + known);
}

}  // namespace chaindrive
