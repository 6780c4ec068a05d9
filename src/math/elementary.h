// The elementary functions of the solver, in our own arithmetic. Why: C runtimes compute
// transcendental functions differently (glibc's versions and its CPU-specific code paths, the
// Windows runtime, other compilers' libraries disagree in the last bits), and the chaotic chain
// dynamics turn one differing bit into a visibly different run. These functions use only IEEE
// double +, -, *, /, sqrt and exact bit operations (no libm call, no fused multiply-add, no long
// double, no 128-bit integers), so they give the same bits on every platform that rounds doubles
// to nearest without excess precision (every x86-64 and ARM64 target) when built, as the project
// is, without contracting a * b + c (GCC needs -ffp-contract=off; src/math/double_double.h tells
// Clang and MSVC with pragmas).
//
// Algorithms, and the largest errors measured against glibc's 64-bit long double functions, in
// ulp of the double nearest the exact value (tests/cpp/math/elementary_test.cpp, about 200000
// samples a function over the general ranges and the solver's; in brackets the largest of 10^7
// or more samples a range, measured once where higher):
//   sin, cos  |x| < 2^20: src/math/sincos.h's sinCos, bit for bit (Cody-Waite reduction, pi/2 in three
//             parts; fdlibm's kernel polynomials, the cosine without its correction term): not
//             faithful, 1.42 on [-8, 8] and 2.0 up to 2^20 (1.55 and 2.43). sin(-0) is -0 here
//             (sinCos gives +0). From 2^20 on: Payne-Hanek reduction (1216 bits of 2/pi) to a
//             double-double, fdlibm's kernels with the tail: 0.75 (0.78), 0.48 at the doubles
//             closest to multiples of pi/2.
//   tan       fdlibm's kernel with the tail of the argument, reduced to a double-double (pi/2 in
//             four parts below 2^20, Payne-Hanek beyond): 0.83 (0.88).
//   asin      fdlibm: x + x^3 R(x^2) below 0.5, pi/2 - 2 asin(sqrt((1 - x)/2)) above, pi/2 in
//             two parts, the leading terms summed without error: 0.67 (0.73).
//   acos      fdlibm's R and splits of pi/2 likewise: 0.65 (0.68).
//   atan      fdlibm: atan(c) + atan((x - c)/(1 + c x)) about the breakpoints 7/16, 11/16, 19/16,
//             39/16, an odd polynomial: 0.85 (0.85).
//   atan2     y/x with its remainder (TwoProduct) as a derivative term, then atan's method;
//             pi - atan in double-double: 0.84 (0.85).
//   exp       fdlibm: x = k ln2 + r (Cody-Waite, ln2 in two parts), exp(r) = 1 + r + r c/(2 - c),
//             the last sums without error; subnormal results rounded once more: 0.75.
//   log       x = 2^e m, m c = 1 + r exactly (128 table values c), log(1/c) in two doubles, the
//             series of log1p(r), all in double-double (relative error below 2^-68): 0.50.
//   pow       exp of y log(x), both in double-double, exp's method on the pair: 0.75 (0.78),
//             also where |y log x| nears 745.
//   cbrt      FreeBSD msun: a cube root from the bits, a polynomial to 23 bits, rounded, one
//             Newton step: 0.67.
// Every function but sin and cos below 2^20 measures within 1 ulp (faithful rounding). Special
// values follow C99 Annex F (signed zeros, infinities, NaN). Cost per call against glibc 2.36 on
// x86-64 (which uses FMA): sin, cos, asin, acos, atan, atan2, cbrt about the same or less; exp 1.2
// to 2.3 times; tan below 2^20 1.8 times; log 2.5 times; pow 2.4 to 3 times (26 to 33 ns).
#pragma once

namespace chaindrive::math {

double sin(double x);
double cos(double x);
double tan(double x);
double asin(double x);
double acos(double x);
double atan(double x);
double atan2(double y, double x);
double exp(double x);
double log(double x);
double pow(double x, double y);
double cbrt(double x);

}  // namespace chaindrive::math

/// math::pow for C code: a third-party C library in the build has its pow references renamed to
/// this symbol, so that it too computes powers with these bits.
extern "C" double chaindrive_pow(double x, double y);
