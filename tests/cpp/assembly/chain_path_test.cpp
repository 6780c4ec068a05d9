// The chain path: common tangents of oriented circles, the taut closed path through the route
// (arcs joined by tangent spans), and the pins inscribed in it with chords of one pitch.
// Tolerances: coordinates are below 0.5 m and each value passes through a few trigonometric
// functions, so rounding stays below 1e-15 m; 1e-12 m is far above that and far below any real
// error (a wrong tangent or a missing arc is off by millimetres).
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "test_util.h"

using namespace chaindrive;
using namespace chaindrive::test;

namespace {

constexpr double kTol = 1e-12;  // [m], see above

// Distance of p from the circle (centre c, radius |r|).
double offCircle(Vec2 p, Vec2 c, double r) { return std::fabs(norm(p - c) - std::fabs(r)); }

}  // namespace

TEST(ChainPath, TwoEqualCirclesMakeAStadium) {
  const double r = 0.05, dist = 0.2;
  const ChainPath path = ChainPath::through({RouteCircle{{0.0, 0.0}, r}, RouteCircle{{dist, 0.0}, r}});
  // two half circles and two straight spans of the centre distance
  EXPECT_NEAR(path.length(), 2.0 * kPi * r + 2.0 * dist, kTol);
  ASSERT_EQ(path.segments().size(), 4u);
  EXPECT_NEAR(std::fabs(path.segments()[0].sweep), kPi, 1e-14);
  EXPECT_NEAR(path.segments()[1].length, dist, kTol);
  // counterclockwise around both: the span leaving the first circle runs along its bottom, in +x
  EXPECT_NEAR(path.segments()[1].from.y, -r, kTol);
  EXPECT_GT(path.tangent(path.segments()[1].start + 0.5 * dist).x, 0.0);
}

TEST(ChainPath, CommonTangentTouchesBothCirclesAtRightAngles) {
  const RouteCircle a{{0.01, -0.02}, 0.03};
  // outer tangent (same sense), crossed tangent (opposite senses), and both the other way round
  for (const RouteCircle& b : {RouteCircle{{0.25, 0.1}, 0.06}, RouteCircle{{0.25, 0.1}, -0.06}}) {
    for (const bool forward : {true, false}) {
      const RouteCircle& c1 = forward ? a : b;
      const RouteCircle& c2 = forward ? b : a;
      Vec2 m;
      ASSERT_TRUE(commonTangent(c1, c2, m));
      EXPECT_NEAR(norm(m), 1.0, 1e-15);
      const Vec2 t1 = c1.center + c1.signedRadius * m, t2 = c2.center + c2.signedRadius * m;
      // the span t1 -> t2 is perpendicular to both radii (m) and runs in the direction perp(m)
      EXPECT_NEAR(dot(t2 - t1, m), 0.0, kTol);
      EXPECT_GT(dot(t2 - t1, perp(m)), 0.0);
    }
  }
}

TEST(ChainPath, NoPathThroughOverlappingCirclesOrASingleOne) {
  Vec2 m;
  // crossed tangents need the centres farther apart than the sum of the radii
  EXPECT_FALSE(commonTangent(RouteCircle{{0.0, 0.0}, 0.05}, RouteCircle{{0.08, 0.0}, -0.05}, m));
  EXPECT_FALSE(commonTangent(RouteCircle{{0.0, 0.0}, 0.05}, RouteCircle{{0.0, 0.0}, 0.02}, m));
  EXPECT_THROW(ChainPath::through({RouteCircle{{0.0, 0.0}, 0.05}, RouteCircle{{0.08, 0.0}, -0.05}}),
               std::invalid_argument);
  EXPECT_THROW(ChainPath::through({RouteCircle{{0.0, 0.0}, 0.05}}), std::invalid_argument);
}

