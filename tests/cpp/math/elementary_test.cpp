// src/math/elementary.h against glibc's long double functions on x86-64 (64-bit significands,
// accurate to about 2^-63: an error of a double result is measured to about 0.001 ulp), over the
// general ranges and the ranges the solver uses, plus the special values of C99 Annex F. Each
// sweep prints its largest error ("[ max ulp ]" lines: the figures of elementary.h's comment).
#include "math/elementary.h"

#include "math/sincos.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <random>

namespace chaindrive {
namespace {

using Rng = std::mt19937_64;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kTwo20 = 1048576.0;

// ---- measuring ----

/// the error of `value` in units in the last place of the double nearest `reference` (the ulp
/// of the reference's binade, 2^-1074 for subnormals); 0 for a NaN against a NaN, or for the
/// infinity a reference beyond the largest double rounds to
double ulpError(double value, long double reference) {
  if (std::isnan(reference) || std::isnan(value)) return std::isnan(reference) && std::isnan(value) ? 0.0 : kInf;
  const long double roundsToInfinity = 0x1.fffffffffffff8p1023L;  // DBL_MAX + half its ulp
  if (std::isinf(value) || fabsl(reference) >= roundsToInfinity)
    return std::isinf(value) && fabsl(reference) >= roundsToInfinity && std::signbit(value) == std::signbit(reference)
               ? 0.0
               : kInf;
  int exponent = 0;
  frexpl(reference, &exponent);  // |reference| in [2^(exponent-1), 2^exponent)
  const long double ulp = ldexpl(1.0L, std::max(exponent - 53, -1074));
  return static_cast<double>(fabsl(static_cast<long double>(value) - reference) / ulp);
}

struct Args {
  double x;
  double y;  // (the second argument of atan2 and pow)
};

/// the largest error of `ours` against `reference` over `count` samples; printed with its argument
double sweep(const char* function, const char* range, int count, const std::function<Args(Rng&)>& sample,
             const std::function<double(Args)>& ours, const std::function<long double(Args)>& reference) {
  Rng rng(20240611);
  double worst = 0.0;
  Args worstAt{0.0, 0.0};
  for (int i = 0; i < count; ++i) {
    const Args a = sample(rng);
    const double error = ulpError(ours(a), reference(a));
    if (!(error <= worst)) {  // (a NaN error counts as the worst)
      worst = error;
      worstAt = a;
    }
  }
  std::printf("[ max ulp ] %-6s %-44s %.3f  at (%.17g, %.17g)\n", function, range, worst, worstAt.x, worstAt.y);
  return worst;
}

double uniform(Rng& rng, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }

/// 2^u for u uniform in [log2 lo, log2 hi]: every binade equally often
double logUniform(Rng& rng, double lo, double hi) { return std::exp2(uniform(rng, std::log2(lo), std::log2(hi))); }

double randomSign(Rng& rng, double x) { return rng() & 1 ? -x : x; }

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// doubles m 2^e closest to multiples of pi/2, the closest of their exponents e (found from the
// continued fractions of 2^e 2/pi), taken with both signs: reduced arguments of 2^-61 to 2^-51
struct HardCase {
  double significand;
  int exponent;
};
constexpr HardCase kHardLarge[] = {  // from 2^20 on
    {6381956970095103, 797}, {7763785107565477, -29}, {5916243447979695, 79},  {8444920710073313, 939},
    {5850965514341686, 525}, {8160885118204141, 808}, {8360820580228475, 628}, {8583082635084172, 145},
    {7958046405119485, 243}, {6808218460873451, 562}, {7636753411044619, 201}, {6366906923947931, 194},
    {6617649673795284, 15},  {6311013172270677, 38},  {5648695676206402, 887}, {6221301883130153, 969}};
constexpr HardCase kHardSmall[] = {  // below 2^20 (45.55 .. 642600)
    {6411027962775774, -47}, {5520028710995367, -34}, {5520028710995367, -33}, {7074237752028440, -52},
    {6331365068168276, -37}, {6251702173560778, -38}, {5305678314021330, -50}, {6291533620864527, -36},
    {7874374887906596, -35}};

template <std::size_t N>
double hardCaseSweep(const char* function, const char* range, const HardCase (&cases)[N], double (*ours)(double),
                     long double (*reference)(long double)) {
  double worst = 0.0;
  for (const HardCase& c : cases)
    for (double sign : {1.0, -1.0}) {
      const double x = sign * std::ldexp(c.significand, c.exponent);
      worst = std::max(worst, ulpError(ours(x), reference(x)));
    }
  std::printf("[ max ulp ] %-6s %-44s %.3f\n", function, range, worst);
  return worst;
}

// the functions as plain function pointers (the long double ones by name: no overload to pick)
double ourSin(double x) { return math::sin(x); }
double ourCos(double x) { return math::cos(x); }
double ourTan(double x) { return math::tan(x); }
long double refSin(long double x) { return sinl(x); }
long double refCos(long double x) { return cosl(x); }
long double refTan(long double x) { return tanl(x); }

// ---- sin, cos, tan ----

// Below 2^20, the bits of sinCos (src/math/sincos.h), which is not faithful: its Cody-Waite reduction
// (pi/2 in three parts, the last a full double) loses bits for large quotients, and its cosine
// polynomial is summed as 1 - z/2 + ... without fdlibm's correction term. Its largest errors,
// measured once over 3 10^7 random arguments on [-8, 8] and 10^8 on [-2^20, 2^20] (uniform and
// log-uniform): 1.55 and 2.43 ulp (the samples here reach 1.42 and 2.0).
constexpr double kSinCosSmallBound = 1.55;
constexpr double kSinCosKernelBound = 2.43;

TEST(ElementarySinCos, BelowTwoToTheTwentyTheBitsOfSinCos) {
  Rng rng(3);
  for (int i = 0; i < 100000; ++i) {
    const double x = i % 2 ? uniform(rng, -kTwo20, kTwo20) : uniform(rng, -8.0, 8.0);
    double s = 0.0, c = 0.0;
    sinCos(x, s, c);
    ASSERT_TRUE(sameBits(math::sin(x), s)) << x;
    ASSERT_TRUE(sameBits(math::cos(x), c)) << x;
  }
}

TEST(ElementarySinCos, WithinTheKernelBoundBelowTwoToTheTwenty) {
  const auto sinOf = [](Args a) { return math::sin(a.x); };
  const auto cosOf = [](Args a) { return math::cos(a.x); };
  const auto sinRef = [](Args a) { return sinl(a.x); };
  const auto cosRef = [](Args a) { return cosl(a.x); };
  const auto small = [](Rng& r) { return Args{uniform(r, -8.0, 8.0), 0.0}; };
  const auto links = [](Rng& r) { return Args{randomSign(r, logUniform(r, 1e-3, kTwo20)), 0.0}; };
  EXPECT_LE(sweep("sin", "[-8, 8]", 30000, small, sinOf, sinRef), kSinCosSmallBound);
  EXPECT_LE(sweep("cos", "[-8, 8]", 30000, small, cosOf, cosRef), kSinCosSmallBound);
  EXPECT_LE(sweep("sin", "+-[1e-3, 2^20] log-uniform", 30000, links, sinOf, sinRef), kSinCosKernelBound);
  EXPECT_LE(sweep("cos", "+-[1e-3, 2^20] log-uniform", 30000, links, cosOf, cosRef), kSinCosKernelBound);
}

TEST(ElementarySinCos, WithinOneUlpFromTwoToTheTwenty) {
  const auto sinOf = [](Args a) { return math::sin(a.x); };
  const auto cosOf = [](Args a) { return math::cos(a.x); };
  const auto sinRef = [](Args a) { return sinl(a.x); };
  const auto cosRef = [](Args a) { return cosl(a.x); };
  const auto wide = [](Rng& r) { return Args{randomSign(r, logUniform(r, kTwo20, 1e300)), 0.0}; };
  const auto near = [](Rng& r) { return Args{randomSign(r, uniform(r, kTwo20, 1e9)), 0.0}; };
  EXPECT_LE(sweep("sin", "+-[2^20, 1e300] log-uniform", 50000, wide, sinOf, sinRef), 1.0);
  EXPECT_LE(sweep("cos", "+-[2^20, 1e300] log-uniform", 50000, wide, cosOf, cosRef), 1.0);
  EXPECT_LE(sweep("sin", "+-[2^20, 1e9]", 30000, near, sinOf, sinRef), 1.0);
  EXPECT_LE(sweep("cos", "+-[2^20, 1e9]", 30000, near, cosOf, cosRef), 1.0);
  EXPECT_LE(hardCaseSweep("sin", "hard cases of reduction, >= 2^20", kHardLarge, ourSin, refSin), 1.0);
  EXPECT_LE(hardCaseSweep("cos", "hard cases of reduction, >= 2^20", kHardLarge, ourCos, refCos), 1.0);
}

// the doubles below 2^20 closest to multiples of pi/2: sinCos's three-part reduction keeps its
// bits there (0.65 and 0.77 ulp)
TEST(ElementarySinCos, HardCasesOfSinCosReductionBelowTwoToTheTwenty) {
  EXPECT_LE(hardCaseSweep("sin", "hard cases of reduction, < 2^20", kHardSmall, ourSin, refSin), 1.0);
  EXPECT_LE(hardCaseSweep("cos", "hard cases of reduction, < 2^20", kHardSmall, ourCos, refCos), 1.0);
}

TEST(ElementarySinCos, SpecialValues) {
  EXPECT_TRUE(sameBits(math::sin(0.0), 0.0));
  EXPECT_TRUE(sameBits(math::sin(-0.0), -0.0));
  EXPECT_EQ(math::cos(0.0), 1.0);
  EXPECT_EQ(math::cos(-0.0), 1.0);
  EXPECT_EQ(math::sin(0x1p-1074), 0x1p-1074);
  EXPECT_EQ(math::sin(-1e-300), -1e-300);
  for (double x : {kInf, -kInf, std::nan("")}) {
    EXPECT_TRUE(std::isnan(math::sin(x))) << x;
    EXPECT_TRUE(std::isnan(math::cos(x))) << x;
    EXPECT_TRUE(std::isnan(math::tan(x))) << x;
  }
  const double largest = std::numeric_limits<double>::max();
  EXPECT_LE(ulpError(math::sin(largest), sinl(largest)), 1.0);
  EXPECT_LE(ulpError(math::cos(-largest), cosl(-largest)), 1.0);
}

TEST(ElementaryTan, WithinOneUlp) {
  const auto tanOf = [](Args a) { return math::tan(a.x); };
  const auto tanRef = [](Args a) { return tanl(a.x); };
  const auto general = [](Rng& r) { return Args{uniform(r, -10.0, 10.0), 0.0}; };
  const auto quarter = [](Rng& r) { return Args{uniform(r, -0.7854, 0.7854), 0.0}; };
  const auto medium = [](Rng& r) { return Args{randomSign(r, logUniform(r, 1e-9, kTwo20)), 0.0}; };
  const auto large = [](Rng& r) { return Args{randomSign(r, logUniform(r, kTwo20, 1e300)), 0.0}; };
  // near the poles: a multiple of pi/2 plus a small offset
  const auto poles = [](Rng& r) {
    return Args{(2.0 * std::floor(uniform(r, -50.0, 50.0)) + 1.0) * 1.5707963267948966 + uniform(r, -1e-6, 1e-6), 0.0};
  };
  EXPECT_LE(sweep("tan", "[-10, 10]", 60000, general, tanOf, tanRef), 1.0);
  EXPECT_LE(sweep("tan", "[-pi/4, pi/4]", 20000, quarter, tanOf, tanRef), 1.0);
  EXPECT_LE(sweep("tan", "+-[1e-9, 2^20] log-uniform", 40000, medium, tanOf, tanRef), 1.0);
  EXPECT_LE(sweep("tan", "+-[2^20, 1e300] log-uniform", 40000, large, tanOf, tanRef), 1.0);
  EXPECT_LE(sweep("tan", "odd multiples of pi/2 +- 1e-6", 20000, poles, tanOf, tanRef), 1.0);
  EXPECT_LE(hardCaseSweep("tan", "hard cases of reduction, >= 2^20", kHardLarge, ourTan, refTan), 1.0);
  EXPECT_LE(hardCaseSweep("tan", "hard cases of reduction, < 2^20", kHardSmall, ourTan, refTan), 1.0);
  EXPECT_TRUE(sameBits(math::tan(0.0), 0.0));
  EXPECT_TRUE(sameBits(math::tan(-0.0), -0.0));
  EXPECT_EQ(math::tan(1e-300), 1e-300);
}

// ---- asin, acos, atan, atan2 ----

TEST(ElementaryInverseTrigonometric, AsinAndAcosWithinOneUlp) {
  const auto asinOf = [](Args a) { return math::asin(a.x); };
  const auto acosOf = [](Args a) { return math::acos(a.x); };
  const auto asinRef = [](Args a) { return asinl(a.x); };
  const auto acosRef = [](Args a) { return acosl(a.x); };
  const auto whole = [](Rng& r) { return Args{uniform(r, -1.0, 1.0), 0.0}; };
  const auto nearOne = [](Rng& r) { return Args{randomSign(r, 1.0 - logUniform(r, 0x1p-53, 0.5)), 0.0}; };
  const auto nearHalf = [](Rng& r) { return Args{randomSign(r, 0.5 + uniform(r, -1e-3, 1e-3)), 0.0}; };
  const auto nearBreak = [](Rng& r) { return Args{randomSign(r, 0.975 + uniform(r, -1e-3, 1e-3)), 0.0}; };
  const auto nearZero = [](Rng& r) { return Args{randomSign(r, logUniform(r, 1e-300, 1e-3)), 0.0}; };
  const struct {
    const char* name;
    std::function<Args(Rng&)> sample;
  } ranges[] = {{"[-1, 1]", whole},
                {"+-(1 - [2^-53, 0.5]) near +-1", nearOne},
                {"+-(0.5 +- 1e-3)", nearHalf},
                {"+-(0.975 +- 1e-3)", nearBreak},
                {"+-[1e-300, 1e-3] log-uniform", nearZero}};
  for (const auto& range : ranges) {
    EXPECT_LE(sweep("asin", range.name, 20000, range.sample, asinOf, asinRef), 1.0);
    EXPECT_LE(sweep("acos", range.name, 20000, range.sample, acosOf, acosRef), 1.0);
  }
}

TEST(ElementaryInverseTrigonometric, AtanWithinOneUlp) {
  const auto atanOf = [](Args a) { return math::atan(a.x); };
  const auto atanRef = [](Args a) { return atanl(a.x); };
  const auto general = [](Rng& r) { return Args{uniform(r, -10.0, 10.0), 0.0}; };
  const auto magnitudes = [](Rng& r) { return Args{randomSign(r, logUniform(r, 1e-300, 1e300)), 0.0}; };
  const auto breakpoints = [](Rng& r) {
    const double breakpoint[] = {0.4375, 0.6875, 1.1875, 2.4375};
    return Args{randomSign(r, breakpoint[r() % 4] * (1.0 + uniform(r, -1e-3, 1e-3))), 0.0};
  };
  EXPECT_LE(sweep("atan", "[-10, 10]", 60000, general, atanOf, atanRef), 1.0);
  EXPECT_LE(sweep("atan", "+-[1e-300, 1e300] log-uniform", 70000, magnitudes, atanOf, atanRef), 1.0);
  EXPECT_LE(sweep("atan", "+-(breakpoints 7/16 .. 39/16) (1 +- 1e-3)", 70000, breakpoints, atanOf, atanRef), 1.0);
}

TEST(ElementaryInverseTrigonometric, Atan2WithinOneUlp) {
  const auto atan2Of = [](Args a) { return math::atan2(a.x, a.y); };  // (x: y of atan2, y: its x)
  const auto atan2Ref = [](Args a) { return atan2l(a.x, a.y); };
  const auto unit = [](Rng& r) { return Args{uniform(r, -1.0, 1.0), uniform(r, -1.0, 1.0)}; };
  const auto magnitudes = [](Rng& r) {
    return Args{randomSign(r, logUniform(r, 1e-300, 1e300)), randomSign(r, logUniform(r, 1e-300, 1e300))};
  };
  const auto breakpoints = [](Rng& r) {  // |y/x| near a breakpoint of atan
    const double breakpoint[] = {0.4375, 0.6875, 1.1875, 2.4375};
    const double x = randomSign(r, logUniform(r, 1e-200, 1e200));
    return Args{randomSign(r, std::fabs(x) * breakpoint[r() % 4] * (1.0 + uniform(r, -1e-3, 1e-3))), x};
  };
  const auto extremeRatios = [](Rng& r) {  // |y/x| about 2^+-(50 .. 70): both sides of the shortcut
    const double x = randomSign(r, logUniform(r, 1e-100, 1e100));
    return Args{randomSign(r, std::fabs(x) * logUniform(r, 0x1p50, 0x1p70) * (r() & 1 ? 1.0 : 0x1p-120)), x};
  };
  const auto subnormal = [](Rng& r) {
    return Args{randomSign(r, logUniform(r, 0x1p-1074, 1e-300)), randomSign(r, logUniform(r, 0x1p-1074, 1e-290))};
  };
  EXPECT_LE(sweep("atan2", "[-1, 1]^2, all quadrants", 50000, unit, atan2Of, atan2Ref), 1.0);
  EXPECT_LE(sweep("atan2", "+-[1e-300, 1e300]^2 log-uniform", 50000, magnitudes, atan2Of, atan2Ref), 1.0);
  EXPECT_LE(sweep("atan2", "|y/x| near 7/16 .. 39/16, all quadrants", 50000, breakpoints, atan2Of, atan2Ref), 1.0);
  EXPECT_LE(sweep("atan2", "|y/x| ~ 2^+-(50 .. 70)", 30000, extremeRatios, atan2Of, atan2Ref), 1.0);
  EXPECT_LE(sweep("atan2", "subnormal and tiny", 20000, subnormal, atan2Of, atan2Ref), 1.0);
}

TEST(ElementaryInverseTrigonometric, SpecialValues) {
  const double pi = 3.141592653589793, halfPi = 1.5707963267948966;
  EXPECT_TRUE(sameBits(math::asin(-0.0), -0.0));
  EXPECT_TRUE(sameBits(math::atan(-0.0), -0.0));
  EXPECT_EQ(math::asin(1.0), halfPi);
  EXPECT_EQ(math::asin(-1.0), -halfPi);
  EXPECT_TRUE(sameBits(math::acos(1.0), 0.0));
  EXPECT_EQ(math::acos(-1.0), pi);
  EXPECT_EQ(math::acos(0.0), halfPi);
  EXPECT_EQ(math::atan(kInf), halfPi);
  EXPECT_EQ(math::atan(-kInf), -halfPi);
  for (double x : {1.0000000000000002, -1.5, kInf, -kInf, std::nan("")}) {
    EXPECT_TRUE(std::isnan(math::asin(x))) << x;
    EXPECT_TRUE(std::isnan(math::acos(x))) << x;
  }
  EXPECT_TRUE(std::isnan(math::atan(std::nan(""))));
  // atan2, C99 F.9.1.4
  EXPECT_TRUE(sameBits(math::atan2(0.0, -0.0), pi));
  EXPECT_TRUE(sameBits(math::atan2(-0.0, -0.0), -pi));
  EXPECT_TRUE(sameBits(math::atan2(0.0, 0.0), 0.0));
  EXPECT_TRUE(sameBits(math::atan2(-0.0, 0.0), -0.0));
  EXPECT_TRUE(sameBits(math::atan2(0.0, -2.0), pi));
  EXPECT_TRUE(sameBits(math::atan2(-0.0, -2.0), -pi));
  EXPECT_TRUE(sameBits(math::atan2(0.0, 2.0), 0.0));
  EXPECT_TRUE(sameBits(math::atan2(-0.0, 2.0), -0.0));
  EXPECT_EQ(math::atan2(-3.0, 0.0), -halfPi);
  EXPECT_EQ(math::atan2(-3.0, -0.0), -halfPi);
  EXPECT_EQ(math::atan2(3.0, 0.0), halfPi);
  EXPECT_EQ(math::atan2(3.0, -0.0), halfPi);
  EXPECT_TRUE(sameBits(math::atan2(3.0, -kInf), pi));
  EXPECT_TRUE(sameBits(math::atan2(-3.0, -kInf), -pi));
  EXPECT_TRUE(sameBits(math::atan2(3.0, kInf), 0.0));
  EXPECT_TRUE(sameBits(math::atan2(-3.0, kInf), -0.0));
  EXPECT_EQ(math::atan2(kInf, 3.0), halfPi);
  EXPECT_EQ(math::atan2(-kInf, -3.0), -halfPi);
  EXPECT_EQ(math::atan2(kInf, -kInf), 3.0 * pi / 4.0);
  EXPECT_EQ(math::atan2(-kInf, -kInf), -3.0 * pi / 4.0);
  EXPECT_EQ(math::atan2(kInf, kInf), pi / 4.0);
  EXPECT_EQ(math::atan2(-kInf, kInf), -pi / 4.0);
  EXPECT_TRUE(std::isnan(math::atan2(std::nan(""), 1.0)));
  EXPECT_TRUE(std::isnan(math::atan2(1.0, std::nan(""))));
  EXPECT_EQ(math::atan2(1.0, 1.0), pi / 4.0);
  EXPECT_EQ(math::atan2(-1.0, -1.0), -3.0 * pi / 4.0);
}

// ---- exp, log, pow ----

TEST(ElementaryExponential, ExpWithinOneUlp) {
  const auto expOf = [](Args a) { return math::exp(a.x); };
  const auto expRef = [](Args a) { return expl(a.x); };
  const auto whole = [](Rng& r) { return Args{uniform(r, -745.2, 709.8), 0.0}; };
  const auto unit = [](Rng& r) { return Args{uniform(r, -1.0, 1.0), 0.0}; };
  const auto small = [](Rng& r) { return Args{randomSign(r, logUniform(r, 1e-300, 1e-3)), 0.0}; };
  const auto subnormal = [](Rng& r) { return Args{uniform(r, -745.2, -708.3), 0.0}; };  // results below 2^-1022
  const auto overflow = [](Rng& r) { return Args{uniform(r, 709.0, 709.8), 0.0}; };
  EXPECT_LE(sweep("exp", "[-745.2, 709.8]", 80000, whole, expOf, expRef), 1.0);
  EXPECT_LE(sweep("exp", "[-1, 1]", 40000, unit, expOf, expRef), 1.0);
  EXPECT_LE(sweep("exp", "+-[1e-300, 1e-3] log-uniform", 20000, small, expOf, expRef), 1.0);
  EXPECT_LE(sweep("exp", "[-745.2, -708.3] (subnormal results)", 40000, subnormal, expOf, expRef), 1.0);
  EXPECT_LE(sweep("exp", "[709, 709.8] (to overflow)", 20000, overflow, expOf, expRef), 1.0);
}

TEST(ElementaryExponential, LogWithinOneUlp) {
  const auto logOf = [](Args a) { return math::log(a.x); };
  const auto logRef = [](Args a) { return logl(a.x); };
  const auto whole = [](Rng& r) { return Args{logUniform(r, 0x1p-1074, 1e308), 0.0}; };
  const auto subnormal = [](Rng& r) { return Args{logUniform(r, 0x1p-1074, 0x1p-1022), 0.0}; };
  const auto nearOne = [](Rng& r) { return Args{1.0 + randomSign(r, logUniform(r, 0x1p-53, 0x1p-6)), 0.0}; };
  const auto octave = [](Rng& r) { return Args{uniform(r, 0.5, 2.0), 0.0}; };
  EXPECT_LE(sweep("log", "(0, 1e308] log-uniform", 80000, whole, logOf, logRef), 1.0);
  EXPECT_LE(sweep("log", "subnormals", 20000, subnormal, logOf, logRef), 1.0);
  EXPECT_LE(sweep("log", "1 +- [2^-53, 2^-6]", 50000, nearOne, logOf, logRef), 1.0);
  EXPECT_LE(sweep("log", "[0.5, 2]", 50000, octave, logOf, logRef), 1.0);
}

TEST(ElementaryExponential, PowWithinOneUlp) {
  const auto powOf = [](Args a) { return math::pow(a.x, a.y); };
  const auto powRef = [](Args a) { return powl(a.x, a.y); };
  const auto solver = [](Rng& r) { return Args{uniform(r, 0.0, 1e3), uniform(r, -10.0, 10.0)}; };
  const auto nearOne = [](Rng& r) {  // x = 1 + d, |y log x| up to 700
    const double d = randomSign(r, logUniform(r, 0x1p-50, 0x1p-6));
    return Args{1.0 + d, randomSign(r, uniform(r, 0.0, 700.0) / std::fabs(d))};
  };
  const auto sundials = [](Rng& r) {  // the step size controller's err^(-1/k)
    return Args{logUniform(r, 1e-10, 1e10), -1.0 / static_cast<double>(1 + r() % 6)};
  };
  const auto extreme = [](Rng& r) {  // y log x in +-[650, 745]: results near overflow or subnormal
    const double x = logUniform(r, 1e-300, 1e300);
    return Args{x, (r() & 1 ? uniform(r, 650.0, 709.7) : uniform(r, -745.0, -650.0)) / std::log(x)};
  };
  const auto subnormalBase = [](Rng& r) { return Args{logUniform(r, 0x1p-1074, 0x1p-1022), uniform(r, -0.95, 1.0)}; };
  const auto negativeBase = [](Rng& r) {
    return Args{-logUniform(r, 1e-3, 1e3), std::floor(uniform(r, -60.0, 60.0))};
  };
  EXPECT_LE(sweep("pow", "x in (0, 1e3], y in [-10, 10]", 60000, solver, powOf, powRef), 1.0);
  EXPECT_LE(sweep("pow", "x = 1 + d, |y log x| <= 700", 40000, nearOne, powOf, powRef), 1.0);
  EXPECT_LE(sweep("pow", "err^(-1/k), err in [1e-10, 1e10], k 1..6", 30000, sundials, powOf, powRef), 1.0);
  EXPECT_LE(sweep("pow", "|y log x| in [650, 745]", 50000, extreme, powOf, powRef), 1.0);
  EXPECT_LE(sweep("pow", "x subnormal, y in [-0.95, 1]", 10000, subnormalBase, powOf, powRef), 1.0);
  EXPECT_LE(sweep("pow", "x in -[1e-3, 1e3], integer y in [-60, 60]", 10000, negativeBase, powOf, powRef), 1.0);
}

TEST(ElementaryExponential, SpecialValues) {
  EXPECT_EQ(math::exp(0.0), 1.0);
  EXPECT_EQ(math::exp(-0.0), 1.0);
  EXPECT_EQ(math::exp(kInf), kInf);
  EXPECT_TRUE(sameBits(math::exp(-kInf), 0.0));
  EXPECT_TRUE(std::isnan(math::exp(std::nan(""))));
  EXPECT_EQ(math::exp(709.79), kInf);
  EXPECT_LE(ulpError(math::exp(7.09782712893383973096e+02), expl(7.09782712893383973096e+02L)), 1.0);  // last finite
  EXPECT_EQ(math::exp(-7.45133219101941108420e+02), 0x1p-1074);  // the last nonzero
  EXPECT_TRUE(sameBits(math::exp(-745.14), 0.0));
  EXPECT_EQ(math::exp(1e-300), 1.0);
  EXPECT_TRUE(sameBits(math::log(1.0), 0.0));
  EXPECT_EQ(math::log(0.0), -kInf);
  EXPECT_EQ(math::log(-0.0), -kInf);
  EXPECT_EQ(math::log(kInf), kInf);
  EXPECT_TRUE(std::isnan(math::log(-1.0)));
  EXPECT_TRUE(std::isnan(math::log(-kInf)));
  EXPECT_TRUE(std::isnan(math::log(std::nan(""))));
  EXPECT_LE(ulpError(math::log(0x1p-1074), logl(0x1p-1074L)), 1.0);
  EXPECT_LE(ulpError(math::log(std::numeric_limits<double>::max()), logl(std::numeric_limits<double>::max())), 1.0);
}

TEST(ElementaryExponential, PowOfZerosInfinitiesAndNaNsAsInAnnexF) {
  const double nan = std::nan("");
  // pow(x, +-0) = 1 for any x, even NaN; pow(+1, y) = 1 for any y, even NaN
  for (double x : {0.0, -0.0, 2.0, -3.0, kInf, -kInf, nan}) {
    EXPECT_EQ(math::pow(x, 0.0), 1.0) << x;
    EXPECT_EQ(math::pow(x, -0.0), 1.0) << x;
  }
  for (double y : {0.5, -7.0, kInf, -kInf, nan}) EXPECT_EQ(math::pow(1.0, y), 1.0) << y;
  EXPECT_TRUE(std::isnan(math::pow(nan, 2.5)));
  EXPECT_TRUE(std::isnan(math::pow(2.5, nan)));
  // zeros
  EXPECT_TRUE(sameBits(math::pow(-0.0, -3.0), -kInf));
  EXPECT_TRUE(sameBits(math::pow(0.0, -3.0), kInf));
  EXPECT_TRUE(sameBits(math::pow(-0.0, -2.0), kInf));
  EXPECT_TRUE(sameBits(math::pow(-0.0, -0.5), kInf));
  EXPECT_TRUE(sameBits(math::pow(-0.0, -kInf), kInf));
  EXPECT_TRUE(sameBits(math::pow(-0.0, 3.0), -0.0));
  EXPECT_TRUE(sameBits(math::pow(0.0, 3.0), 0.0));
  EXPECT_TRUE(sameBits(math::pow(-0.0, 4.0), 0.0));
  EXPECT_TRUE(sameBits(math::pow(-0.0, 0.5), 0.0));
  EXPECT_TRUE(sameBits(math::pow(-0.0, kInf), 0.0));
  // infinite exponents
  EXPECT_EQ(math::pow(-1.0, kInf), 1.0);
  EXPECT_EQ(math::pow(-1.0, -kInf), 1.0);
  EXPECT_EQ(math::pow(0.5, -kInf), kInf);
  EXPECT_EQ(math::pow(-0.5, -kInf), kInf);
  EXPECT_TRUE(sameBits(math::pow(3.0, -kInf), 0.0));
  EXPECT_TRUE(sameBits(math::pow(-0.5, kInf), 0.0));
  EXPECT_EQ(math::pow(-3.0, kInf), kInf);
  // infinite bases
  EXPECT_TRUE(sameBits(math::pow(-kInf, -3.0), -0.0));
  EXPECT_TRUE(sameBits(math::pow(-kInf, -2.0), 0.0));
  EXPECT_TRUE(sameBits(math::pow(-kInf, -0.5), 0.0));
  EXPECT_TRUE(sameBits(math::pow(-kInf, 3.0), -kInf));
  EXPECT_TRUE(sameBits(math::pow(-kInf, 2.0), kInf));
  EXPECT_TRUE(sameBits(math::pow(-kInf, 0.5), kInf));
  EXPECT_TRUE(sameBits(math::pow(kInf, -0.5), 0.0));
  EXPECT_EQ(math::pow(kInf, 0.5), kInf);
}

TEST(ElementaryExponential, PowOfNegativeBasesOverflowAndExactResults) {
  EXPECT_TRUE(std::isnan(math::pow(-2.0, 0.5)));
  EXPECT_EQ(math::pow(-2.0, 3.0), -8.0);
  EXPECT_EQ(math::pow(-2.0, 4.0), 16.0);
  EXPECT_EQ(math::pow(-2.0, -3.0), -0.125);
  EXPECT_EQ(math::pow(-2.0, 0x1p60), kInf);  // even (beyond 2^53 every double is)
  EXPECT_EQ(math::pow(-1.0, 0x1p53 + 2.0), 1.0);
  EXPECT_EQ(math::pow(-1.0, 0x1p52 + 1.0), -1.0);  // odd
  EXPECT_EQ(math::pow(-1.0, 1e300), 1.0);
  EXPECT_EQ(math::pow(-1.0, -1e300), 1.0);
  EXPECT_EQ(math::pow(-3.0, 1e300), kInf);
  EXPECT_TRUE(sameBits(math::pow(-3.0, -1e300), 0.0));
  // overflow, underflow, exact results
  EXPECT_EQ(math::pow(10.0, 400.0), kInf);
  EXPECT_EQ(math::pow(-10.0, 401.0), -kInf);
  EXPECT_TRUE(sameBits(math::pow(10.0, -400.0), 0.0));
  EXPECT_TRUE(sameBits(math::pow(-10.0, -401.0), -0.0));
  EXPECT_EQ(math::pow(2.0, -1074.0), 0x1p-1074);
  EXPECT_EQ(math::pow(2.0, 1023.0), 0x1p1023);
  EXPECT_EQ(math::pow(2.0, 10.0), 1024.0);
  EXPECT_EQ(math::pow(10.0, 22.0), 1e22);
  EXPECT_EQ(math::pow(9.0, 0.5), 3.0);
  EXPECT_EQ(math::pow(1.0000000000000002, 0x1p70), kInf);
  EXPECT_EQ(math::pow(0.9999999999999999, 0x1p70), 0.0);
  EXPECT_TRUE(sameBits(chaindrive_pow(-0.0, 3.0), -0.0));
  EXPECT_TRUE(sameBits(chaindrive_pow(1.7, 3.3), math::pow(1.7, 3.3)));
}

// ---- cbrt ----

TEST(ElementaryCbrt, WithinOneUlp) {
  const auto cbrtOf = [](Args a) { return math::cbrt(a.x); };
  const auto cbrtRef = [](Args a) { return cbrtl(a.x); };
  const auto whole = [](Rng& r) { return Args{randomSign(r, logUniform(r, 1e-310, 1e300)), 0.0}; };
  const auto subnormal = [](Rng& r) { return Args{randomSign(r, logUniform(r, 0x1p-1074, 0x1p-1022)), 0.0}; };
  const auto unit = [](Rng& r) { return Args{uniform(r, -8.0, 8.0), 0.0}; };
  EXPECT_LE(sweep("cbrt", "+-[1e-310, 1e300] log-uniform", 100000, whole, cbrtOf, cbrtRef), 1.0);
  EXPECT_LE(sweep("cbrt", "subnormals", 30000, subnormal, cbrtOf, cbrtRef), 1.0);
  EXPECT_LE(sweep("cbrt", "[-8, 8]", 70000, unit, cbrtOf, cbrtRef), 1.0);
  EXPECT_TRUE(sameBits(math::cbrt(0.0), 0.0));
  EXPECT_TRUE(sameBits(math::cbrt(-0.0), -0.0));
  EXPECT_EQ(math::cbrt(kInf), kInf);
  EXPECT_EQ(math::cbrt(-kInf), -kInf);
  EXPECT_TRUE(std::isnan(math::cbrt(std::nan(""))));
  EXPECT_EQ(math::cbrt(27.0), 3.0);
  EXPECT_EQ(math::cbrt(-8.0), -2.0);
  EXPECT_EQ(math::cbrt(0x1p-1074), 0x1p-358);
}

}  // namespace
}  // namespace chaindrive
