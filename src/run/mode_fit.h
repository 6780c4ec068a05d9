// One damped mode fitted to several channels of a response at once, finer than a spectrum's bin:
// the model of each channel is exp(-sigma t) (a cos(omega t) + b sin(omega t)) + c0 + c1 t + c2 t^2
// (its own amplitude, phase and slow drift: what a pulse leaves behind), one omega and sigma for
// all. For each trial (omega, sigma) the rest is linear least squares (variable projection);
// (omega, sigma) come from a grid search refined by Nelder-Mead on (frequency, log damping ratio).
// The same design as the harness's modes study (harness/study/modes.py), for the span model's
// calibration, which runs without Python.
#pragma once

#include <vector>

namespace chaindrive {

struct FittedMode {
  double frequency = 0.0;     // [Hz] the damped mode's
  double dampingRatio = 0.0;  // sigma / sqrt(sigma^2 + omega^2)
  double residual = 0.0;      // rms of the fit's residual over the rms of the signal (drift removed)
  bool atBound = false;       // the frequency ended at the search's bound (within a thousandth of a
                              // bin): not a mode within it
};

/// Fits one mode to the channels (each sampled at times t, equally spaced or not) with
/// frequencies in [fMin, fMax] Hz and damping ratios in [1e-4, 0.5].
FittedMode fitDampedMode(const std::vector<double>& t, const std::vector<std::vector<double>>& channels, double fMin,
                         double fMax);

}  // namespace chaindrive
