// Sine and cosine together, in our own arithmetic: the link kinematics take one pair per link
// and evaluation (the hottest transcendental of the solver). Unlike libm's sin/cos, whose last
// bits differ between library versions and between the CPU-specific code paths a library picks
// at run time (with and without FMA), these give the same bits on every x86-64 machine: the
// chaotic link dynamics turn any such difference into a visibly different run.
//
// Range reduction by multiples of pi/2 in three parts (Cody-Waite, fdlibm's pio2_1/2/2t),
// then fdlibm's kernel polynomials on [-pi/4, pi/4]: for |x| < 2^20 within 2 ulp of libm
// (tests/cpp/sincos_test.cpp) and 2.43 ulp of the exact value (tests/cpp/math/elementary_test.cpp).
// Beyond that (a link turns 2^20 rad after hours of running), and for NaN and infinities,
// math::sin and math::cos (src/math/elementary.h: Payne-Hanek reduction, within 1 ulp), which in
// turn give these functions' bits below 2^20.
#pragma once

#include <cmath>

#include "math/elementary.h"
#include "simd.h"

namespace chaindrive {

namespace sincos_detail {

constexpr double kTwoOverPi = 6.36619772367581382433e-01;
constexpr double kPio2A = 1.57079632673412561417e+00;  // first 33 bits of pi/2: k * kPio2A is exact
constexpr double kPio2B = 6.07710050630396597660e-11;  // next 33 bits
constexpr double kPio2C = 2.02226624879595063154e-21;  // pi/2 - kPio2A - kPio2B
constexpr double kReducible = 1048576.0;               // 2^20

/// sin and cos of x - kd pi/2 (|x - kd pi/2| <= pi/4): one definition for a double and for a
/// pair of doubles (the same operations in the same order, so the same bits in every lane).
template <class T>
CHAINDRIVE_ALWAYS_INLINE void kernel(T x, T kd, T& s, T& c) {
  const T r = ((x - kd * kPio2A) - kd * kPio2B) - kd * kPio2C;
  const T z = r * r;
  s = r + r * z *
              (-1.66666666666666324348e-01 +
               z * (8.33333333332248946124e-03 +
                    z * (-1.98412698298579493134e-04 +
                         z * (2.75573137070700676789e-06 +
                              z * (-2.50507602534068634195e-08 + z * 1.58969099521155010221e-10)))));
  c = 1.0 - 0.5 * z +
      z * z *
          (4.16666666666666019037e-02 +
           z * (-1.38888888888741095749e-03 +
                z * (2.48015872894767294178e-05 +
                     z * (-2.75573143513906633035e-07 +
                          z * (2.08757232129817482790e-09 + z * -1.13596475577881948265e-11)))));
}

}  // namespace sincos_detail

inline void sinCos(double x, double& sine, double& cosine) {
  using namespace sincos_detail;
  if (!(std::fabs(x) < kReducible)) {  // (and NaN)
    sine = math::sin(x);
    cosine = math::cos(x);
    return;
  }
  const long long k = static_cast<long long>(x * kTwoOverPi + (x >= 0.0 ? 0.5 : -0.5));
  double s, c;
  kernel(x, static_cast<double>(k), s, c);
  switch (k & 3) {
    case 0: sine = s; cosine = c; break;
    case 1: sine = c; cosine = -s; break;
    case 2: sine = -s; cosine = -c; break;
    default: sine = -c; cosine = s; break;
  }
}

/// sinCos of a vector of W angles (simd.h), bit for bit the values of sinCos one at a time: the
/// quadrant chosen by bit masks instead of a branch per angle (the link angles around the chain
/// fall in every quadrant); lanes beyond the reducible range (and NaN) fall back to math::sin and
/// math::cos, one angle at a time.
template <int W>
CHAINDRIVE_ALWAYS_INLINE void sinCosLanes(typename simd::Lanes<W>::V x, typename simd::Lanes<W>::V& sine,
                                          typename simd::Lanes<W>::V& cosine) {
  using namespace sincos_detail;
  using V = typename simd::Lanes<W>::V;
  using Mask = typename simd::Lanes<W>::Mask;
  using simd::flipSign;
  using simd::select;
  const V magnitude = (V)((Mask)x & ~(Mask)simd::splat<V>(-0.0));  // |x|: the sign bit cleared
  const Mask reducible = magnitude < kReducible;                    // false for NaN too
  const V xr = (V)((Mask)x & reducible);          // 0 where not: nothing out of int range converted
  const V half = select(xr >= 0.0, simd::splat<V>(0.5), simd::splat<V>(-0.5));
  const auto k = __builtin_convertvector(xr * kTwoOverPi + half, typename simd::Lanes<W>::Int);  // |k| < 2^20
  V s, c;
  kernel(xr, __builtin_convertvector(k, V), s, c);
  // the quadrant as a double: SSE2 compares doubles into 64-bit masks, but not 64-bit integers
  const V quadrant = __builtin_convertvector(k & 3, V);
  const Mask swap = (quadrant == 1.0) | (quadrant == 3.0), negateSine = quadrant >= 2.0,
             negateCosine = (quadrant == 1.0) | (quadrant == 2.0);
  sine = flipSign(negateSine, select(swap, c, s));
  cosine = flipSign(negateCosine, select(swap, s, c));
  if (simd::allSet(reducible)) return;
  for (int l = 0; l < W; ++l)
    if (!reducible[l]) {
      sine[l] = math::sin(x[l]);
      cosine[l] = math::cos(x[l]);
    }
}

/// sinCos of two angles at once (one pair of SSE2 registers), the same bits.
inline void sinCos2(const double x[2], double sine[2], double cosine[2]) {
  using V = simd::Lanes<2>::V;
  V s, c;
  sinCosLanes<2>(simd::load<V>(x), s, c);
  simd::store(sine, s);
  simd::store(cosine, c);
}

}  // namespace chaindrive
