// tensioner.model and tensioner.hydraulic: a hydraulic block parses into the description and
// the assembled model; every field out of its range is reported with its full path, its value
// and the allowed range; fields of the other model are errors.
#include <gtest/gtest.h>

#include "test_util.h"

using namespace chaindrive;
using namespace chaindrive::test;
using nlohmann::json;

namespace {

// The default drive with a hydraulic tensioner (its spring-damper damping removed).
void makeHydraulic(json& j) {
  j["tensioner"]["model"] = "hydraulic";
  j["tensioner"].erase("damping");
  j["tensioner"].erase("dampingExtension");
}

std::vector<std::string> problemsOfHydraulic(const std::function<void(json& hydraulic)>& edit) {
  return problemsOf([&](json& j) {
    makeHydraulic(j);
    j["tensioner"]["hydraulic"] = json::object();
    edit(j["tensioner"]["hydraulic"]);
  });
}

// One problem, starting with the field's path and naming the value and the range.
void expectNamed(const std::vector<std::string>& p, const std::string& field, const std::string& value,
                 const std::string& range) {
  ASSERT_EQ(p.size(), 1u) << problemLines(p);
  EXPECT_EQ(p[0].rfind(field + ": ", 0), 0u) << p[0];
  EXPECT_NE(p[0].find(value), std::string::npos) << p[0];
  EXPECT_NE(p[0].find(range), std::string::npos) << p[0];
}

}  // namespace

TEST(HydraulicDescription, DefaultDriveIsHydraulic) {
  const DriveDescription d = defaultDriveDescription();
  EXPECT_EQ(d.tensioner.kind, TensionerKind::Hydraulic);
}

TEST(HydraulicDescription, BlockParsesIntoDescriptionAndModel) {
  const DriveDescription d = modifiedDefault([](json& j) {
    makeHydraulic(j);
    j["tensioner"]["hydraulic"] = {{"plungerDiameter", 0.014},
                                   {"clearance", 15e-6},
                                   {"oilTemperature", 353.15},
                                   {"checkValve", {{"crackingPressure", 2e4}, {"maxArea", 2e-6}}},
                                   {"reliefValve", {{"present", false}}},
                                   {"oil", {{"airFraction", 0.02}, {"bulkModulus", 1.5e9}}}};
  });
  const HydraulicTensionerDesc& h = d.tensioner.hydraulic;
  EXPECT_EQ(d.tensioner.kind, TensionerKind::Hydraulic);
  EXPECT_EQ(h.plungerDiameter, 0.014);
  EXPECT_EQ(h.clearance, 15e-6);
  EXPECT_EQ(h.oilTemperature, 353.15);
  EXPECT_EQ(h.checkValve.crackingPressure, 2e4);
  EXPECT_EQ(h.checkValve.maxArea, 2e-6);
  EXPECT_EQ(h.checkValve.fullLiftPressure, defaultCheckValve().fullLiftPressure);  // the rest keep defaults
  EXPECT_FALSE(h.reliefValve.present);
  EXPECT_EQ(h.oil.airFraction, 0.02);
  EXPECT_EQ(h.oil.bulkModulus, 1.5e9);
  EXPECT_EQ(h.guideLength, HydraulicTensionerDesc{}.guideLength);
  const Model m = assemble(d);
  EXPECT_EQ(m.tensioner.kind, TensionerKind::Hydraulic);
  EXPECT_EQ(m.tensioner.hydraulic.clearance, 15e-6);
  EXPECT_EQ(m.tensioner.hydraulic.oil.airFraction, 0.02);
}

TEST(HydraulicDescription, DefaultsAreValid) {
  EXPECT_TRUE(problemsOfHydraulic([](json&) {}).empty());
}

TEST(HydraulicDescription, UnknownModelListsTheNames) {
  const auto p = problemsOf([](json& j) { j["tensioner"]["model"] = "pneumatic"; });
  ASSERT_EQ(p.size(), 1u) << problemLines(p);
  EXPECT_EQ(p[0].rfind("tensioner.model: ", 0), 0u) << p[0];
  EXPECT_NE(p[0].find("spring-damper, hydraulic"), std::string::npos) << p[0];
}

TEST(HydraulicDescription, FieldsOfTheOtherModelAreErrors) {
  auto p = problemsOf([](json& j) {
    test::useSpringDamperTensioner(j);
    j["tensioner"]["hydraulic"] = json::object();
  });
  ASSERT_EQ(p.size(), 1u) << problemLines(p);
  EXPECT_EQ(p[0].rfind("tensioner.hydraulic: ", 0), 0u) << p[0];
  p = problemsOf([](json& j) {  // the hydraulic default drive with the spring-damper law's damping
    j["tensioner"]["damping"] = 3000.0;
    j["tensioner"]["dampingExtension"] = 300.0;
  });
  EXPECT_EQ(p.size(), 2u) << problemLines(p);
  for (const auto& s : p) EXPECT_NE(s.find("applies to the model 'spring-damper' only"), std::string::npos) << s;
}

