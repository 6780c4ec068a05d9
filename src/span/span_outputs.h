// The outputs of the span model, in the quantities and signs of the link model (outputs/outputs.h).
// What it does not compute gets a defined value: the monitored link's tensile force is the
// tension where the link is on the path (moved with the chain from its start position), its
// position is on the nominal path; its contact forces, the closed contacts are 0; the largest
// joint deformation is the largest span tension over the joint stiffness.
#pragma once

#include "outputs/outputs.h"
#include "span/span_dynamics.h"

namespace chaindrive::span {

void computeSpanOutputs(const SpanModel& m, SpanData& d, const InputSignal& in, double t, const double* y,
                        int monitoredLink, Outputs& out);

/// Tension at path position s [m] of the assembled path (after an evaluation).
double tensionAt(const SpanModel& m, const SpanData& d, double s);

}  // namespace chaindrive::span
