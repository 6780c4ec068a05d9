// The forward dynamics: state -> state derivative, calling the stages in order
// (kinematics, joints, contacts, body forces, accelerations). This is the right-hand side that
// every smooth integrator sees, and the table of contents of the model.
#pragma once

#include "dynamics/data.h"
#include "assembly/model.h"

namespace chaindrive {

/// ydot = f(t, y) with compliant contacts. Leaves forces, contacts and outputs of this
/// evaluation in d. Never allocates.
void forwardCompliant(const Model& m, Data& d, const InputSignal& in, double t, const double* y, double* ydot);

/// Generalized forces only (no derivative), used by the static preload and the Jacobian.
/// Evaluates kinematics, joints, contacts and body forces at (t, y) into d.gen.
void generalizedForces(const Model& m, Data& d, const InputSignal& in, double t, const double* y);

struct EnergyTerms {
  double kinetic = 0.0, elastic = 0.0, gravity = 0.0, dissipated = 0.0, inputWork = 0.0;
  double balance() const { return kinetic + elastic + gravity + dissipated - inputWork; }
};
/// Energy terms at state y (after a forward evaluation at the same state).
EnergyTerms energyTerms(const Model& m, const Data& d, const double* y);

/// Largest joint deformation [m] and a finite-state check; used to detect blow-up.
struct StateHealth {
  bool finite = true;
  double maxJointDeformation = 0.0;
  int worstJoint = -1;
};
StateHealth checkState(const Model& m, const Data& d, const double* y);

}  // namespace chaindrive
