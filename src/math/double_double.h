// Error-free transformations of IEEE doubles, the extra precision of src/math: a sum or a product
// of two doubles as an unevaluated pair hi + lo ("double-double"), from round-to-nearest
// additions and multiplications alone. No fused multiply-add anywhere (the project builds with
// -ffp-contract=off; the pragmas below say the same to compilers that default to contracting,
// since one contracted a * b - p would silently break TwoProduct).
// Internal to src/math: not part of the library's interface.
#pragma once

#include <cstdint>
#include <cstring>
#include <limits>

#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(_MSC_VER)
#pragma fp_contract(off)
#endif

namespace chaindrive::math::detail {

/// the value hi + lo; normalized pairs have |lo| <= ulp(hi) / 2
struct DoubleDouble {
  double hi;
  double lo;
};

inline std::uint64_t bitsOf(double x) {
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  return bits;
}

inline double fromBits(std::uint64_t bits) {
  double x;
  std::memcpy(&x, &bits, sizeof x);
  return x;
}

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kPio2Hi = 1.57079632679489655800e+00;  // pi/2 in two doubles
constexpr double kPio2Lo = 6.12323399573676603587e-17;

/// x with the low 32 bits of its significand cleared (a short high part whose products are exact)
inline double highPart(double x) { return fromBits(bitsOf(x) & 0xFFFFFFFF00000000ull); }

/// 2^k for -1022 <= k <= 1023, written as its bits
inline double powerOfTwo(int k) { return fromBits(static_cast<std::uint64_t>(k + 1023) << 52); }

/// a + b = hi + lo exactly, whatever the magnitudes (Knuth's TwoSum)
inline DoubleDouble twoSum(double a, double b) {
  const double sum = a + b;
  const double bPart = sum - a;  // the part of the sum that came from b ...
  const double aPart = sum - bPart;
  return {sum, (a - aPart) + (b - bPart)};  // ... and what each lost
}

/// a + b = hi + lo exactly, for |a| >= |b| or a == 0 (Dekker's FastTwoSum)
inline DoubleDouble fastTwoSum(double a, double b) {
  const double sum = a + b;
  return {sum, b - (sum - a)};
}

/// a = hi + lo with hi of at most 26 significant bits and lo of at most 26 and a sign, so that
/// the four products of two split numbers are exact (Dekker's split; |a| < 2^995)
inline DoubleDouble split(double a) {
  const double scaled = 134217729.0 * a;  // (2^27 + 1) a
  const double hi = scaled - (scaled - a);
  return {hi, a - hi};
}

/// a * b = hi + lo exactly (Dekker's TwoProduct, without fused multiply-add), provided
/// |a|, |b| < 2^995 and the error term does not underflow (|a b| above about 2^-969)
inline DoubleDouble twoProduct(double a, double b) {
  const double product = a * b;
  const DoubleDouble as = split(a), bs = split(b);
  const double error = ((as.hi * bs.hi - product) + as.hi * bs.lo + as.lo * bs.hi) + as.lo * bs.lo;
  return {product, error};
}

}  // namespace chaindrive::math::detail
