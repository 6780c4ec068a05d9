// Constructors of the concrete integrators (selected by name through makeIntegrator).
#pragma once

#include <memory>

#include "integrators/ode_system.h"

namespace chaindrive {

std::unique_ptr<Integrator> makeCvodeBdf(OdeSystem& sys, const AdaptiveOptions& adaptive, const BdfOptions& bdf,
                                         bool klu);
/// `fixed` null: adaptive; otherwise at that fixed step (with the adaptive options' tolerances,
/// step limits and step count).
std::unique_ptr<Integrator> makeArkodeErk(OdeSystem& sys, const AdaptiveOptions& adaptive, const ErkOptions& erk,
                                          const FixedStepOptions* fixed);
/// implicitDamping: fixed-verlet-implicit-damping (fixed_verlet.cpp).
std::unique_ptr<Integrator> makeFixedVerlet(OdeSystem& sys, const FixedStepOptions& fixed, bool implicitDamping);
std::unique_ptr<Integrator> makeFixedNewmark(OdeSystem& sys, const FixedStepOptions& fixed,
                                             const NewmarkOptions& newmark);

}  // namespace chaindrive
