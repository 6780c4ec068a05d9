// Output quantities at one instant, in the signs users read: sprocket angles and speeds in the
// running direction (angles from the start), guide angles from the drawn pose, positive in the
// direction the tensioner pushes (towards the chain).
#pragma once

#include <vector>

#include "dynamics/data.h"
#include "dynamics/dynamics.h"
#include "assembly/model.h"

namespace chaindrive {

struct Outputs {
  double time = 0.0;
  std::vector<double> rotorAngle;   // (rotors) [rad]
  std::vector<double> rotorRate;    // (rotors) [rad/s]
  std::vector<double> rotorTorque;  // (rotors) [N m] chain (contact) torque on the rotor, output sign
  double crankTorque = 0.0;         // [N m] chain torque on the driven sprocket, + in running direction
  // the same averaged since the step means' accumulators were last zeroed (model.h: ImpulseStates;
  // at that instant itself the torque then); NaN with rigid contacts, which do not accumulate them
  std::vector<double> rotorTorqueStepMean;  // (rotors) [N m] output sign
  double crankTorqueStepMean = 0.0;         // [N m]
  double tensionerForce = 0.0, tensionerStroke = 0.0, tensionerRate = 0.0;
  double chamberPressure = 0.0;     // [Pa] gauge, a hydraulic tensioner's (0 for the spring-damper law)
  HydraulicFlows tensionerFlows;    // [m3/s] its check valve's, leak's and relief valve's
  double tightSpanForce = 0.0, slackSpanForce = 0.0;  // [N]
  std::vector<double> spanForce;    // (route elements) [N] chain force in the span leaving each
  double linkTension = 0.0;         // [N] tensile force of the monitored link
  double linkNormalForce = 0.0;     // [N] sum of contact normal forces on the monitored link
  double linkSprocketForce = 0.0, linkGuideForce = 0.0;
  Vec2 linkPosition;                // [m] centre of the monitored link
  EnergyTerms energy;
  int contacts = 0;                 // closed contacts
  double maxJointDeformation = 0.0; // [m]
};

/// Constraint forces of the rigid-contact methods, for the outputs.
struct RigidForces {
  const std::vector<ContactPoint>* contacts = nullptr;  // contact points with fN, fT set
  const std::vector<double>* joints = nullptr;          // ideal joints: (fx, fy) per joint on link j's front pin
};

/// Evaluates the dynamics at (t, y) and fills the outputs. `monitoredLink` overrides the model's.
/// With `rigid`, the contact (and ideal-joint) forces are those of the complementarity method.
void computeOutputs(const Model& m, Data& d, const InputSignal& in, double t, const double* y, int monitoredLink,
                    Outputs& out, const RigidForces* rigid = nullptr);

/// The rotor outputs from the rotors' angles and rates (math sense) and, in out.rotorTorque, the
/// chain's torques on them (math sense): all turned into the output sense (outputs.h header), the
/// crankshaft torque and the step means from the state y's accumulators (`impulse`; y nullptr:
/// none, NaN). Shared by the link and span models.
void finishRotorOutputs(const Model& m, const std::vector<double>& angle, const std::vector<double>& rate,
                        const ImpulseStates& impulse, const double* y, Outputs& out);

/// Force at a span probe, interpolated between the two joints that bracket it.
double spanForce(const Model& m, const Data& d, const SpanProbe& probe);

}  // namespace chaindrive
