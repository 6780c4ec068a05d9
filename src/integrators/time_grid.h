// The global time grid of a run: t_k = start + k * unit, with the step count k held as an
// integer. Fixed-step methods take one step per grid point (unit = their step); adaptive methods
// stop only at requested times (communication points, output times) snapped to a grid of a fixed
// time quantum. Because a requested time is turned into an integer k before anything is
// integrated, the states a run reaches do not depend on how a caller forms its times: k*H,
// t += H, (k+1)H - kH and integer nanoseconds all give the same k, and so the same bits.
//
// The snapping rule: a requested time within kSnapFraction of a grid unit from a grid point IS
// that grid point (25 ns at a 2.5 us step, 10 ns on the 1 us quantum). This absorbs the
// rounding of every known way of forming times: k*H is exact to an ulp (1.4e-14 s at t = 100 s),
// t += H accumulates 2.2e-9 s over 1e6 steps of 100 us, a step of 1/60 s passed as
// 0.016666666666666677 is 1e-17 s off. A requested time farther from the grid is integrated to the
// grid point before it; the remainder is not lost but carried: the next request is again mapped
// from its own time, so the state never lags by a step or more and never runs ahead.
#pragma once

#include <cmath>

namespace chaindrive {

/// The grid unit of adaptive methods [s]: they stop at requested times rounded to it.
/// Communication and output steps are whole microseconds in practice.
constexpr double kAdaptiveTimeQuantum = 1e-6;

/// A requested time within this fraction of the grid unit from a grid point is that point.
constexpr double kSnapFraction = 0.01;

struct TimeGrid {
  double start = 0.0;  // t_0 [s]
  double unit = 1.0;   // spacing of the grid points [s], > 0

  double time(long long k) const { return start + static_cast<double>(k) * unit; }

  /// Whether a grid index for t can be represented (finite and well inside a long long).
  bool reaches(double t) const { return std::isfinite(t) && std::fabs((t - start) / unit) < 4e18; }

  /// The grid point of a requested time t: the nearest one when t lies within kSnapFraction
  /// units of it, otherwise the one before t. Needs reaches(t).
  long long indexOf(double t) const {
    const double steps = (t - start) / unit;
    const double nearest = std::nearbyint(steps);
    if (std::fabs(steps - nearest) <= kSnapFraction) return static_cast<long long>(nearest);
    return static_cast<long long>(std::floor(steps));
  }

  /// Whether t is a grid point (within the snapping tolerance).
  bool contains(double t) const {
    const double steps = (t - start) / unit;
    return std::fabs(steps - std::nearbyint(steps)) <= kSnapFraction;
  }
};

}  // namespace chaindrive
