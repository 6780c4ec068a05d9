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

/// Adds the generalized forces of contact c (forces c.fN, c.fT) to the link and rotor entries.
void addContactGen(const Model& m, const ContactPoint& c, double* gen);

/// Evaluates the law for d.contacts[0..nContacts) and accumulates generalized forces; returns
/// the dissipated power.
double evaluateCompliantContacts(const Model& m, Data& d);

}  // namespace chaindrive
