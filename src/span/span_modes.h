// The span model's stiffest mode and the fixed step plain Verlet holds on it: the span model's
// own step limit (docs/defaults.md#a-step-that-fits-the-drive). Its free rotors (sprockets and
// pivoting guides, with the chain lumped on them) are coupled by the spans' longitudinal springs:
// a span's stretch moves with R at the sprocket it leaves and arrives at and with its guide
// table's slope at the guide it holds (span_model.h). The largest eigenvalue of M^-1 K of that
// system, the spans at their joints' stiffness in series (an engagement law is softer where the
// rollers seat) and every sprocket at its full pitch radius (the polygon's effective radius is not
// larger), is its highest frequency; the spans' damping is proportional to their stiffness
// (the joints' damping over their stiffness), so that mode's damping rate is that ratio times
// omega^2. The tensioner and the chamber's oil are not counted (not the stiffest on the drives
// measured: the default's span model runs open loop at 6000 rpm at 250 us and blows up at 300
// and 400 us, the estimate 280 us).
#pragma once

#include <string>

#include "span/span_model.h"

namespace chaindrive::span {

struct SpanModeStep {
  double step = 0.0;        // [s] plain Verlet's stable step on the highest mode
  double omega = 0.0;       // [rad/s] the highest mode's angular frequency
  std::string stiffestSpan; // the span whose stiffness over its rotors' inertia is the largest
  double spanStiffness = 0.0;  // [N/m] that span's
};

/// The span model's explicit stable step (for a model with at least one free rotor a span moves;
/// otherwise step is infinite).
SpanModeStep spanModeStep(const SpanModel& sm);

}  // namespace chaindrive::span
