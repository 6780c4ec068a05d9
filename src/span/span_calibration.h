// What the span model takes from the link model: each span's engagement law, the chain's tension
// over the span's stretch where the link model's rollers seat in the tooth gaps and its links
// settle on the guides (span_model.h, EngagementLaw). It is identified from the link model's
// statics under several loads: per static pose, the link model's mean joint tension over each
// span's free parts and guides, and the span's stretch that the link model's rotor angles give
// through the span model's own kinematics. A piecewise-linear least-squares fit of the stretch
// over the tension per span gives the law's nodes. Its cost (the link model's static solves over
// a grid of loads and supply pressures) is paid once per drive description and code: the result
// is kept in a cache file keyed by both (span/calibration_cache.h).
#pragma once

#include <string>
#include <vector>

#include "span/span_model.h"

namespace chaindrive::span {

/// The identified laws and what the identification measured.
struct SpanCalibration {
  std::vector<EngagementLaw> laws;  // (spans)
  int poses = 0;                    // static poses of the link model used
  int posesRejected = 0;            // not converged, or a span nearly slack (below kMinTension)
  std::vector<double> residualRms, residualMax;  // (spans) [m] stretch off the fitted law
  // per pivoting guide: the link model's chain torque on it over the span model's at the same
  // tensions and pose (1: the span model's guide geometry holds), smallest and largest
  std::vector<double> leverRatioMin, leverRatioMax;
  double cpuSeconds = 0.0;          // of the identification
};

/// Identifies the laws of the span model's spans (assembled without them) from its link model.
/// Throws std::runtime_error when fewer poses than the fit needs converge.
SpanCalibration identifySpanLaws(const SpanModel& sm);

/// Puts the laws into the span model.
void applyCalibration(SpanModel& sm, const SpanCalibration& c);

/// Lines describing a calibration (the laws' nodes, residuals, lever ratios, cost).
std::vector<std::string> describeCalibration(const SpanModel& sm, const SpanCalibration& c);

}  // namespace chaindrive::span
