// The forward dynamics: state -> state derivative, calling the stages in order. This is the
// right-hand side that every smooth integrator sees, and the table of contents of the model.
//
// Stages of one evaluation at (t, y), each reading the immutable Model m and writing the work
// area Data d (dynamics/data.h):
//   1. inputs        InputSignal::evaluate: crankshaft speed, load torques at t
//                    (the interface in dynamics/data.h; the signals of a run in run/inputs.h)
//   2. kinematics    evaluateKinematics: link poses, joint points, rotor angles
//                                                                (dynamics/contact_kinematics.h)
//   3. joints        evaluateJoints: journal-bearing forces between neighbouring links
//                                                                    (dynamics/joint_forces.h)
//   4. contacts      detectContacts with the compliant law: roller-sprocket and plate-guide
//                    gaps, normal and friction forces
//                                  (dynamics/contact_kinematics.h, dynamics/contact_compliant.h)
//   5. body forces   evaluateBodyForces: gravity, tensioner, guide pivots, load torques, the
//                    input and dissipated powers                    (dynamics/body_forces.h)
//   6. accelerations forwardCompliant: generalized forces over the diagonal mass matrix
// The rigid-contact methods (nonsmooth/) run stages 1-3 and 5 here and replace stage 4 by their
// complementarity problems. Beside the stages: the Jacobian by element differences
// (dynamics/jacobian.h) and the health checks of a state (dynamics/health.h).
#pragma once

#include "dynamics/data.h"
#include "assembly/model.h"

namespace chaindrive {

/// ydot = f(t, y) with compliant contacts. Leaves forces, contacts and outputs of this
/// evaluation in d. Never allocates.
void forwardCompliant(const Model& m, Data& d, const InputSignal& in, double t, const double* y, double* ydot);
/// Its last stage, after generalizedForces: the links' derivatives (those of range r) and the
/// others' (rotors, energy accumulators, chamber, impulses).
void linkDerivatives(const Model& m, const Data& d, const double* y, double* ydot, LinkRange r);
void otherDerivatives(const Model& m, const Data& d, const double* y, double* ydot);

/// Generalized forces only (no derivative), used by the static preload and the Jacobian.
/// Evaluates kinematics, joints, contacts and body forces at (t, y) into d.gen.
void generalizedForces(const Model& m, Data& d, const InputSignal& in, double t, const double* y);
/// Its last stage, after the joints', the contacts' and the links' weight: the chain's torques on
/// the rotors kept (rotorChainTorque), a hydraulic chamber filled, the rotors' and the tensioner's
/// own forces, the powers (given: the chain's) into d.
void rotorStage(const Model& m, Data& d, const double* y, double powerInput, double powerDissipated);

struct EnergyTerms {
  double kinetic = 0.0, elastic = 0.0, gravity = 0.0, dissipated = 0.0, inputWork = 0.0;
  double balance() const { return kinetic + elastic + gravity + dissipated - inputWork; }
};
/// Energy terms at state y (after a forward evaluation at the same state).
EnergyTerms energyTerms(const Model& m, const Data& d, const double* y);

}  // namespace chaindrive
