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
/// fixed-verlet, with the damping explicit or implicit (fixed_verlet.cpp): the joints' by one
/// Jacobi sweep (fixed-verlet-implicit-joint-damping), or the diagonal of the joints' and contacts'
/// (fixed-verlet-implicit-damping).
enum class VerletDamping { Explicit, Joints, All };
std::unique_ptr<Integrator> makeFixedVerlet(OdeSystem& sys, const FixedStepOptions& fixed, VerletDamping damping);
std::unique_ptr<Integrator> makeFixedNewmark(OdeSystem& sys, const FixedStepOptions& fixed,
                                             const NewmarkOptions& newmark);

}  // namespace chaindrive