TEST(ChainPath, SegmentsOfTheDefaultDriveJoinTangentially) {
  const ChainPath& path = defaultModel()->path;
  const auto& segs = path.segments();
  ASSERT_EQ(segs.size(), 2 * defaultModel()->description.chain.route.size());
  double total = 0.0;
  for (std::size_t k = 0; k < segs.size(); ++k) {
    const PathSegment& s = segs[k];
    const PathSegment& next = segs[(k + 1) % segs.size()];
    EXPECT_NEAR(s.start, total, kTol) << "segment " << k;
    total += s.length;
    // each segment ends where the next begins
    EXPECT_LT(norm(next.from - s.to), kTol) << "segment " << k;
    if (s.isArc) {
      // the ends of an arc lie on its circle; its length is radius times sweep
      EXPECT_LT(offCircle(s.from, s.center, s.signedRadius), kTol) << "arc " << k;
      EXPECT_LT(offCircle(s.to, s.center, s.signedRadius), kTol) << "arc " << k;
      EXPECT_NEAR(s.length, std::fabs(s.signedRadius * s.sweep), kTol) << "arc " << k;
    } else {
      // a span is tangent to the arcs at both its ends: perpendicular to their radii
      const PathSegment& before = segs[k - 1];
      const Vec2 dir = (1.0 / s.length) * (s.to - s.from);
      EXPECT_NEAR(dot(dir, s.from - before.center), 0.0, kTol) << "span " << k;
      EXPECT_NEAR(dot(dir, s.to - next.center), 0.0, kTol) << "span " << k;
    }
  }
  EXPECT_NEAR(path.length(), total, kTol);
}

TEST(ChainPath, TangentIsTheDerivativeOfThePoint) {
  const ChainPath& path = defaultModel()->path;
  // central differences with h = 1 um: truncation h^2 / (6 r^2) < 1e-9, rounding 1e-16 m / h < 1e-9
  const double h = 1e-6;
  for (const PathSegment& s : path.segments()) {
    const double mid = s.start + 0.5 * s.length;
    const Vec2 fd = (1.0 / (2.0 * h)) * (path.point(mid + h) - path.point(mid - h));
    EXPECT_LT(norm(fd - path.tangent(mid)), 1e-8) << "at s = " << mid;
    EXPECT_NEAR(norm(path.tangent(mid)), 1.0, 1e-15);
  }
}

TEST(ChainPath, NextPinIsOnePitchAwayAlongThePath) {
  const Model& m = *defaultModel();
  const double p = m.chain.pitch;
  // across the whole path, including chords that span an arc/span junction; the root search
  // stops at 1e-15 m of arc length, the fast paths are exact up to rounding
  const int samples = 997;
  for (int k = 0; k < samples; ++k) {
    const double s = m.path.length() * k / samples;
    const double next = m.path.nextPin(s, p);
    EXPECT_NEAR(norm(m.path.point(next) - m.path.point(s)), p, kTol) << "from s = " << s;
    // a chord is never longer than the path it spans, nor shorter than 0.6 of it here
    EXPECT_GE(next - s, p * (1.0 - 1e-12)) << "from s = " << s;
    EXPECT_LT(next - s, 1.6 * p) << "from s = " << s;
  }
}

TEST(ChainPath, TheDefaultChainClosesOnItsPath) {
  const Model& m = *defaultModel();
  const int n = m.chain.links;
  const double p = m.chain.pitch;
  // n chords of one pitch from the middle of the first wrap come back to the start: the arc
  // length walked equals the path length, and the chords' total is n p. Tolerance 1e-9 m: the
  // closure solve stops at a gap of 1e-14 m and each pin's root search adds at most ~1e-15 m.
  const double s0 = m.path.arcMiddle(0);
  double s = s0, chords = 0.0;
  for (int k = 0; k < n; ++k) {
    const double next = m.path.nextPin(s, p);
    chords += norm(m.path.point(next) - m.path.point(s));
    s = next;
  }
  EXPECT_NEAR(s - s0, m.path.length(), 1e-9);
  EXPECT_LT(norm(m.path.point(s) - m.path.point(s0)), 1e-9);
  EXPECT_NEAR(chords, n * p, 1e-9);
  // the path is longer than the pin polygon (arcs are longer than their chords), but by less than
  // one pitch
  EXPECT_GT(m.path.length(), n * p + 1e-6);
  EXPECT_LT(m.path.length(), (n + 1) * p);
}

TEST(ChainPath, ArcMiddlesLieOnTheirCircles) {
  const ChainPath& path = defaultModel()->path;
  const auto& segs = path.segments();
  for (std::size_t r = 0; r < segs.size() / 2; ++r) {
    const PathSegment& arc = segs[2 * r];
    const double mid = path.arcMiddle(static_cast<int>(r));
    EXPECT_EQ(path.segmentAt(mid), static_cast<int>(2 * r));
    EXPECT_LT(offCircle(path.point(mid), arc.center, arc.signedRadius), kTol) << "route element " << r;
  }
}
