// Geometry of the controlling elements: the closest-point query of a sprocket's tooth gap
// against a dense polyline of its outline.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "test_util.h"

using namespace chaindrive;
using namespace chaindrive::test;

TEST(Geometry, ToothGapClosestPointMatchesADenseOutline) {
  const Model m = assemble(defaultDriveDescription());
  const ToothGap& g = m.sprockets[0].gap;
  const std::vector<Vec2> outline = g.outline(400);
  // points in gap 0's region, inside the free space
  int n = 0;
  for (double r = g.pitchRadius - 2.0e-3; r < g.tipRadius + 2e-3; r += 2.5e-4)
    for (double a = -0.9 * kPi / g.teeth; a <= 0.9 * kPi / g.teeth; a += 0.02 * kPi / g.teeth) {
      const Vec2 p = r * unit(a);
      const ProfileHit h = g.closest(p);
      double best = 1e300;
      for (std::size_t k = 0; k + 1 < outline.size(); ++k) {
        const Vec2 s0 = outline[k], s1 = outline[k + 1];
        const Vec2 d = s1 - s0;
        double t = dot(p - s0, d) / std::max(norm2(d), 1e-300);
        t = std::min(1.0, std::max(0.0, t));
        best = std::min(best, norm(p - (s0 + t * d)));
      }
      // tolerance: the outline polyline has 400 points per arc (chord error < 1e-8 m)
      EXPECT_NEAR(h.distance, best, 2e-8) << "at r=" << r << " a=" << a;
      EXPECT_NEAR(norm(h.normal), 1.0, 1e-12);
      ++n;
    }
  EXPECT_GT(n, 500);
}
