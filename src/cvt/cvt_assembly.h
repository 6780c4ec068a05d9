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
  double freeRadius[2] = {0.0, 0.0};     // [m] where the sheaves would just touch an unloaded pin
  double wrapAngle[2] = {0.0, 0.0};      // [rad]
  double pretension = 0.0;               // [N] in both strands at the assembled pose
  double chord = 0.0;                    // [m] a link's pin distance stretched by the pre-tension
  double clampingForce[2] = {0.0, 0.0};  // [N] of the pins on each pulley at the assembled pose
};

/// Points of the sheaves' table over a CVT's ratio range (Model::ratioTable): the radii between
/// them are interpolated linearly; on the default CVT (0.5-2) within 0.24 um of the layout at
/// that ratio (64 points: 4 um, a tenth of the pins' compression).
constexpr int kRatioPoints = 256;

/// The rotors of a CVT model: the driving pulley (prescribed speed) and the driven one (free).
constexpr int kDrivingPulley = 0, kDrivenPulley = 1;

/// Builds the model at the description's ratio, with the sheaves' table over its ratio range;
/// throws DescriptionError when the chain cannot be laid around the pulleys (naming the fields).
Model assembleCvt(const CvtDescription& d, CvtLayout* layout = nullptr);

/// The nominal state at a driving-pulley speed [rad/s, running direction]: the chain moving with
/// the pulleys without slip, the driven pulley at the geometric ratio.
std::vector<double> cvtNominalState(const Model& m, double drivingSpeed);

}  // namespace chaindrive
