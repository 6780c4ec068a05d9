// The span model's stiffest mode and its explicit stable step (src/span/span_modes.h).
#include <gtest/gtest.h>

#include <cmath>

#include "span/span_modes.h"
#include "test_util.h"

using namespace chaindrive;
using namespace chaindrive::test;

// The default drive's span model: the short span between the camshafts is the stiffest against
// its rotors; its highest mode's step, about 280 us, lies where the span model's open-loop limit was
// measured at 6000 rpm (250 us ran 0.2 s, 300 us blew up, 400 us in that span, docs/defaults.md).
TEST(SpanModes, TheDefaultDrivesStiffestSpanIsBetweenTheCamshafts) {
  const Model& m = *defaultModel();
  const span::SpanModeStep s = span::spanModeStep(span::assembleSpanModel(m, false));
  EXPECT_EQ(s.stiffestSpan, "camshaftExhaust->camshaftIntake");
  EXPECT_GT(s.step, 200e-6);
  EXPECT_LT(s.step, 400e-6);
  EXPECT_NEAR(s.step * s.omega, 2.0, 0.05);  // (the spans' damping is light)
}

// Stiffer joints make stiffer spans (four times as stiff: half the step), lighter camshafts faster
// rotors: both shorten the step (camshafts five times lighter: 0.71 of it, the chain lumped on them
// keeps part of their inertia).
TEST(SpanModes, StifferSpansAndLighterRotorsShortenTheStep) {
  const double base = span::spanModeStep(span::assembleSpanModel(*defaultModel(), false)).step;
  auto stepOf = [](const std::function<void(nlohmann::json&)>& edit) {
    const Model m = assemble(modifiedDefault(edit));
    return span::spanModeStep(span::assembleSpanModel(m, false)).step;
  };
  EXPECT_NEAR(stepOf([](nlohmann::json& j) { j["chain"]["joint"]["stiffness"] = 4.8e8; }), 0.5 * base, 0.02 * base);
  EXPECT_LT(stepOf([](nlohmann::json& j) {
              sprocketJson(j, "camshaftIntake")["inertia"] = 2e-4;
              sprocketJson(j, "camshaftExhaust")["inertia"] = 2e-4;
            }),
            0.75 * base);
}
