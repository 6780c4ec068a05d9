// Saved states (src/run/state_file.h): a state written and read back is the same to the bit, and a
// file that is unreadable, corrupt or of another drive is refused with an error naming the file
// and the problem.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

#include "test_util.h"
#include "run/state_file.h"

using namespace chaindrive;
using namespace chaindrive::test;
using nlohmann::json;

namespace {

std::string tempPath(const std::string& name) { return ::testing::TempDir() + "state_file_test_" + name; }

// A state of the default drive with values whose decimal forms would not round-trip: thirds,
// a subnormal, the extremes, a negative zero.
StateSnapshot awkwardState(const Model& m) {
  StateSnapshot s;
  s.time = 0.1 + 0.2;
  s.y.resize(m.nStates);
  for (int i = 0; i < m.nStates; ++i) s.y[i] = (i % 2 ? -1.0 : 1.0) * (i + 1) / 3.0 * std::pow(10.0, i % 17 - 8);
  s.y[0] = std::numeric_limits<double>::denorm_min();
  s.y[1] = std::numeric_limits<double>::max();
  s.y[2] = std::numeric_limits<double>::lowest();
  s.y[3] = -0.0;
  return s;
}

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// A state file of the default drive written by writeStateFile, then changed by `edit`.
std::string editedFile(const std::string& name, const std::function<void(json&)>& edit) {
  const Model& m = *defaultModel();
  const std::string path = tempPath(name);
  writeStateFile(path, m, awkwardState(m));
  json j;
  std::ifstream(path) >> j;
  edit(j);
  std::ofstream(path) << j.dump(1) << "\n";
  return path;
}

// A file as the layout before the step means' accumulators wrote it: without them (model.h:
// ImpulseStates, the last components), under `schema`.
void asEarlierLayout(json& j, const Model& m, const char* schema) {
  j["schema"] = schema;
  const int without = m.chainImpulse.first;
  j["y"].erase(j["y"].begin() + without, j["y"].end());
  j["states"] = without;
}

// The message of the error readStateFile throws for `path` (empty if it throws none).
std::string readError(const std::string& path) {
  try {
    readStateFile(path, *defaultModel(), defaultModel()->nStates);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(StateFile, WrittenStateReadsBackBitIdentical) {
  const Model& m = *defaultModel();
  const StateSnapshot s = awkwardState(m);
  const std::string path = tempPath("roundtrip.json");
  writeStateFile(path, m, s);
  const StateSnapshot back = readStateFile(path, m, m.nStates);
  EXPECT_TRUE(sameBits(back.time, s.time));
  ASSERT_EQ(back.y.size(), s.y.size());
  for (std::size_t i = 0; i < s.y.size(); ++i) EXPECT_TRUE(sameBits(back.y[i], s.y[i])) << "y[" << i << "]";
}

TEST(StateFile, StateOfAnotherDriveIsRefused) {
  const Model& m = *defaultModel();
  const std::string states = editedFile("other_states.json", [&](json& j) { j["states"] = m.nStates + 2; });
  EXPECT_NE(readError(states).find(states + ": a state of another drive"), std::string::npos) << readError(states);
  const std::string links = editedFile("other_links.json", [&](json& j) { j["links"] = m.chain.links - 1; });
  EXPECT_NE(readError(links).find("a state of another drive"), std::string::npos) << readError(links);
}

// A file of the schema before the chamber's oil content ("chaindrive.state/2") holds a hydraulic
// chamber's pressure where this version keeps its content: refused for such a drive, naming the
// change; read as before for a drive without a chamber (the same layout).
TEST(StateFile, PressureStateOfAHydraulicChamberIsRefused) {
  const std::string old = editedFile("pressure_state.json", [](json& j) { j["schema"] = "chaindrive.state/2"; });
  EXPECT_NE(readError(old).find("the hydraulic chamber's pressure as its state"), std::string::npos) << readError(old);

  const Model spring = assemble(modifiedDefault(useSpringDamperTensioner));
  ASSERT_LT(spring.stateChamberOil, 0);
  const std::string path = tempPath("spring_damper_v2.json");
  writeStateFile(path, spring, awkwardState(spring));
  json j;
  std::ifstream(path) >> j;
  asEarlierLayout(j, spring, "chaindrive.state/2");
  std::ofstream(path) << j.dump(1) << "\n";
  const StateSnapshot back = readStateFile(path, spring, spring.nStates);
  EXPECT_TRUE(sameBits(back.y[3], -0.0));
  EXPECT_EQ(back.y.size(), static_cast<std::size_t>(spring.nStates));
}

// A file of the layout before the step means' accumulators ("chaindrive.state/3": the same state
// without them) reads with them zero, every other component to the bit.
TEST(StateFile, StateWithoutTheImpulseAccumulatorsReadsWithThemZero) {
  const Model& m = *defaultModel();
  const StateSnapshot s = awkwardState(m);
  const std::string path = editedFile("content_state_v3.json", [&](json& j) { asEarlierLayout(j, m, "chaindrive.state/3"); });
  const StateSnapshot back = readStateFile(path, m, m.nStates);
  ASSERT_EQ(back.y.size(), s.y.size());
  for (int i = 0; i < m.chainImpulse.first; ++i) EXPECT_TRUE(sameBits(back.y[i], s.y[i])) << "y[" << i << "]";
  for (int i = m.chainImpulse.first; i < m.nStates; ++i) EXPECT_EQ(back.y[i], 0.0) << "y[" << i << "]";
  EXPECT_EQ(m.chainImpulse.time, m.nStates - 1);
}

TEST(StateFile, CorruptFilesAreRefusedNamingTheProblem) {
  const std::string garbage = tempPath("garbage.json");
  std::ofstream(garbage) << "{\"schema\": \"chaindrive.state/3\", \"y\": [";
  EXPECT_NE(readError(garbage).find(garbage + ": not valid JSON"), std::string::npos) << readError(garbage);

  const std::string schema = editedFile("schema.json", [](json& j) { j["schema"] = "chaindrive.state/0"; });
  EXPECT_NE(readError(schema).find("not a state file"), std::string::npos) << readError(schema);

  const std::string value = editedFile("value.json", [](json& j) { j["y"][5] = "0x1.8p+1junk"; });
  EXPECT_NE(readError(value).find("y[5] = '0x1.8p+1junk' is not a finite number"), std::string::npos)
      << readError(value);

  const std::string infinite = editedFile("infinite.json", [](json& j) { j["time"] = "inf"; });
  EXPECT_NE(readError(infinite).find("time = 'inf' is not a finite number"), std::string::npos) << readError(infinite);

  const std::string shortY = editedFile("short.json", [](json& j) { j["y"].erase(j["y"].size() - 1); });
  EXPECT_NE(readError(shortY).find("y must be an array of"), std::string::npos) << readError(shortY);

  const std::string missing = tempPath("missing.json");
  std::remove(missing.c_str());
  EXPECT_NE(readError(missing).find(missing + ": cannot be opened"), std::string::npos) << readError(missing);
}
