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

inline void sinCos(double x, double& sine, double& cosine) {
  constexpr double kTwoOverPi = 6.36619772367581382433e-01;
  constexpr double kPio2A = 1.57079632673412561417e+00;  // first 33 bits of pi/2: k * kPio2A is exact
  constexpr double kPio2B = 6.07710050630396597660e-11;  // next 33 bits
  constexpr double kPio2C = 2.02226624879595063154e-21;  // pi/2 - kPio2A - kPio2B
  if (!(std::fabs(x) < 1048576.0)) {  // 2^20 (and NaN)
    sine = std::sin(x);
    cosine = std::cos(x);
    return;
  }
  const long long k = static_cast<long long>(x * kTwoOverPi + (x >= 0.0 ? 0.5 : -0.5));
  const double kd = static_cast<double>(k);
  const double r = ((x - kd * kPio2A) - kd * kPio2B) - kd * kPio2C;
  const double z = r * r;
  const double s = r + r * z *
                           (-1.66666666666666324348e-01 +
                            z * (8.33333333332248946124e-03 +
                                 z * (-1.98412698298579493134e-04 +
                                      z * (2.75573137070700676789e-06 +
                                           z * (-2.50507602534068634195e-08 + z * 1.58969099521155010221e-10)))));
  const double c = 1.0 - 0.5 * z +
                   z * z *
                       (4.16666666666666019037e-02 +
                        z * (-1.38888888888741095749e-03 +
                             z * (2.48015872894767294178e-05 +
                                  z * (-2.75573143513906633035e-07 +
                                       z * (2.08757232129817482790e-09 + z * -1.13596475577881948265e-11)))));
  switch (k & 3) {
    case 0: sine = s; cosine = c; break;
    case 1: sine = c; cosine = -s; break;
    case 2: sine = -s; cosine = -c; break;
    default: sine = -c; cosine = s; break;
  }
}

}  // namespace chaindrive
