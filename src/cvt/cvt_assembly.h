// Assembly of a chain CVT: description -> the immutable Model the shared stages run (links and
// joints as the timing drive's, the two pulleys as rotors, the pin-sheave contacts in
// Model::pulleys), with the chain at its nominal pose: the pins on the running circles of the
// pulleys and the two strands, the links stretched by the pre-tension the clamping force sets and
// the pins compressed between the sheaves to hold it.
#pragma once

#include <vector>

#include "assembly/model.h"
#include "cvt/cvt_description.h"

namespace chaindrive {

/// What the assembly found: the running radii, the pre-tension and the clamping forces it sets.
struct CvtLayout {
  double runningRadius[2] = {0.0, 0.0};  // [m] driving, driven
  double wrapAngle[2] = {0.0, 0.0};      // [rad]
  double pretension = 0.0;               // [N] in both strands at the assembled pose
  double clampingForce[2] = {0.0, 0.0};  // [N] of the pins on each pulley at the assembled pose
};

/// The rotors of a CVT model: the driving pulley (prescribed speed) and the driven one (free).
constexpr int kDrivingPulley = 0, kDrivenPulley = 1;

/// Builds the model; throws DescriptionError when the chain cannot be laid around the pulleys
/// (naming the fields).
Model assembleCvt(const CvtDescription& d, CvtLayout* layout = nullptr);

/// The nominal state at a driving-pulley speed [rad/s, running direction]: the chain moving with
/// the pulleys without slip, the driven pulley at the geometric ratio.
std::vector<double> cvtNominalState(const Model& m, double drivingSpeed);

}  // namespace chaindrive
