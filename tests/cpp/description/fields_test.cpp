// The field reader of drive descriptions: values with their defaults and ranges, angles in rad
// or deg, and problems named by their full field path, unknown keys included.
#include <gtest/gtest.h>

#include <cmath>

#include "description/fields.h"

using namespace chaindrive;
using nlohmann::json;

TEST(Fields, ValuesDefaultsAndAnglesInDegrees) {
  const json j = json::parse(R"({"x": 2.5, "n": 7, "a_deg": 90, "v": [1, -2], "names": ["p", "q"], "on": true})");
  std::vector<std::string> problems;
  Fields f(&j, "root", problems);
  EXPECT_EQ(f.number("x", 0.0, 10.0, std::nullopt, "m"), 2.5);
  EXPECT_EQ(f.number("missing", 0.0, 10.0, 4.0, "m"), 4.0);
  EXPECT_EQ(f.integer("n", 0, 10, std::nullopt), 7);
  // deg -> rad as deg * pi / 180, so exactly pi / 2 here
  EXPECT_EQ(f.angle("a", -kPi, kPi, std::nullopt), 90.0 * kPi / 180.0);
  const Vec2 v = f.vec2("v", 10.0, std::nullopt, "m");
  EXPECT_EQ(v.x, 1.0);
  EXPECT_EQ(v.y, -2.0);
  EXPECT_EQ(f.strings("names", true), (std::vector<std::string>{"p", "q"}));
  EXPECT_TRUE(f.boolean("on", false));
  f.finish();
  EXPECT_TRUE(problems.empty()) << problems.front();
}

TEST(Fields, ProblemsNameTheFieldPathAndTheAllowedRange) {
  const json j = json::parse(R"({"x": -1, "n": 2.5, "a": 1, "a_deg": 57, "s": "maybe", "list": [1, "b"],
                                 "sub": {"k": 1}, "extra": 0})");
  std::vector<std::string> problems;
  Fields f(&j, "top", problems);
  f.number("x", 0.0, 10.0, std::nullopt, "m", true);
  f.integer("n", 0, 5, std::nullopt);
  EXPECT_TRUE(std::isnan(f.angle("a", -1.0, 1.0, std::nullopt)));
  f.string("s", {"yes", "no"}, std::nullopt);
  f.strings("list", true);
  f.number("required", 0.0, 1.0, std::nullopt, "kg");
  Fields sub = f.object("sub", true);
  sub.finish();  // "k" was never asked for
  f.finish();
  const std::vector<std::string> expected = {
      "top.x: -1 is out of range; allowed (0, 10] m",
      "top.n: must be an integer, got 2.5",
      "top.a: given both as 'a' [rad] and 'a_deg' [deg]; give one",
      "top.s: 'maybe' is unknown; allowed: yes, no",
      "top.list[0]: must be a string",
      "top.required: missing; required, [0, 1] kg",
      "top.sub.k: unknown key; known keys here: ",
      "top.extra: unknown key; known keys here: a, a_deg, list, n, required, s, sub, x",
  };
  EXPECT_EQ(problems, expected);
}

TEST(Fields, WrongContainerTypesAndMissingOptionalObjects) {
  const json j = json::parse(R"({"obj": 3, "arr": {}, "names": "p"})");
  std::vector<std::string> problems;
  Fields f(&j, "", problems);
  EXPECT_FALSE(f.object("obj", true).valid());
  EXPECT_TRUE(f.objects("arr", true).empty());
  EXPECT_TRUE(f.strings("names", false).empty());
  // a missing optional object gives the defaults and reports nothing
  Fields none = f.object("none", false);
  EXPECT_FALSE(none.valid());
  EXPECT_TRUE(std::isnan(none.number("x", 0.0, 1.0, std::nullopt, "m")));
  EXPECT_EQ(none.number("y", 0.0, 1.0, 0.5, "m"), 0.5);
  const std::vector<std::string> expected = {
      "obj: must be an object, got a number",
      "arr: must be an array, got an object",
      "names: must be an array of names, got a string",
  };
  EXPECT_EQ(problems, expected);
}
