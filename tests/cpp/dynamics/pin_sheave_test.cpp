#include "dynamics/pin_sheave.h"

#include <cmath>

#include <gtest/gtest.h>

using namespace chaindrive;

namespace {

PinSheaveLaw law() {
  PinSheaveLaw l;
  const double beta = 11.0 * 3.14159265358979323846 / 180.0;
  l.tanWedge = std::tan(beta);
  l.cosWedge = std::cos(beta);
  l.axialStiffness = 1e8;
  l.axialDamping = 1000.0;
  l.friction = 0.09;
  return l;
}

}  // namespace

TEST(PinSheave, WedgeTurnsTheRadialDepthIntoAxialForce) {
  const PinSheaveLaw l = law();
  const double depth = 2e-5;
  const PinSheaveForce f = pinSheaveForce(l, 0.02, depth, 0.0, 0.0);
  EXPECT_DOUBLE_EQ(f.axial, l.axialStiffness * 2.0 * l.tanWedge * depth);
  EXPECT_DOUBLE_EQ(f.normal, 2.0 * l.tanWedge * f.axial);
  EXPECT_EQ(f.frictionRadial, 0.0);
  EXPECT_EQ(f.frictionCircumferential, 0.0);
  EXPECT_NEAR(f.energy, 0.5 * f.axial * 2.0 * l.tanWedge * depth, 1e-18);
}

TEST(PinSheave, FrictionOpposesSlidingInBothDirectionsWithinTheCone) {
  const PinSheaveLaw l = law();
  const double depth = 2e-5, vr = -0.3, vt = 0.4;  // sliding inwards and forwards, far beyond vReg
  const PinSheaveForce f = pinSheaveForce(l, 1e-3, depth, vr, vt);
  const double limit = 2.0 * l.friction * f.axial / l.cosWedge;
  const double magnitude = std::hypot(f.frictionRadial, f.frictionCircumferential);
  EXPECT_LE(magnitude, limit);
  EXPECT_GT(magnitude, 0.99 * limit);
  EXPECT_NEAR(f.frictionRadial / f.frictionCircumferential, vr / vt, 1e-12);  // along the sliding
  EXPECT_GT(f.frictionRadial, 0.0);
  EXPECT_LT(f.frictionCircumferential, 0.0);
  EXPECT_GT(f.frictionPower, 0.0);
  EXPECT_GT(f.dampingPower, 0.0);  // (compressing: the damping works against it)
}

TEST(PinSheave, SeparatingPinIsNotPulled) {
  const PinSheaveLaw l = law();
  // moving out fast enough that the damping would pull: the axial force stays at zero
  const PinSheaveForce f = pinSheaveForce(l, 0.02, 1e-7, 50.0, 0.0);
  EXPECT_EQ(f.axial, 0.0);
  EXPECT_EQ(f.normal, 0.0);
  EXPECT_EQ(f.frictionRadial, 0.0);
}
