// What limits a fixed step, from the schemes' side: velocity Verlet's stable step for one
// oscillating mode whose damping it takes explicitly, and the step that divides an interval (the
// communication step) into whole steps below a limit. Nothing here knows what the mode is.
#pragma once

#include <cmath>

namespace chaindrive {

/// Velocity Verlet's largest stable step [s] for the mode x'' = -omega^2 x - rate x' with the
/// damping `rate` [1/s] taken explicitly: 2 / omega without damping, 2 (sqrt(1 + zeta^2) - zeta)
/// / omega with zeta = rate / (2 omega) (explicit damping shrinks it; a damping the scheme takes
/// implicitly is not counted in `rate`). omega > 0 [rad/s], rate >= 0.
inline double verletStableStep(double omega, double rate) {
  const double zeta = rate / (2.0 * omega);
  return 2.0 * (std::sqrt(1.0 + zeta * zeta) - zeta) / omega;
}

/// The number n of steps interval / n of the shortest division of `interval` whose step is not
/// above `limit` (n >= 1; limit > 0): the smallest n with interval / n <= limit, a limit that
/// equals a division interval / n within a relative 1e-12 taken as that division (so that a limit
/// computed as margin x estimate lands on the step it was calibrated to, whatever its rounding).
/// A limit so small that n would not fit (or not a number) gives kNoDivision: no step to take.
constexpr long long kNoDivision = 1LL << 62;
inline long long divisionsWithin(double interval, double limit) {
  const double n = std::ceil(interval / limit * (1.0 - 1e-12));
  if (!(n < static_cast<double>(kNoDivision))) return kNoDivision;
  return n < 1.0 ? 1 : static_cast<long long>(n);
}

}  // namespace chaindrive
