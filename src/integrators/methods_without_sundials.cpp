// The SUNDIALS methods in a build without SUNDIALS (the FMUs' source build: their sources/ carry
// no SUNDIALS, harness/package): refused by name, with the reason and what remains, when the
// model starts (the FMU's initialization fails with this message).
#include <stdexcept>
#include <string>

#include "integrators/integrators.h"

namespace chaindrive {

namespace {

[[noreturn]] void refuse(const char* method) {
  throw std::invalid_argument(std::string("solver.method '") + method +
                              "' needs SUNDIALS, which this build does not have (a build from the FMU's sources/, "
                              "which carry no SUNDIALS); the fixed-step methods (fixed-verlet, "
                              "fixed-verlet-implicit-joint-damping, fixed-newmark, ...) and time-stepping do not");
}

}  // namespace

std::unique_ptr<Integrator> makeCvodeBdf(OdeSystem&, const AdaptiveOptions&, const BdfOptions&, bool klu) {
  refuse(klu ? "cvode-bdf-klu" : "cvode-bdf-band");
}

std::unique_ptr<Integrator> makeArkodeErk(OdeSystem&, const AdaptiveOptions&, const ErkOptions&,
                                          const FixedStepOptions* fixed) {
  refuse(fixed ? "arkode-erk-fixed" : "arkode-erk");
}

}  // namespace chaindrive
