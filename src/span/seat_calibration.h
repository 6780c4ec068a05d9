// The span model's guide seats (span_model.h, GuideSeat), identified from the link model's
// linearisation at a reference pose: the chain's stiffness and damping against a pivoting
// guide's turn with the sprockets held.
//
// Why there: the modes of both models (docs/modes.md) put the span model's camshafts' mode above
// the link model's and show a guide mode of the link model's own that the span model lacks; the
// link model's guide rings on its chain (without the plate-guide contacts' damping its guide mode
// moves by a third). Its chain gives under the guide where the spans cannot: plates pressed into
// the face, links beside it bending off their line. With the sprockets held, the link model's
// static stiffness against the guide's turn (its stiffness matrix condensed onto the guide's
// angle) is smaller than the span model's from its spans' laws (2050 against 2637 N m/rad on the
// default drive at 10 N m per camshaft). A spring in series with the spans makes up the
// difference: 1 / k_seat = 1 / k_link - 1 / k_span (the tensioner's share, the same law in both
// models, taken out of both). The link model's damping on the same motion (the condensation's
// shape, at the nominal chain speed: joints, contacts, friction) is measured and reported beside
// the spans' dampers' (on the default drive it is the smaller: the seat takes no damper).
#pragma once

#include <string>
#include <vector>

#include "dynamics/data.h"
#include "span/span_model.h"

namespace chaindrive::span {

/// What the identification measured per pivoting guide, and the seat it gives.
struct SeatIdentification {
  GuideSeat seat;               // stiffness 0: the link model's chain is not softer (no seat); its
                                // spanStiffness: the span model's spans against the guide's turn
  double linkStiffness = 0.0;   // [N m/rad] the link model's chain against the guide's turn
  double linkDamping = 0.0;     // [N m s/rad] the link model's chain on the same motion
  double spanDamping = 0.0;     // [N m s/rad] the span model's spans
  double tensionerStiffness = 0.0;  // [N m/rad] the rest of the guide's (the same in both)
};

/// The reference pose's load torque on every loaded sprocket [N m] and crankshaft speed of the
/// damping's nominal motion [rad/s].
constexpr double kSeatReferenceLoad = 10.0;
constexpr double kSeatReferenceSpeed = 3000.0 * 2.0 * 3.14159265358979323846 / 60.0;

/// The link model's inputs at the reference pose: kSeatReferenceLoad on every loaded sprocket,
/// the drive's supply pressure, the crankshaft at rest.
InputValues seatReferenceInputs(const Model& m);

/// Identifies the seats of sm's pivoting guides (sm with its laws, without seats) at the
/// reference pose: the loads above at the drive's supply pressure. Throws std::runtime_error when
/// the link model's statics do not converge there.
std::vector<SeatIdentification> identifyGuideSeats(const SpanModel& sm);

/// One line per seat for describeCalibration.
std::string describeSeat(const SpanModel& sm, int table, const SeatIdentification& s);

}  // namespace chaindrive::span
