// The span model's assembly: spans of the default drive, the guide table against the path
// geometry, the polygonal chain passage, description errors naming the field.
#include "span/span_model.h"

#include <cmath>

#include <gtest/gtest.h>

#include "test_util.h"

namespace chaindrive::span {
namespace {

using test::defaultModel;

TEST(SpanModel, DefaultDriveHasThreeSpansBetweenItsSprockets) {
  const SpanModel sm = assembleSpanModel(*defaultModel());
  ASSERT_EQ(sm.spans.size(), 3u);
  EXPECT_EQ(sm.spans[0].name, "crankshaft->camshaftExhaust");
  EXPECT_EQ(sm.spans[1].name, "camshaftExhaust->camshaftIntake");
  EXPECT_EQ(sm.spans[2].name, "camshaftIntake->crankshaft");
  EXPECT_EQ(sm.spans[0].table, 0);       // the tension guide
  EXPECT_EQ(sm.spans[2].table, -1);      // the fixed guide: no table
  EXPECT_EQ(sm.spans[2].wraps.size(), 1u);
  // series stiffness: the joint stiffness over the links the span holds
  for (const Span& s : sm.spans) EXPECT_NEAR(s.stiffness * s.links, defaultModel()->chain.jointStiffness, 1e-3);
}

// Without friction the torque on the guide is the virtual work of the span's tension:
// torque = -T dl/dpsi, so torqueIn + torqueOut = -slope at every node.
TEST(SpanModel, GuideTorqueIsTheVirtualWorkOfTheSpanLength) {
  const SpanModel sm = assembleSpanModel(*defaultModel());
  const GuideTable& t = sm.tables.at(0);
  ASSERT_GT(t.length.size(), 100u);
  for (std::size_t i = 0; i < t.length.size(); i += 20) {
    EXPECT_NEAR(t.torqueIn[i] + t.torqueOut[i], -t.slope[i], 1e-6 * std::fabs(t.slope[i]) + 1e-9) << "node " << i;
  }
}

// One pitch of chain per tooth; the effective radius R cos(theta_rel) within the pitch.
TEST(SpanModel, ChainPassedIsOnePitchPerToothWithThePolygonalRadius) {
  SpanEnd e;
  e.radius = 0.03;
  e.toothAngle = 2.0 * kPi / 21.0;
  e.pitch = 2.0 * e.radius * std::sin(kPi / 21.0);
  e.phase = 0.05;
  e.passedAtPhase = e.radius * std::sin(e.phase);
  double r = 0.0;
  EXPECT_NEAR(chainPassed(e, 0.0, r), 0.0, 1e-15);
  EXPECT_NEAR(chainPassed(e, 5.0 * e.toothAngle, r), 5.0 * e.pitch, 1e-14);
  double rMin = 1e9, rMax = 0.0;
  for (int k = 0; k < 1000; ++k) {
    chainPassed(e, k * e.toothAngle / 1000.0, r);
    rMin = std::min(rMin, r);
    rMax = std::max(rMax, r);
  }
  EXPECT_NEAR(rMin / rMax, std::cos(kPi / 21.0), 1e-5);
}
}  // namespace
}  // namespace chaindrive::span
