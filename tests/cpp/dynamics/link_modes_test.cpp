// The link model's stiffest modes and their explicit stable step (src/dynamics/link_modes.h).
#include <gtest/gtest.h>

#include <cmath>

#include "dynamics/link_modes.h"
#include "test_util.h"

using namespace chaindrive;
using namespace chaindrive::test;

// The default drive: its rollers' contact (2e8 N/m) is the stiffer law, and the link's rotation
// (the pins at +-p/2 with both rollers seated) is its stiffest mode; the step is Verlet's on it,
// with the contacts' damping at the reference roller force (and the joints' where explicit), by hand.
TEST(LinkModes, TheDefaultDrivesRotationWithItsRollersSeated) {
  const Model& m = *defaultModel();
  const LinkModeStep s = linkModeStep(m, false);
  EXPECT_STREQ(s.contact, "roller-sprocket");
  EXPECT_STREQ(s.mode, "rotation");
  EXPECT_EQ(s.contactStiffness, 2e8);
  EXPECT_DOUBLE_EQ(s.contactDamping, 1.5 * 0.25 * kReferenceContactForce);
  const double p2 = m.chain.pitch * m.chain.pitch, J = m.chain.inertia;
  const double w = std::sqrt((1.2e8 + 1e8) * p2 / J), rate = 0.5 * s.contactDamping * p2 / J;
  EXPECT_NEAR(s.step, 2.0 * (std::sqrt(1.0 + rate * rate / (4 * w * w)) - rate / (2 * w)) / w, 1e-15);
  EXPECT_NEAR(s.step, 2.989e-6, 0.001e-6);
  // plain Verlet takes the joints' damping explicitly too: a shorter step
  const LinkModeStep plain = linkModeStep(m, true);
  EXPECT_LT(plain.step, s.step);
  EXPECT_NEAR(plain.step, 2.252e-6, 0.001e-6);
}

// A lighter link, a stiffer contact, stiffer joints or more contact damping: each a shorter step;
// a softer contact a longer one.
TEST(LinkModes, LighterLinksAndStifferContactsShortenTheStep) {
  const double base = linkModeStep(*defaultModel(), false).step;
  auto stepOf = [](const std::function<void(nlohmann::json&)>& edit) {
    return linkModeStep(assemble(modifiedDefault(edit)), false).step;
  };
  EXPECT_LT(stepOf([](nlohmann::json& j) { j["chain"]["linkMass"] = 0.5 * 0.0039; }), base);
  EXPECT_LT(stepOf([](nlohmann::json& j) { j["chain"]["linkInertia"] = 0.5 * 7e-8; }), base);
  EXPECT_LT(stepOf([](nlohmann::json& j) { j["contact"]["rollerSprocket"]["stiffness"] = 4e8; }), base);
  EXPECT_LT(stepOf([](nlohmann::json& j) { j["chain"]["joint"]["stiffness"] = 2.4e8; }), base);
  EXPECT_LT(stepOf([](nlohmann::json& j) { j["contact"]["rollerSprocket"]["dampingFactor"] = 0.5; }), base);
  EXPECT_GT(stepOf([](nlohmann::json& j) { j["contact"]["rollerSprocket"]["stiffness"] = 5e7; }), base);
  // both the mass and the inertia halved: every mode's frequency times sqrt(2), the damping
  // ratios too (their rates double), so the step shrinks by more than 1 / sqrt(2)
  EXPECT_LT(stepOf([](nlohmann::json& j) {
              j["chain"]["linkMass"] = 0.5 * 0.0039;
              j["chain"]["linkInertia"] = 0.5 * 7e-8;
            }),
            base / std::sqrt(2.0));
}

// The stiffer law sets the step: plate-guide contacts stiffer than the rollers' take over.
TEST(LinkModes, TheStifferContactLawSetsIt) {
  const Model m = assemble(modifiedDefault([](nlohmann::json& j) { j["contact"]["plateGuide"]["stiffness"] = 4e8; }));
  const LinkModeStep s = linkModeStep(m, false);
  EXPECT_STREQ(s.contact, "plate-guide");
  EXPECT_EQ(s.contactStiffness, 4e8);
}
