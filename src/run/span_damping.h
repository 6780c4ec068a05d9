// The span model's damping fitted to the link model's dynamics (the drive's spanModel.damping
// "identified"). The link model's camshafts' mode in phase decays 2 to 6 times faster than the
// span model's (docs/modes.md), though the link model's damping on the guide's static motion is
// the smaller (span/seat_calibration.h): its chain loses the energy where its rollers seat and
// spreads it into its chaotic motion, which the spans' dampers (the joints' in series) do not
// hold. So the spans' dampers are scaled until the span model's mode decays as the link model's,
// both measured the same way at a reference point: a run-in at the reference speed and loads,
// then per twin pair (crankshaft speeds 1e-9 apart) a plain run and one with a load pulse on
// every loaded sprocket in phase, the pairs' differences averaged (the chaos averages out), one
// mode fitted to the sprockets' angles (run/mode_fit.h; the channels and window of the harness's
// modes study). The span model is not chaotic: one pair
// measures it. The scale is found by the secant method on its logarithm; the result is cached in
// the cache folder of the spans' laws, keyed the same (span/calibration_cache.h).
#pragma once

#include <memory>
#include <string>

#include "assembly/model.h"
#include "run/mode_fit.h"
#include "span/span_model.h"

namespace chaindrive {

/// The reference point: crankshaft speed [rad/s] and the load on every loaded sprocket [N m]
/// (span/seat_calibration.h), the pulse [N m] and its length [s], the run-in [crankshaft
/// revolutions], the wait from the run-in to the pulse [s], the fit's window after the pulse [s].
constexpr double kDampingPulse = 20.0, kDampingPulseLength = 3e-4;
constexpr double kDampingRunInRevolutions = 40.0, kDampingWait = 0.05;
constexpr double kDampingFitFrom = 0.002, kDampingFitTo = 0.02;
constexpr int kDampingLinkPairs = 12;

struct MeasuredMode {
  FittedMode mode;
  double coherent = 1.0;  // the pairs' mean's share of their response energy (1: no chaos)
};

struct SpanDampingCalibration {
  bool identified = false;  // false: the scale stays 1 (`note` says why)
  double scale = 1.0;       // the spans' dampers over the joints' in series
  MeasuredMode link, spanBefore, span;  // the link model's mode, the span model's at scale 1 and at `scale`
  int iterations = 0;       // span runs of the secant method
  double cpuSeconds = 0.0;
  std::string note;
};

/// Measures the link model's mode and fits the scale of sm (with its laws and seats).
SpanDampingCalibration identifySpanDamping(const std::shared_ptr<const Model>& m, const span::SpanModel& sm);

/// The cached calibration of sm's drive, else identified and cached; sets sm's damping scale and
/// notes what it did in sm.notes.
SpanDampingCalibration calibrateSpanDamping(const std::shared_ptr<const Model>& m, span::SpanModel& sm);

/// One line describing a calibration.
std::string describeSpanDamping(const SpanDampingCalibration& c);

}  // namespace chaindrive
