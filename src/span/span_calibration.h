// The one quantity the span model takes from the link model: the seating slack, the chain the
// link model holds beyond the nominal path of pitch circles and guide pin circles. Under load
// its rollers settle into the tooth gaps and its links onto the guides, and its tension guide
// stands further out than the nominal path says (default drive: 1.2 deg with infinitely stiff
// joints); the tension guide's lever on the chain changes with its angle. The slack is measured
// at rest without loads: the link model's static preload gives the tension guide's angle, and
// the slack in the span of the tension guide is set so that the span model's static equilibrium
// puts the guide at the same angle (secant iterations).
#pragma once

#include "span/span_model.h"

namespace chaindrive::span {

/// Sets the slack of the tension guide's span; a note says what was measured. Drives
/// without a tensioned pivoting guide keep no slack (a note says so).
void measureSeatingSlack(SpanModel& sm);

}  // namespace chaindrive::span
