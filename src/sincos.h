// Sine and cosine together, in our own arithmetic: the link kinematics take one pair per link
// and evaluation (the hottest transcendental of the solver). Unlike libm's sin/cos, whose last
// bits differ between library versions and between the CPU-specific code paths a library picks
// at run time (with and without FMA), these give the same bits on every x86-64 machine: the
// chaotic link dynamics turn any such difference into a visibly different run.
//
// Range reduction by multiples of pi/2 in three parts (Cody-Waite, fdlibm's pio2_1/2/2t),
// then fdlibm's kernel polynomials on [-pi/4, pi/4]; within 2 ulp of libm for |x| < 2^20
// (tests/cpp/sincos_test.cpp). Beyond that, libm (a link turns 2^20 rad after hours of running).
#pragma once

#include <cmath>

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
inline void kernel(T x, T kd, T& s, T& c) {
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
    sine = std::sin(x);
    cosine = std::cos(x);
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

/// sinCos of two angles at once, bit for bit the same values: both lanes in one pair of SSE2
/// registers (GCC's and Clang's vector extensions), the quadrant chosen by bit masks instead of
/// a branch per angle (the link angles around the chain fall in every quadrant).
inline void sinCos2(const double x[2], double sine[2], double cosine[2]) {
  using namespace sincos_detail;
  typedef double Pair __attribute__((vector_size(16)));
  typedef long long Mask __attribute__((vector_size(16)));
  typedef int Int2 __attribute__((vector_size(8)));
  // a where the mask is set, b elsewhere; b with its sign flipped where the mask is set
  const auto select = [](Mask m, Pair a, Pair b) { return (Pair)(((Mask)a & m) | ((Mask)b & ~m)); };
  const auto flipSign = [](Mask m, Pair a) { return (Pair)((Mask)a ^ (m & (Mask)Pair{-0.0, -0.0})); };
  const Pair in = {x[0], x[1]};
  const Pair magnitude = {std::fabs(x[0]), std::fabs(x[1])};
  const Mask reducible = magnitude < kReducible;  // false for NaN too
  const Pair xr = (Pair)((Mask)in & reducible);   // 0 where not: nothing out of int range converted
  const Pair half = select(xr >= 0.0, Pair{0.5, 0.5}, Pair{-0.5, -0.5});
  const Int2 k = __builtin_convertvector(xr * kTwoOverPi + half, Int2);  // truncation, |k| < 2^20
  Pair s, c;
  kernel(xr, __builtin_convertvector(k, Pair), s, c);
  // the quadrant as a double: SSE2 compares doubles into 64-bit masks, but not 64-bit integers
  const Pair quadrant = __builtin_convertvector(k & 3, Pair);
  const Mask swap = (quadrant == 1.0) | (quadrant == 3.0), negateSine = quadrant >= 2.0,
             negateCosine = (quadrant == 1.0) | (quadrant == 2.0);
  const Pair sineOut = flipSign(negateSine, select(swap, c, s));
  const Pair cosineOut = flipSign(negateCosine, select(swap, s, c));
  for (int lane = 0; lane < 2; ++lane) {
    if (reducible[lane]) {
      sine[lane] = sineOut[lane];
      cosine[lane] = cosineOut[lane];
    } else {
      sine[lane] = std::sin(x[lane]);
      cosine[lane] = std::cos(x[lane]);
    }
  }
}

}  // namespace chaindrive
