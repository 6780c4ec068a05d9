// Verlet's stable step on one damped mode and the divisions of the communication step
// (src/integrators/stable_step.h).
#include <gtest/gtest.h>

#include <cmath>

#include "integrators/stable_step.h"

using namespace chaindrive;

namespace {

// The largest |x| over 2000 steps of velocity Verlet (kick, drift, kick; the force, damping
// included, evaluated at the half-step velocity as the schemes do) on x'' = -w^2 x - r x' from x = 1.
double verletAmplitude(double w, double r, double h) {
  double x = 1.0, v = 0.0, a = -w * w * x;
  double largest = 1.0;
  for (int k = 0; k < 2000; ++k) {
    const double vHalf = v + 0.5 * h * a;
    x += h * vHalf;
    a = -w * w * x - r * vHalf;
    v = vHalf + 0.5 * h * a;
    largest = std::fmax(largest, std::fabs(x));
  }
  return largest;
}

}  // namespace

// Undamped 2 / omega; the explicit damping shortens it, and the scheme's amplitude stays bounded
// just inside the step and grows without bound just outside (to 2 % on either side).
TEST(StableStep, VerletsLimitWithExplicitDamping) {
  const double w = 4.9e5;
  EXPECT_DOUBLE_EQ(verletStableStep(w, 0.0), 2.0 / w);
  for (const double zeta : {0.0, 0.1, 0.3, 0.6}) {
    const double r = 2.0 * zeta * w, h = verletStableStep(w, r);
    EXPECT_NEAR(h * w, 2.0 * (std::sqrt(1.0 + zeta * zeta) - zeta), 1e-14);
    EXPECT_LT(verletAmplitude(w, r, 0.98 * h), 10.0) << "zeta " << zeta;
    EXPECT_GT(verletAmplitude(w, r, 1.02 * h), 1e3) << "zeta " << zeta;
  }
  EXPECT_LT(verletStableStep(w, 1e5), verletStableStep(w, 0.0));
}

// The shortest division within the limit: exact divisions are themselves, a limit a rounding
// above or below one lands on it, anything clearly below takes the next.
TEST(StableStep, DivisionsOfTheCommunicationStep) {
  EXPECT_EQ(divisionsWithin(1e-4, 1e-4 / 28), 28);
  EXPECT_EQ(divisionsWithin(1e-4, 1e-4 / 28 * (1.0 + 1e-14)), 28);
  EXPECT_EQ(divisionsWithin(1e-4, 1e-4 / 28 * (1.0 - 1e-14)), 28);
  EXPECT_EQ(divisionsWithin(1e-4, 1e-4 / 28 * (1.0 - 1e-9)), 29);
  EXPECT_EQ(divisionsWithin(1e-4, 3.5e-6), 29);   // 1e-4 / 28 = 3.571 us is above 3.5 us
  EXPECT_EQ(divisionsWithin(1e-4, 2.5e-6), 40);
  EXPECT_EQ(divisionsWithin(1e-4, 4e-4), 1);      // never less than one step
  EXPECT_LE(1e-4 / static_cast<double>(divisionsWithin(1e-4, 2.7e-6)), 2.7e-6);
  EXPECT_GT(1e-4 / static_cast<double>(divisionsWithin(1e-4, 2.7e-6) - 1), 2.7e-6);
}
