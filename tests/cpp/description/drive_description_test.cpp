// Drive descriptions: the default drive is valid; every kind of error is reported with the
// field it concerns and the allowed range, and all errors of a file are reported at once.
#include <gtest/gtest.h>

#include <fstream>

#include "test_util.h"

using namespace chaindrive;
using namespace chaindrive::test;
using nlohmann::json;

namespace {

bool mentions(const std::vector<std::string>& problems, const std::string& field, const std::string& what = "") {
  for (const auto& p : problems)
    if (p.rfind(field, 0) == 0 && p.find(what) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST(Description, DefaultDriveIsValid) {
  const DriveDescription d = defaultDriveDescription();
  EXPECT_EQ(d.chain.numberOfLinks, 120);
  EXPECT_EQ(d.sprockets.size(), 3u);
  EXPECT_TRUE(problemsOf([](json&) {}).empty());
}

TEST(Description, NegativeMassNamesTheFieldAndRange) {
  const auto p = problemsOf([](json& j) { j["chain"]["linkMass"] = -0.001; });
  ASSERT_FALSE(p.empty());
  EXPECT_TRUE(mentions(p, "chain.linkMass", "out of range")) << problemLines(p);
  EXPECT_TRUE(mentions(p, "chain.linkMass", "kg")) << problemLines(p);
}

TEST(Description, UnknownKeyIsReported) {
  const auto p = problemsOf([](json& j) { j["chain"]["pitchh"] = 0.008; });
  EXPECT_TRUE(mentions(p, "chain.pitchh", "unknown key")) << problemLines(p);
}

TEST(Description, MissingRequiredField) {
  const auto p = problemsOf([](json& j) { j["sprockets"][1].erase("inertia"); });
  EXPECT_TRUE(mentions(p, "sprockets[1].inertia", "missing")) << problemLines(p);
}

TEST(Description, WrongTypeIsReported) {
  const auto p = problemsOf([](json& j) { j["chain"]["numberOfLinks"] = "120"; });
  EXPECT_TRUE(mentions(p, "chain.numberOfLinks", "integer")) << problemLines(p);
}

TEST(Description, OddNumberOfLinks) {
  const auto p = problemsOf([](json& j) { j["chain"]["numberOfLinks"] = 121; });
  EXPECT_TRUE(mentions(p, "chain.numberOfLinks", "even")) << problemLines(p);
}

TEST(Description, OverlappingSprockets) {
  const auto p = problemsOf([](json& j) {
    auto& intake = sprocketJson(j, "camshaftIntake");
    auto& exhaust = sprocketJson(j, "camshaftExhaust");
    intake["center"][0] = exhaust["center"][0].get<double>() + 0.1;
  });
  EXPECT_TRUE(mentions(p, "sprockets[2].center", "overlaps")) << problemLines(p);
}

TEST(Description, ChainThatCannotClose) {
  const auto p = problemsOf([](json& j) { j["chain"]["numberOfLinks"] = 110; });
  ASSERT_TRUE(mentions(p, "chain.numberOfLinks", "cannot close")) << problemLines(p);
  // the message states how many links the layout holds
  EXPECT_TRUE(mentions(p, "chain.numberOfLinks", "holds between")) << problemLines(p);
}

TEST(Description, UnknownRouteElementAndUnusedSprocket) {
  const auto p = problemsOf([](json& j) { j["chain"]["route"][2] = "camshaftExaust"; });
  EXPECT_TRUE(mentions(p, "chain.route[2]", "neither a sprocket nor a guide")) << problemLines(p);
  EXPECT_TRUE(mentions(p, "sprockets[1]", "not in chain.route")) << problemLines(p);
}

TEST(Description, TensionerOnAFixedGuide) {
  const auto p = problemsOf([](json& j) { j["tensioner"]["guide"] = "fixedGuide"; });
  EXPECT_TRUE(mentions(p, "tensioner.guide", "pivoting")) << problemLines(p);
}

TEST(Description, AngleGivenTwice) {
  const auto p = problemsOf([](json& j) { guideJson(j, "fixedGuide")["profile"][0]["startAngle"] = 0.1; });
  EXPECT_TRUE(mentions(p, "guides[1].profile[0].startAngle", "both")) << problemLines(p);
}

TEST(Description, EveryErrorIsReportedAtOnce) {
  const auto p = problemsOf([](json& j) {
    j["chain"]["linkMass"] = 0.0;
    j["chain"]["joint"]["stiffness"] = -1.0;
    j["sprockets"][0]["teeth"] = 3;
    j["contact"]["rollerSprocket"]["friction"] = 5.0;
  });
  EXPECT_TRUE(mentions(p, "chain.linkMass")) << problemLines(p);
  EXPECT_TRUE(mentions(p, "chain.joint.stiffness")) << problemLines(p);
  EXPECT_TRUE(mentions(p, "sprockets[0].teeth", "6..200")) << problemLines(p);
  EXPECT_TRUE(mentions(p, "contact.rollerSprocket.friction", "[0, 2]")) << problemLines(p);
  EXPECT_GE(p.size(), 4u);
}

TEST(Description, InvalidJsonAndMissingFile) {
  try {
    parseDriveDescription("{ \"chain\": ");
    FAIL() << "expected an error";
  } catch (const DescriptionError& e) {
    EXPECT_NE(std::string(e.what()).find("not valid JSON"), std::string::npos);
  }
  try {
    loadDriveDescription("/nonexistent/drive.json");
    FAIL() << "expected an error";
  } catch (const DescriptionError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/drive.json"), std::string::npos);
  }
}

TEST(Description, Iso606ToothFormValues) {
  // ISO 606 formulas for z = 21, d1 = 6.35 mm (06B): seat radius 0.505 d1 .. 0.505 d1 + 0.069 d1^(1/3)
  const auto mn = iso606ToothForm(21, 0.009525, 0.00635, "min");
  const auto mx = iso606ToothForm(21, 0.009525, 0.00635, "max");
  EXPECT_NEAR(mn.seatRadius, 0.505 * 6.35e-3, 1e-12);
  EXPECT_NEAR(mx.seatRadius, (0.505 * 6.35 + 0.069 * std::cbrt(6.35)) * 1e-3, 1e-12);
  EXPECT_NEAR(mn.seatAngle * 180.0 / kPi, 140.0 - 90.0 / 21.0, 1e-9);
  EXPECT_NEAR(mx.seatAngle * 180.0 / kPi, 120.0 - 90.0 / 21.0, 1e-9);
  const double d = 9.525 / std::sin(kPi / 21.0);
  EXPECT_NEAR(mn.tipDiameter, (d + 1.25 * 9.525 - 6.35) * 1e-3, 1e-12);
}
