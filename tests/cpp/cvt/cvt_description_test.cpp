#include "cvt/cvt_description.h"

#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

using namespace chaindrive;

namespace {

// The default CVT's JSON with one field replaced (a JSON pointer) or removed (null value).
std::string defaultWith(const std::string& pointer, const nlohmann::json& value) {
  nlohmann::json j = nlohmann::json::parse(defaultCvtJson());
  const nlohmann::json::json_pointer p(pointer);
  if (value.is_null()) j[p.parent_pointer()].erase(p.back());
  else j[p] = value;
  return j.dump();
}

// The problems of an invalid description, one per line.
std::string problemsOf(const std::string& text) {
  try {
    parseCvtDescription(text);
  } catch (const DescriptionError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(CvtDescription, DefaultParsesInSi) {
  const CvtDescription d = defaultCvtDescription();
  EXPECT_EQ(d.numberOfLinks, 63);  // the paper's example 4.1
  EXPECT_NEAR(d.wedgeHalfAngle, 11.0 * 3.14159265358979323846 / 180.0, 1e-15);
  EXPECT_GT(d.pinAxialStiffness, 0.0);
  EXPECT_EQ(d.joint.model, JointModel::JournalBearing);
}

TEST(CvtDescription, ProblemsNameTheFieldAndTheRange) {
  const std::string wedge = problemsOf(defaultWith("/pulleys/wedgeHalfAngle_deg", 45.0));
  EXPECT_NE(wedge.find("pulleys.wedgeHalfAngle_deg"), std::string::npos) << wedge;
  EXPECT_NE(wedge.find("30"), std::string::npos) << wedge;
  const std::string ratio = problemsOf(defaultWith("/pulleys/ratio", -1.0));
  EXPECT_NE(ratio.find("pulleys.ratio"), std::string::npos) << ratio;
  const std::string missing = problemsOf(defaultWith("/chain/pin", nullptr));
  EXPECT_NE(missing.find("chain.pin"), std::string::npos) << missing;
  const std::string unknown = problemsOf(defaultWith("/contact/frictionn", 0.1));
  EXPECT_NE(unknown.find("contact.frictionn"), std::string::npos) << unknown;
  const std::string restitution = problemsOf(defaultWith("/contact/restitution", 1.5));
  EXPECT_NE(restitution.find("contact.restitution"), std::string::npos) << restitution;
  const std::string ideal = problemsOf(defaultWith("/chain/joint/model", "ideal"));
  EXPECT_NE(ideal.find("chain.joint.model"), std::string::npos) << ideal;
}

TEST(CvtDescription, EveryProblemAtOnce) {
  nlohmann::json j = nlohmann::json::parse(defaultCvtJson());
  j["pulleys"]["centerDistance"] = -1.0;
  j["contact"]["friction"] = 2.0;
  const std::string p = problemsOf(j.dump());
  EXPECT_NE(p.find("pulleys.centerDistance"), std::string::npos) << p;
  EXPECT_NE(p.find("contact.friction"), std::string::npos) << p;
}
