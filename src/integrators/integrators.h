// Constructors of the concrete integrators (selected by name through makeIntegrator).
#pragma once

#include <memory>

#include "integrators/ode_system.h"

namespace chaindrive {

std::unique_ptr<Integrator> makeCvodeBdf(OdeSystem& sys, const IntegratorSettings& s, bool klu);
std::unique_ptr<Integrator> makeArkodeErk(OdeSystem& sys, const IntegratorSettings& s, bool fixedStep);
std::unique_ptr<Integrator> makeFixedVerlet(OdeSystem& sys, const IntegratorSettings& s);

}  // namespace chaindrive
