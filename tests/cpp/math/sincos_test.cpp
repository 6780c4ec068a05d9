#include "math/sincos.h"
#include "math/vec2.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

namespace chaindrive {
namespace {

// distance in units in the last place of the reference
double ulps(double value, double reference) {
  const double ulp = std::nextafter(std::fabs(reference), INFINITY) - std::fabs(reference);
  return std::fabs(value - reference) / ulp;
}

TEST(SinCos, WithinTwoUlpOfLibmOverTheRangeOfLinkAngles) {
  std::mt19937_64 rng(7);
  for (double range : {1.0, 10.0, 1e3, 1e6}) {
    std::uniform_real_distribution<double> angle(-range, range);
    double worstSin = 0.0, worstCos = 0.0;
    for (int i = 0; i < 200000; ++i) {
      const double x = angle(rng);
      double s = 0.0, c = 0.0;
      sinCos(x, s, c);
      worstSin = std::max(worstSin, ulps(s, std::sin(x)));
      worstCos = std::max(worstCos, ulps(c, std::cos(x)));
    }
    EXPECT_LE(worstSin, 2.0) << "range " << range;
    EXPECT_LE(worstCos, 2.0) << "range " << range;
  }
}

TEST(SinCos, QuadrantsAndSpecialValues) {
  for (int k = -8; k <= 8; ++k) {
    double s = 0.0, c = 0.0;
    sinCos(k * 0.5 * kPi, s, c);
    EXPECT_NEAR(s, std::sin(k * 0.5 * kPi), 1e-15) << k;
    EXPECT_NEAR(c, std::cos(k * 0.5 * kPi), 1e-15) << k;
  }
  double s = 1.0, c = 1.0;
  sinCos(0.0, s, c);
  EXPECT_EQ(s, 0.0);
  EXPECT_EQ(c, 1.0);
  sinCos(std::nan(""), s, c);
  EXPECT_TRUE(std::isnan(s) && std::isnan(c));
  sinCos(INFINITY, s, c);
  EXPECT_TRUE(std::isnan(s) && std::isnan(c));
}

// Beyond the reduction's range (2^20), math::sin and math::cos (Payne-Hanek reduction): within
// 1 ulp of the exact value (glibc's long double functions), the same for a pair of angles.
TEST(SinCos, WithinOneUlpBeyondTwoToTheTwenty) {
  const auto ulpsOfExact = [](double value, long double exact) {
    int exponent = 0;
    frexpl(exact, &exponent);
    return static_cast<double>(fabsl(value - exact) / ldexpl(1.0L, exponent - 53));
  };
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> binade(20.0, 1000.0);
  double worstSin = 0.0, worstCos = 0.0;
  for (int i = 0; i < 20000; ++i) {
    const double x = (i % 2 ? -1.0 : 1.0) * std::exp2(binade(rng));
    double s = 0.0, c = 0.0;
    sinCos(x, s, c);
    worstSin = std::max(worstSin, ulpsOfExact(s, sinl(x)));
    worstCos = std::max(worstCos, ulpsOfExact(c, cosl(x)));
  }
  EXPECT_LE(worstSin, 1.0);
  EXPECT_LE(worstCos, 1.0);
  double s = 0.0, c = 0.0;
  sinCos(1e9, s, c);
  EXPECT_LE(ulpsOfExact(s, sinl(1e9L)), 1.0);
  EXPECT_LE(ulpsOfExact(c, cosl(1e9L)), 1.0);
}

// The paired version must give the scalar one's bits in both lanes, in every quadrant, for
// angles of either sign, at the quadrant boundaries, and for the lanes that fall back to math::sin
// (large angles, NaN, infinities) next to a lane that does not.
TEST(SinCos, PairsGiveTheBitsOfSingleAngles) {
  std::mt19937_64 rng(11);
  std::vector<double> angles = {0.0, -0.0, 0.25 * kPi, -0.25 * kPi, 0.5 * kPi, kPi, -kPi, 1.5 * kPi, 1048575.9,
                                -1048575.9, 1048576.0, 1e9, -1e300, std::nan(""), INFINITY, -INFINITY};
  for (double range : {1.0, 10.0, 1e3, 1e6}) {
    std::uniform_real_distribution<double> angle(-range, range);
    for (int i = 0; i < 50000; ++i) angles.push_back(angle(rng));
  }
  const auto sameBits = [](double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; };
  for (std::size_t i = 0; i + 1 < angles.size(); ++i) {
    const double pair[2] = {angles[i], angles[i + 1]};
    double sine[2], cosine[2];
    sinCos2(pair, sine, cosine);
    for (int lane = 0; lane < 2; ++lane) {
      double s = 0.0, c = 0.0;
      sinCos(pair[lane], s, c);
      ASSERT_TRUE(sameBits(sine[lane], s)) << "sin of " << pair[lane] << ": " << sine[lane] << " vs " << s;
      ASSERT_TRUE(sameBits(cosine[lane], c)) << "cos of " << pair[lane] << ": " << cosine[lane] << " vs " << c;
    }
  }
}

}  // namespace
}  // namespace chaindrive
