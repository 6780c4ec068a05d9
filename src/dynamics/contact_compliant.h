// Compliant contact law: a normal force only under penetration (Hunt-Crossley or linear
// spring-damper, both clamped at zero) with Coulomb friction regularised by a continuous
// function of the sliding speed (the paper's remark on the CVT model).
#pragma once

#include "dynamics/data.h"
#include "assembly/model.h"

namespace chaindrive {

struct CompliantResult {
  double power = 0.0;   // dissipated power (normal damping and friction) [W]
  double energy = 0.0;  // elastic energy stored in the contact [J]
};

/// Sets c.fN and c.fT from the contact kinematics.
CompliantResult compliantContactForce(const ContactLaw& law, double vReg, ContactPoint& c);

/// The law's slopes at contact c's state (after compliantContactForce): the normal force's by
/// penetration [N/m] and by its rate [N s/m], the friction force's by sliding speed [N s/m]
/// (zero for an open contact or a normal force clamped at zero).
struct CompliantSlopes {
  double byPenetration = 0.0, byPenetrationRate = 0.0, bySliding = 0.0;
};
CompliantSlopes compliantContactSlopes(const ContactLaw& law, double vReg, const ContactPoint& c);

/// Adds the generalized forces of contact c (forces c.fN, c.fT) to the link and rotor entries.
void addContactGen(const Model& m, const ContactPoint& c, double* gen);

/// Evaluates the law for d.contacts[0..nContacts) and accumulates generalized forces; returns
/// the dissipated power.
double evaluateCompliantContacts(const Model& m, Data& d);

}  // namespace chaindrive