// Every number field, one value outside its range each: the problem names the full path, the
// value and the range.
TEST(HydraulicDescription, EachBadFieldNamesItself) {
  struct Case {
    const char* path;  // below tensioner.hydraulic
    double value;
    const char* value_text;
    const char* range;
  };
  const Case cases[] = {
      {"plungerDiameter", 0.1, "0.1", "[0.003, 0.05] m"},
      {"clearance", 0.0, "0", "[1e-06, 0.0002] m"},
      {"guideLength", 0.5, "0.5", "[0.001, 0.1] m"},
      {"eccentricity", 1.5, "1.5", "[0, 1]"},
      {"chamberVolume", 1e-9, "1e-09", "[1e-08, 0.0001] m3"},
      {"plungerMass", 0.0, "0", "[0.0001, 1] kg"},
      {"strokeMin", 0.001, "0.001", "[-0.05, 0] m"},
      {"strokeMax", 0.0, "0", "(0, 0.05] m"},
      {"endStopStiffness", -1.0, "-1", "[0, 1e+10] N/m"},
      {"oilTemperature", 250.0, "250", "[293.15, 423.15] K"},
      {"supplyPressure", 2e6, "2e+06", "[0, 1e+06] Pa"},
      {"checkValve.crackingPressure", -5.0, "-5", "[0, 1e+08] Pa"},
      {"checkValve.fullLiftPressure", 0.0, "0", "(0, 1e+08] Pa"},
      {"checkValve.maxArea", 0.0, "0", "(0, 0.0001] m2"},
      {"checkValve.dischargeCoefficient", 1.2, "1.2", "(0, 1]"},
      {"reliefValve.laminarPressure", 0.0, "0", "(0, 100000] Pa"},
      {"oil.vogelA", 0.0, "0", "(0, 1] Pa s"},
      {"oil.vogelB", -3.0, "-3", "(0, 100000] K"},
      {"oil.density", 2000.0, "2000", "[600, 1200] kg/m3"},
      {"oil.bulkModulus", 1e7, "1e+07", "[1e+08, 1e+10] Pa"},
      {"oil.airFraction", 0.6, "0.6", "[0, 0.5]"},
      {"oil.polytropicExponent", 2.0, "2", "[1, 1.67]"},
      {"oil.vapourPressure", 0.0, "0", "(0, 50000] Pa (absolute)"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.path);
    const auto p = problemsOfHydraulic([&](json& h) {
      const std::string path = c.path;
      const auto dot = path.find('.');
      if (dot == std::string::npos) h[path] = c.value;
      else h[path.substr(0, dot)][path.substr(dot + 1)] = c.value;
    });
    expectNamed(p, std::string("tensioner.hydraulic.") + c.path, c.value_text, c.range);
  }
}

TEST(HydraulicDescription, RelationsBetweenFieldsAreChecked) {
  auto p = problemsOfHydraulic([](json& h) { h["oil"] = {{"temperatureMin", 400.0}, {"temperatureMax", 350.0}}; });
  EXPECT_FALSE(p.empty());
  EXPECT_EQ(p[0].rfind("tensioner.hydraulic.oil.temperatureMax: 350 K must exceed temperatureMin 400 K", 0), 0u)
      << problemLines(p);
  p = problemsOfHydraulic([](json& h) { h["oil"] = {{"vogelC", 240.0}, {"temperatureMin", 230.0}}; });
  ASSERT_FALSE(p.empty());
  EXPECT_EQ(p[0].rfind("tensioner.hydraulic.oil.vogelC: 240 K must lie below temperatureMin 230 K", 0), 0u)
      << problemLines(p);
  // a 2 cm3 chamber on a 12 mm plunger empties 17.7 mm below the nominal stroke
  p = problemsOfHydraulic([](json& h) { h["strokeMin"] = -0.02; });
  ASSERT_EQ(p.size(), 1u) << problemLines(p);
  EXPECT_EQ(p[0].rfind("tensioner.hydraulic.strokeMin: -0.02 m empties the chamber", 0), 0u) << p[0];
  EXPECT_NE(p[0].find("allowed > -0.0176839 m"), std::string::npos) << p[0];
  p = problemsOfHydraulic([](json& h) { h["checkValve"]["lift"] = 1.0; });
  ASSERT_EQ(p.size(), 1u) << problemLines(p);
  EXPECT_EQ(p[0].rfind("tensioner.hydraulic.checkValve.lift: ", 0), 0u) << p[0];
}
