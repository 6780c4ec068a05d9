// cbrt (src/math/elementary.h): FreeBSD msun's s_cbrt.c (Sun's, optimized by Bruce D. Evans):
// a cube root to about 5 bits from the bits of x, a polynomial to 23 bits, rounded away from
// zero to 23 bits so that its square is exact, one Newton step to 53 bits (error < 0.667 ulp).
#include <cstdint>

#include "math/double_double.h"
#include "math/elementary.h"

namespace chaindrive::math {

double cbrt(double x) {
  // (1023 - 1023/3 - 0.03306235651) 2^20: dividing the high word (biased exponent and top of the
  // significand) by 3 and adding this gives cbrt within 1/32; B2 for x scaled by 2^54 first
  constexpr std::uint32_t B1 = 715094163, B2 = 696219795;
  // |1/cbrt(r) - P(r)| < 2^-23.5 for |r - 1| < 1/10
  constexpr double P0 = 1.87595182427177009643, P1 = -1.88497979543377169875, P2 = 1.621429720105354466140,
                   P3 = -0.758397934778766047437, P4 = 0.145996192886612446982;
  const std::uint64_t bits = detail::bitsOf(x);
  const std::uint64_t sign = bits & 0x8000000000000000ull;
  const std::uint32_t high = static_cast<std::uint32_t>(bits >> 32) & 0x7FFFFFFF;
  if (high >= 0x7FF00000) return x + x;  // NaN, +-inf
  double t;
  if (high < 0x00100000) {                    // zero or subnormal
    if ((bits << 1) == 0) return x;           // +-0
    const double scaled = x * 0x1p54;         // exact
    const std::uint32_t scaledHigh = static_cast<std::uint32_t>(detail::bitsOf(scaled) >> 32) & 0x7FFFFFFF;
    t = detail::fromBits(sign | static_cast<std::uint64_t>(scaledHigh / 3 + B2) << 32);
  } else {
    t = detail::fromBits(sign | static_cast<std::uint64_t>(high / 3 + B1) << 32);
  }
  // cbrt(x) = t cbrt(x / t^3) ~ t P(t^3 / x)
  const double r = (t * t) * (t / x);
  t = t * ((P0 + r * (P1 + r * P2)) + ((r * r) * r) * (P3 + r * P4));
  // rounded away from zero to 23 bits: t^2 is exact, and t larger than cbrt(x) in magnitude
  t = detail::fromBits((detail::bitsOf(t) + 0x80000000ull) & 0xFFFFFFFFC0000000ull);
  // one Newton step: t + t (x/t^2 - t) / (2t + x/t^2), the error <= 0.5 + 0.5/3 + epsilon ulp
  const double quotient = x / (t * t);
  return t + t * ((quotient - t) / ((t + t) + quotient));
}

}  // namespace chaindrive::math
