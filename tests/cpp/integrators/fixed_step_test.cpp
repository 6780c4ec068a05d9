#include "integrators/fixed_step.h"

#include <gtest/gtest.h>

#include <random>
#include <utility>
#include <vector>

namespace chaindrive {
namespace {

using Items = std::vector<std::pair<int, int>>;

Items visited(const ComponentSet& set) {
  Items out;
  set.forEach([&](int i, int partner) { out.push_back({i, partner - i}); });
  return out;
}

// A drive's layout: bodies of (x, y, angle, vx, vy, w), then rotors' angle and rate pairs,
// prescribed angles and accumulators.
TEST(ComponentSet, VisitsAMultibodyStateInOrderWithItsPartners) {
  Items positions, velocities, others;
  for (int b = 0; b < 120; ++b)
    for (int c = 0; c < 3; ++c) {
      positions.push_back({6 * b + c, 3});
      velocities.push_back({6 * b + 3 + c, 0});
    }
  positions.push_back({720, 1});
  velocities.push_back({721, 0});
  others.push_back({722, 0});
  positions.push_back({723, 1});
  velocities.push_back({724, 0});
  others.push_back({725, 0});
  others.push_back({726, 0});
  for (const Items& items : {positions, velocities, others, Items{}}) EXPECT_EQ(visited(ComponentSet(items)), items);
}

// Any increasing set of components with any offsets: the same components, order and partners.
TEST(ComponentSet, VisitsAnyIncreasingSetAsAnIndexListWould) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 2000; ++trial) {
    Items items;
    const int n = static_cast<int>(rng() % 60);
    const int offsets = 1 + static_cast<int>(rng() % 3);
    for (int i = 0; i < n; ++i)
      if (rng() % 4 != 0) items.push_back({i, static_cast<int>(rng() % offsets)});
    ASSERT_EQ(visited(ComponentSet(items)), items) << "trial " << trial;
  }
}

}  // namespace
}  // namespace chaindrive
