// asin, acos, atan and atan2 (src/math/elementary.h): fdlibm's methods (FreeBSD msun e_asin.c,
// e_acos.c, s_atan.c) and their coefficients; asin and acos sum their leading terms without
// error where fdlibm rounds them (their largest errors near 0.5 fall from about 0.93 to 0.7 ulp);
// atan2 adds the rounding error of y/x as a derivative term and forms pi - atan in double-double,
// which keeps it within 1 ulp.
#include <cmath>
#include <cstdint>
#include <limits>

#include "math/double_double.h"
#include "math/elementary.h"

namespace chaindrive::math {
namespace {

using detail::DoubleDouble;
using detail::highPart;
using detail::kInfinity;
using detail::kPio2Hi;
using detail::kPio2Lo;

constexpr double kPio4Hi = 7.85398163397448278999e-01;
constexpr double kPiHi = 3.14159265358979311600e+00;  // pi in two doubles
constexpr double kPiLo = 1.22464679914735317720e-16;
constexpr double k3Pio4 = 2.35619449019234492885e+00;

/// (asin(s) - s) / s^3 as a function of t = s^2 (t times a rational function of t, Remez error
/// below 2^-58.75 on [0, 0.25]): fdlibm's pS0..pS5, qS1..qS4
double asinRational(double t) {
  const double p = t * (1.66666666666666657415e-01 +
                        t * (-3.25565818622400915405e-01 +
                             t * (2.01212532134862925881e-01 +
                                  t * (-4.00555345006794114027e-02 +
                                       t * (7.91534994289814532176e-04 + t * 3.47933107596021167570e-05)))));
  const double q = 1.0 + t * (-2.40339491173441421878e+00 +
                              t * (2.02094576023350569471e+00 +
                                   t * (-6.88283971605453293030e-01 + t * 7.70381505559019352791e-02)));
  return p / q;
}

/// atan(t) + correction = table - rest for 0 <= t < 2^66 (s_atan.c: atan(t) = atan(c) + atan(u)
/// for the breakpoint c at hand, u by an odd polynomial); with correction 0, fdlibm's bits
struct AtanParts {
  double table;
  double rest;  // (subtracted: the order of fdlibm's operations)
};

AtanParts atanParts(double t, double correction) {
  constexpr double kAtanHi[4] = {4.63647609000806093515e-01, 7.85398163397448278999e-01, 9.82793723247329054082e-01,
                                 1.57079632679489655800e+00};  // atan(0.5), atan(1), atan(1.5), atan(inf)
  constexpr double kAtanLo[4] = {2.26987774529616870924e-17, 3.06161699786838301793e-17, 1.39033110312309984516e-17,
                                 6.12323399573676603587e-17};
  constexpr double aT[11] = {3.33333333333329318027e-01,  -1.99999999998764832476e-01, 1.42857142725034663711e-01,
                             -1.11111104054623557880e-01, 9.09088713343650656196e-02,  -7.69187620504482999495e-02,
                             6.66107313738753120669e-02,  -5.83357013379057348645e-02, 4.97687799461593236017e-02,
                             -3.65315727442169155270e-02, 1.62858201153657823623e-02};
  // the breakpoint c (id) and u = (t - c) / (1 + c t), with exact numerators
  const int id = t < 0.4375 ? -1 : t < 0.6875 ? 0 : t < 1.1875 ? 1 : t < 2.4375 ? 2 : 3;
  const double u = id == -1 ? t
                   : id == 0 ? (2.0 * t - 1.0) / (2.0 + t)
                   : id == 1 ? (t - 1.0) / (t + 1.0)
                   : id == 2 ? (t - 1.5) / (1.0 + 1.5 * t)
                             : -1.0 / t;
  const double z = u * u, w = z * z;
  const double odd = z * (aT[0] + w * (aT[2] + w * (aT[4] + w * (aT[6] + w * (aT[8] + w * aT[10])))));
  const double even = w * (aT[1] + w * (aT[3] + w * (aT[5] + w * (aT[7] + w * aT[9]))));
  if (id < 0) return {0.0, (u * (odd + even) - correction) - u};
  return {kAtanHi[id], (u * (odd + even) - (kAtanLo[id] + correction)) - u};
}

int exponentField(double x) { return static_cast<int>(detail::bitsOf(x) >> 52 & 0x7FF); }

/// atan2(a, +-b) for finite a, b > 0 (leftHalf: x < 0), in [0, pi]
double angleOfFinite(double a, double b, bool leftHalf) {
  const int exponentGap = exponentField(a) - exponentField(b);
  if (exponentGap > 60) return kPio2Hi + (kPio2Lo + (leftHalf ? b / a : -(b / a)));  // pi/2 -+ b/a
  if (exponentGap < -60) return leftHalf ? kPiHi + (kPiLo - a / b) : a / b;          // 0 or pi, +- a/b
  // the same ratio with magnitudes near 1: no overflow or underflow in TwoProduct below
  const double scale = a > 0x1p500 || b > 0x1p500 ? 0x1p-600 : a < 0x1p-500 && b < 0x1p-500 ? 0x1p600 : 1.0;
  a *= scale;
  b *= scale;
  const double q = a / b;
  const DoubleDouble qb = detail::twoProduct(q, b);
  const double remainder = (a - qb.hi) - qb.lo;  // a - q b, exact (the remainder of a division is a double)
  const double correction = remainder / b / (1.0 + q * q);  // atan(a/b) - atan(q) to first order
  const AtanParts parts = atanParts(q, correction);
  if (!leftHalf) return parts.table - parts.rest;
  const DoubleDouble fromPi = detail::twoSum(kPiHi, -parts.table);  // pi - atan, rounded once
  return fromPi.hi + ((fromPi.lo + kPiLo) + parts.rest);
}

}  // namespace

double asin(double x) {
  const double a = std::fabs(x);
  if (!(a < 1.0)) return a == 1.0 ? x * kPio2Hi + x * kPio2Lo : (x - x) / (x - x);  // +-pi/2; NaN
  if (a < 0.5) return a < 0x1p-27 ? x : x + x * asinRational(x * x);
  // asin(a) = pi/2 - 2 asin(s), s = sqrt((1 - a)/2) (1 - a exact)
  const double t = (1.0 - a) * 0.5, s = std::sqrt(t), r = asinRational(t);
  double result;
  if (a >= 0x1.f3333p-1) {  // a > 0.975
    result = kPio2Hi - (2.0 * (s + s * r) - kPio2Lo);
  } else {  // pi/4 + (pi/4 - 2 f) - (2 s r - pi/2's tail - 2 c), s = f + c split so that pi/4 - 2 f is exact;
            // the first sum without error (fdlibm rounds it: 0.93 ulp instead of 0.7)
    const double f = highPart(s), c = (t - f * f) / (s + f);
    const DoubleDouble lead = detail::twoSum(kPio4Hi, kPio4Hi - 2.0 * f);
    result = lead.hi + (lead.lo - (2.0 * s * r - (kPio2Lo - 2.0 * c)));
  }
  return x > 0.0 ? result : -result;
}

double acos(double x) {
  const double a = std::fabs(x);
  if (!(a < 1.0)) {
    if (a == 1.0) return x > 0.0 ? 0.0 : kPiHi + 2.0 * kPio2Lo;
    return (x - x) / (x - x);  // NaN
  }
  if (a < 0.5) {  // pi/2 - asin(x), pi/2 - x without error (fdlibm rounds it)
    if (a < 0x1p-57) return kPio2Hi + kPio2Lo;
    const DoubleDouble lead = detail::twoSum(kPio2Hi, -x);
    return lead.hi + ((lead.lo + kPio2Lo) - x * asinRational(x * x));
  }
  if (x < 0.0) {  // pi - 2 asin(s), s = sqrt((1 + x)/2), pi - 2 s without error (fdlibm rounds s + s R)
    const double t = (1.0 + x) * 0.5, s = std::sqrt(t);
    const DoubleDouble lead = detail::twoSum(kPiHi, -2.0 * s);
    return lead.hi + ((lead.lo + 2.0 * kPio2Lo) - 2.0 * (asinRational(t) * s));
  }
  // 2 asin(s), s = sqrt((1 - x)/2) = f + c with a short f
  const double t = (1.0 - x) * 0.5, s = std::sqrt(t), f = highPart(s), c = (t - f * f) / (s + f);
  return 2.0 * (f + (asinRational(t) * s + c));
}

double atan(double x) {
  const double t = std::fabs(x);
  if (std::isnan(x)) return x + x;
  if (t >= 0x1p66) return x > 0.0 ? kPio2Hi + kPio2Lo : -kPio2Hi - kPio2Lo;
  if (t < 0x1p-29) return x;  // atan x = x (1 - x^2/3 + ...): x itself, correctly rounded (and -0)
  const AtanParts parts = atanParts(t, 0.0);
  const double result = parts.table - parts.rest;
  return x < 0.0 ? -result : result;
}

double atan2(double y, double x) {
  if (std::isnan(x) || std::isnan(y)) return x + y;
  const double a = std::fabs(y), b = std::fabs(x);
  const bool leftHalf = std::signbit(x);  // x < 0 or x = -0
  double angle;                           // atan2(|y|, x), in [0, pi]
  if (a == 0.0) angle = leftHalf ? kPiHi : 0.0;
  else if (b == 0.0) angle = kPio2Hi;
  else if (a == kInfinity) angle = b == kInfinity ? (leftHalf ? k3Pio4 : kPio4Hi) : kPio2Hi;
  else if (b == kInfinity) angle = leftHalf ? kPiHi : 0.0;
  else angle = angleOfFinite(a, b, leftHalf);
  return std::signbit(y) ? -angle : angle;
}

}  // namespace chaindrive::math
