// sin, cos and tan (src/math/elementary.h): the argument reduced to [-pi/4, pi/4] as a
// double-double r + t, then fdlibm's kernels (FreeBSD msun k_sin.c, k_cos.c, k_tan.c) with the
// tail t as a first-order correction. Below 2^20, sin and cos are src/math/sincos.h's sinCos (the hot
// loops' own bits); tan reduces with pi/2 in four parts. From 2^20 on, Payne-Hanek: the bits of
// x times the bits of 2/pi that matter, in exact integer arithmetic.
#include <cmath>
#include <cstdint>
#include <limits>

#include "math/double_double.h"
#include "math/elementary.h"
#include "math/sincos.h"

namespace chaindrive::math {
namespace {

using detail::DoubleDouble;
using detail::highPart;
using detail::kPio2Hi;
using detail::kPio2Lo;

constexpr double kLargestDouble = std::numeric_limits<double>::max();

/// an argument x = (4 j + quadrant) pi/2 + hi + lo for some integer j, |hi + lo| <= pi/4 or a hair more
struct Reduced {
  int quadrant;
  double hi;
  double lo;
};

// ---- Payne-Hanek reduction, |x| >= 2^20 ----

constexpr int kWindowWords = 8;                 // 32-bit words of 2/pi multiplied by an argument
constexpr int kProductLimbs = kWindowWords + 2;  // the product with the 53-bit significand

// 2/pi = sum over i of kTwoOverPi[i] 2^(-32 (i + 1)), 1216 bits: the largest double (2^1023 times
// a 53-bit significand) needs words up to (1023 - 52 - 3) / 32 + kWindowWords = 38. From exact
// integer arithmetic, pi from Machin's formula (equal to fdlibm's 24-bit table ipio2):
//   python3 -c '
//   def atan_inv(n, one):  # atan(1/n) * one, the alternating series in integers
//       term, total, k = one // n, one // n, 1
//       while term:
//           term //= n * n; k += 2
//           total += term // k if k % 4 == 1 else -(term // k)
//       return total
//   words = 38; bits = 32 * words; one = 1 << (bits + 64)
//   pi = 16 * atan_inv(5, one) - 4 * atan_inv(239, one)   # pi 2^(bits+64), off by a few units
//   two_over_pi = (1 << (2 * bits + 129)) // pi >> 64     # floor(2/pi 2^bits)
//   print(", ".join("0x%08X" % (two_over_pi >> 32 * (words - 1 - i) & 0xFFFFFFFF) for i in range(words)))'
constexpr std::uint32_t kTwoOverPi[38] = {
    0xA2F9836E, 0x4E441529, 0xFC2757D1, 0xF534DDC0, 0xDB629599, 0x3C439041, 0xFE5163AB, 0xDEBBC561,
    0xB7246E3A, 0x424DD2E0, 0x06492EEA, 0x09D1921C, 0xFE1DEB1C, 0xB129A73E, 0xE88235F5, 0x2EBB4484,
    0xE99C7026, 0xB45F7E41, 0x3991D639, 0x835339F4, 0x9C845F8B, 0xBDF9283B, 0x1FF897FF, 0xDE05980F,
    0xEF2F118B, 0x5A0A6D1F, 0x6D367ECF, 0x27CB09B7, 0x4F463F66, 0x9E5FEA2D, 0x7527BAC7, 0xEBE5F17B,
    0x3D0739F7, 0x8A5292EA, 0x6BFB5FB1, 0x1F8D5D08, 0x56033046, 0xFC7B6BAB};
static_assert((1023 - 52 - 3) / 32 + kWindowWords <= 38, "the window of the largest double lies in the table");

/// m times the words first .. first + kWindowWords - 1 of 2/pi, least significant limb first
void multiplyWindow(std::uint64_t m, int first, std::uint32_t product[kProductLimbs]) {
  const std::uint64_t mLimbs[2] = {m & 0xFFFFFFFFu, m >> 32};
  for (int i = 0; i < kProductLimbs; ++i) product[i] = 0;
  for (int j = 0; j < kWindowWords; ++j) {
    const std::uint64_t word = kTwoOverPi[first + kWindowWords - 1 - j];
    std::uint64_t carry = 0;
    for (int i = 0; i < 2; ++i) {
      const std::uint64_t sum = word * mLimbs[i] + product[i + j] + carry;  // <= 2^64 - 1
      product[i + j] = static_cast<std::uint32_t>(sum);
      carry = sum >> 32;
    }
    product[j + 2] = static_cast<std::uint32_t>(carry);
  }
}

/// the 64 bits of `limbs` just below bit position `top` (bits top - 64 .. top - 1; 0 outside them)
std::uint64_t bitsBelow(const std::uint32_t limbs[kProductLimbs], int top) {
  const int lowest = top - 64;                   // >= -64 in every use
  const int limb = (lowest + 64) / 32 - 2;       // floor(lowest / 32)
  const int shift = lowest - 32 * limb;          // 0 .. 31
  const auto limbAt = [limbs](int i) -> std::uint64_t { return i >= 0 && i < kProductLimbs ? limbs[i] : 0; };
  const std::uint64_t low = limbAt(limb) | limbAt(limb + 1) << 32;
  return shift == 0 ? low : low >> shift | limbAt(limb + 2) << (64 - shift);
}

/// clears the bits from position `point` on
void keepBelow(std::uint32_t limbs[kProductLimbs], int point) {
  for (int i = 0; i < kProductLimbs; ++i) {
    const int lowest = 32 * i;
    if (lowest >= point) limbs[i] = 0;
    else if (point - lowest < 32) limbs[i] &= (1u << (point - lowest)) - 1u;
  }
}

/// two's complement of the whole number
void negate(std::uint32_t limbs[kProductLimbs]) {
  std::uint64_t carry = 1;
  for (int i = 0; i < kProductLimbs; ++i) {
    const std::uint64_t sum = static_cast<std::uint64_t>(~limbs[i]) + carry;
    limbs[i] = static_cast<std::uint32_t>(sum);
    carry = sum >> 32;
  }
}

/// position of the highest set bit of v != 0
int highestBit(std::uint32_t v) {
  int position = 0;
  for (int step = 16; step > 0; step /= 2)
    if (v >> step) {
      v >>= step;
      position += step;
    }
  return position;
}

/// pi/2 times fraction / 2^point (a part of a quadrant, below 1/2), from its leading 106 bits
DoubleDouble radiansOfFraction(const std::uint32_t fraction[kProductLimbs], int point) {
  int limb = kProductLimbs - 1;
  while (limb >= 0 && fraction[limb] == 0) --limb;
  if (limb < 0) return {0.0, 0.0};  // (no double is a multiple of pi/2 but 0, which is not reduced here)
  const int top = 32 * limb + highestBit(fraction[limb]);  // the leading 1
  const std::uint64_t lead = bitsBelow(fraction, top + 1), next = bitsBelow(fraction, top - 63);
  // two 53-bit integers, exact as doubles, scaled by powers of two (the leading 1 lies within
  // about 64 bits of the point for every double, far from the exponent range's ends)
  const double hi = static_cast<double>(lead >> 11) * detail::powerOfTwo(top - 52 - point);
  const double lo = static_cast<double>((lead & 0x7FF) << 42 | next >> 22) * detail::powerOfTwo(top - 105 - point);
  const DoubleDouble product = detail::twoProduct(hi, kPio2Hi);
  return detail::fastTwoSum(product.hi, product.lo + (hi * kPio2Lo + lo * kPio2Hi));
}

/// Payne-Hanek: x 2/pi to its integer part mod 4 and a fraction of 222 bits or more; the words of
/// 2/pi after the window add less than 2^(53 - 222). The worst double, 6381956970095103 2^797,
/// leaves 2^-61 of pi/2: more than 150 bits of the fraction stay significant.
Reduced reduceLarge(double x) {  // 2^20 <= |x| < infinity
  const std::uint64_t bits = detail::bitsOf(x);
  const int q = static_cast<int>(bits >> 52 & 0x7FF) - 1075;  // |x| = m 2^q
  const std::uint64_t m = (bits & 0xFFFFFFFFFFFFFull) | 1ull << 52;
  // words i before `first` contribute m kTwoOverPi[i] 2^(q - 32 (i + 1)), multiples of 8: dropped
  const int first = q >= 3 ? (q - 3) / 32 : 0;
  std::uint32_t product[kProductLimbs];
  multiplyWindow(m, first, product);
  const int point = 32 * (first + kWindowWords) - q;  // the product's bits below `point` are the fraction
  int quadrant = static_cast<int>(bitsBelow(product, point + 2) >> 62);
  keepBelow(product, point);
  const bool roundUp = bitsBelow(product, point) >> 63;  // fraction >= 1/2: the next multiple, from below
  if (roundUp) {
    negate(product);
    keepBelow(product, point);
    ++quadrant;
  }
  DoubleDouble r = radiansOfFraction(product, point);
  if (roundUp != (x < 0)) r = {-r.hi, -r.lo};
  return {(x < 0 ? -quadrant : quadrant) & 3, r.hi, r.lo};
}

// ---- the reduction below 2^20 (tan) ----

// pi/2 in four parts (fdlibm's pio2_1, pio2_2, pio2_3 of 33 bits or fewer, pio2_3t): for
// |k| < 2^20 the products with the first three are exact
constexpr double kPio2Part1 = 1.57079632673412561417e+00;
constexpr double kPio2Part2 = 6.07710050630396597660e-11;
constexpr double kPio2Part3 = 2.02226624871116645580e-21;
constexpr double kPio2Part4 = 8.47842766036889956997e-32;

Reduced reduceMedium(double x) {  // |x| < 2^20
  const long long k = static_cast<long long>(x * sincos_detail::kTwoOverPi + (x >= 0.0 ? 0.5 : -0.5));
  const double kd = static_cast<double>(k);
  const double first = x - kd * kPio2Part1;  // exact (Sterbenz: x and k kPio2Part1 within a factor 2)
  const DoubleDouble second = detail::twoSum(first, -kd * kPio2Part2);
  const DoubleDouble third = detail::twoSum(second.hi, -kd * kPio2Part3);
  const DoubleDouble r = detail::twoSum(third.hi, (second.lo + third.lo) - kd * kPio2Part4);
  return {static_cast<int>(k & 3), r.hi, r.lo};
}

// ---- fdlibm's kernels on [-pi/4, pi/4], y the tail of x ----

double sinKernel(double x, double y) {  // k_sin.c with iy = 1: sin(x + y) ~ sin(x) + (1 - x^2/2) y
  constexpr double S1 = -1.66666666666666324348e-01, S2 = 8.33333333332248946124e-03,
                   S3 = -1.98412698298579493134e-04, S4 = 2.75573137070700676789e-06,
                   S5 = -2.50507602534068634195e-08, S6 = 1.58969099521155010221e-10;
  const double z = x * x, w = z * z;
  const double r = S2 + z * (S3 + z * S4) + z * w * (S5 + z * S6);
  const double v = z * x;
  return x - ((z * (0.5 * y - v * r) - y) - v * S1);
}

double cosKernel(double x, double y) {  // k_cos.c: cos(x + y) ~ cos(x) - x y
  constexpr double C1 = 4.16666666666666019037e-02, C2 = -1.38888888888741095749e-03,
                   C3 = 2.48015872894767294178e-05, C4 = -2.75573143513906633035e-07,
                   C5 = 2.08757232129817482790e-09, C6 = -1.13596475577881948265e-11;
  const double z = x * x, w = z * z;
  const double r = z * (C1 + z * (C2 + z * C3)) + w * w * (C4 + z * (C5 + z * C6));
  const double halfZ = 0.5 * z, oneMinusHalfZ = 1.0 - halfZ;
  return oneMinusHalfZ + (((1.0 - oneMinusHalfZ) - halfZ) + (z * r - x * y));  // (1 - z/2 in two parts)
}

/// tan(x + y) (iy = 1) or -1/tan(x + y) (iy = -1): k_tan.c
double tanKernel(double x, double y, int iy) {
  constexpr double T[13] = {3.33333333333334091986e-01,  1.33333333333201242699e-01, 5.39682539762260521377e-02,
                            2.18694882948595424599e-02,  8.86323982359930005737e-03, 3.59207910759131235356e-03,
                            1.45620945432529025516e-03,  5.88041240820264096874e-04, 2.46463134818469906812e-04,
                            7.81794442939557092300e-05,  7.14072491382608190305e-05, -1.85586374855275456654e-05,
                            2.59073051863633712884e-05};
  constexpr double kPio4 = 7.85398163397448278999e-01, kPio4Lo = 3.06161699786838301793e-17;
  const bool nearPio4 = std::fabs(x) >= 0x1.59428p-1, negative = x < 0.0;  // |x| >= 0.6744: tan(pi/4 - u)
  if (nearPio4) {
    if (negative) {
      x = -x;
      y = -y;
    }
    x = (kPio4 - x) + (kPio4Lo - y);
    y = 0.0;
  }
  const double z = x * x, w = z * z;
  // x^5 (T1 + x^2 T2 + ...) as odd and even powers of x^4, tan(x + y) ~ tan(x) + (1 + x^2) y
  const double odd = T[1] + w * (T[3] + w * (T[5] + w * (T[7] + w * (T[9] + w * T[11]))));
  const double even = z * (T[2] + w * (T[4] + w * (T[6] + w * (T[8] + w * (T[10] + w * T[12])))));
  const double s = z * x;
  const double r = (y + z * (s * (odd + even) + y)) + T[0] * s;
  const double sum = x + r;
  if (nearPio4) {
    const double v = iy;  // (1 - tan u) / (1 + tan u) = 1 - 2 (tan u - tan^2 u / (1 + tan u))
    return (negative ? -1.0 : 1.0) * (v - 2.0 * (x - (sum * sum / (sum + v) - r)));
  }
  if (iy == 1) return sum;
  const double sumHigh = highPart(sum), sumRest = r - (sumHigh - x);  // sumHigh + sumRest = x + r
  const double inverse = -1.0 / sum, inverseHigh = highPart(inverse);
  return inverseHigh + inverse * ((1.0 + inverseHigh * sumHigh) + inverseHigh * sumRest);
}

}  // namespace

double sin(double x) {
  if (x == 0.0) return x;  // sin(-0) = -0 (sinCos's polynomial gives +0)
  if (std::fabs(x) < sincos_detail::kReducible) {
    double sine, cosine;
    sinCos(x, sine, cosine);
    return sine;
  }
  if (!(std::fabs(x) <= kLargestDouble)) return x - x;  // NaN for NaN and infinities
  const Reduced r = reduceLarge(x);
  switch (r.quadrant) {
    case 0: return sinKernel(r.hi, r.lo);
    case 1: return cosKernel(r.hi, r.lo);
    case 2: return -sinKernel(r.hi, r.lo);
    default: return -cosKernel(r.hi, r.lo);
  }
}

double cos(double x) {
  if (std::fabs(x) < sincos_detail::kReducible) {
    double sine, cosine;
    sinCos(x, sine, cosine);
    return cosine;
  }
  if (!(std::fabs(x) <= kLargestDouble)) return x - x;
  const Reduced r = reduceLarge(x);
  switch (r.quadrant) {
    case 0: return cosKernel(r.hi, r.lo);
    case 1: return -sinKernel(r.hi, r.lo);
    case 2: return -cosKernel(r.hi, r.lo);
    default: return sinKernel(r.hi, r.lo);
  }
}

double tan(double x) {
  const double magnitude = std::fabs(x);
  if (magnitude < 0x1p-27) return x;  // tan x = x (1 + x^2/3 + ...): x itself, correctly rounded (and -0)
  if (!(magnitude <= kLargestDouble)) return x - x;
  if (magnitude < 0x1.921fcp-1) return tanKernel(x, 0.0, 1);  // |x| <~ pi/4: no reduction
  const Reduced r = magnitude < sincos_detail::kReducible ? reduceMedium(x) : reduceLarge(x);
  return tanKernel(r.hi, r.lo, 1 - 2 * (r.quadrant & 1));  // odd quadrants: -1/tan
}

}  // namespace chaindrive::math
