// The span model's damping fitted to the link model's camshafts' mode (run/span_damping.h) on the
// default drive with its seat: the span model's mode then decays as the link model's, and the
// cache gives the same scale to the bit.
#include "run/span_damping.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include <gtest/gtest.h>

#include "span/calibration_cache.h"
#include "test_util.h"

namespace chaindrive {
namespace {

TEST(SpanDamping, TheSpanModelsModeDecaysAsTheLinkModelsAndTheCacheKeepsTheBits) {
  const auto m = std::make_shared<const Model>(assemble(test::modifiedDefault([](nlohmann::json& j) {
    j["spanModel"] = {{"guideSeat", "identified"}, {"damping", "identified"}};
  })));
  span::SpanModel sm = span::assembleSpanModel(*m);
  const SpanDampingCalibration c = identifySpanDamping(m, sm);
  ASSERT_TRUE(c.identified) << c.note;
  EXPECT_GT(c.link.coherent, 0.5);  // the pairs' mean holds the mode, not the chaos
  EXPECT_FALSE(c.link.mode.atBound);
  EXPECT_GT(c.link.mode.dampingRatio, c.spanBefore.mode.dampingRatio);  // what the calibration is for
  EXPECT_GT(c.scale, 1.0);
  EXPECT_NEAR(c.span.mode.dampingRatio, c.link.mode.dampingRatio, 0.02 * c.link.mode.dampingRatio);
  EXPECT_NEAR(c.span.mode.frequency, c.link.mode.frequency, 0.1 * c.link.mode.frequency);

  // through the cache: identified once, then read with the same bits
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "chaindrive-span-damping-test";
  std::filesystem::remove_all(dir);
  const char* before = std::getenv("CHAINDRIVE_CACHE_DIR");
  const std::string saved = before ? before : "";
  ASSERT_EQ(setenv("CHAINDRIVE_CACHE_DIR", dir.string().c_str(), 1), 0);
  span::SpanModel first = sm, second = sm;
  const SpanDampingCalibration a = calibrateSpanDamping(m, first), b = calibrateSpanDamping(m, second);
  if (before) setenv("CHAINDRIVE_CACHE_DIR", saved.c_str(), 1);
  else unsetenv("CHAINDRIVE_CACHE_DIR");
  EXPECT_EQ(a.scale, c.scale);  // (the identification is deterministic)
  EXPECT_EQ(b.scale, a.scale);
  EXPECT_EQ(first.spans[0].damping, second.spans[0].damping);
  EXPECT_EQ(second.dampingScale, c.scale);
  EXPECT_NE(second.notes.back().find("from the cache"), std::string::npos);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace chaindrive
