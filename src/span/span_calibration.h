// What the span model takes from the link model: each span's engagement law, the chain's tension
// over the span's stretch where the link model's rollers seat in the tooth gaps and its links
// settle on the guides (span_model.h, EngagementLaw). It is identified from the link model's
// statics under several loads: per static pose, the link model's mean joint tension over each
// span's free parts and guides, and the span's stretch that the link model's rotor angles give
// through the span model's own kinematics. A piecewise-linear least-squares fit of the stretch
// over the tension per span gives the law's nodes. Its cost (the link model's static solves over
// a design of loads and supply pressures, calibrationLoads) is paid once per drive description
// and code: the result is kept in a cache file keyed by both (span/calibration_cache.h).
#pragma once

#include <string>
#include <vector>

#include "span/seat_calibration.h"
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
  std::vector<SeatIdentification> seats;  // (guide tables) identifyGuideSeats, with the laws
  double cpuSeconds = 0.0;          // of the identification
};

/// The load torques of the calibration's static poses [N m], one row per pose, a column per
/// loaded sprocket (free with a load torque, in rotor order; an idler carries none and takes no
/// levels), each pose at every supply pressure of a hydraulic chamber (calibrationSupplies). The
/// full grid (fullLoadGrid) up to one loaded sprocket, and up to two while its poses times the
/// chain's links cubed stay within the default drive's grid (180 poses, 120 links: its 36 rows);
/// the linear design (linearLoadDesign) otherwise.
std::vector<std::vector<double>> calibrationLoads(int loadedSprockets, int supplyPressures, int links);

/// Every combination of the six levels (-5 to 40 N m) on n sprockets (6^n rows), the first
/// sprocket's level changing fastest.
std::vector<std::vector<double>> fullLoadGrid(int loadedSprockets);

/// A design that grows linearly, 6 + 5 n rows: the six levels on every sprocket together (the
/// diagonal: every span's tension over its whole range), then each sprocket's other five levels
/// with the rest at the reference 10 N m (one at a time: the spans' tensions apart from one
/// another).
std::vector<std::vector<double>> linearLoadDesign(int loadedSprockets);

/// The rotors of the loaded sprockets, the columns of calibrationLoads.
std::vector<int> loadedSprockets(const Model& m);

/// The supply pressures of the poses [Pa]: 1 to 35 bar with a hydraulic chamber, else the drive's.
std::vector<double> calibrationSupplies(const Model& m);

/// Identifies the laws of the span model's spans (assembled without them) from its link model's
/// statics at the poses of calibrationLoads. Throws std::runtime_error when fewer poses than the
/// fit needs converge.
SpanCalibration identifySpanLaws(const SpanModel& sm);

/// The same at the poses of `loads` (rows as calibrationLoads gives them).
SpanCalibration identifySpanLaws(const SpanModel& sm, const std::vector<std::vector<double>>& loads);

/// Puts the laws and the seats into the span model.
void applyCalibration(SpanModel& sm, const SpanCalibration& c);

/// Lines describing a calibration (the laws' nodes, residuals, lever ratios, cost).
std::vector<std::string> describeCalibration(const SpanModel& sm, const SpanCalibration& c);

}  // namespace chaindrive::span
