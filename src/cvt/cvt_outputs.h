// What a CVT's users read (paper section 4.1): the pulleys' speeds and slip, the strand forces,
// the clamping forces, the torques and the power loss, and for one pin (the monitored link's)
// the forces of the paper's Figure 9: the sheaves' normal force, the radial and circumferential
// friction and the link's tensile force. From the shared outputs and the contacts behind them.
#pragma once

#include "dynamics/data.h"
#include "assembly/model.h"
#include "outputs/outputs.h"

namespace chaindrive {

struct CvtOutputs {
  double drivingSpeed = 0.0, drivenSpeed = 0.0;  // [rad/s] in the running direction
  double slip = 0.0;            // 1 - (driven speed / driving speed) / (its geometric value r1 / r2 at the ratio)
  double tightStrandForce = 0.0, slackStrandForce = 0.0;  // [N] at the strands' middles
  double clampingForce[2] = {0.0, 0.0};  // [N] the pins' axial forces on each pulley
  int pinsInContact[2] = {0, 0};
  double drivingTorque = 0.0;   // [N m] the chain's torque on the driving pulley, against its running direction
  double drivenTorque = 0.0;    // [N m] the chain's torque on the driven pulley, in its running direction
  double powerLoss = 0.0;       // [W] dissipated in the chain (joints, pins, friction)
  // the monitored link's pin (its rear pin), paper Figure 9
  double pinNormalForce = 0.0;  // [N] the sheaves' radial (wedge) force
  double pinRadialFriction = 0.0, pinCircumferentialFriction = 0.0;  // [N] on the pin, outwards and forwards
  double pinAxialForce = 0.0;   // [N]
  double linkTension = 0.0;     // [N]
  int pinPulley = -1;           // the pulley the pin touches (-1: none, on a strand)
};

/// From outputs `out` computed in the work area d (Simulation::outputs, outputData).
CvtOutputs cvtOutputs(const Model& m, const Data& d, const Outputs& out, int monitoredLink);

/// Places the models' strand probes (Model::tightSpan, slackSpan) at the strands' middles: the
/// tight strand runs onto the driving pulley (it pulls the chain in), the slack one leaves it.
void placeStrandProbes(Model& m);

}  // namespace chaindrive
