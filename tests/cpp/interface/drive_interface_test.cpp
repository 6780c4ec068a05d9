// The FMU interface generated from a drive (src/interface/): the default drive keeps its value
// references and GUID, every element's variables by its name, the value-reference scheme on a
// drive with more rotors, the names refused, and the files an exporter writes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "description/fields.h"
#include "interface/fmu_files.h"

namespace chaindrive {
namespace {

std::map<std::string, const InterfaceVariable*> byName(const DriveInterface& di) {
  std::map<std::string, const InterfaceVariable*> m;
  for (const InterfaceVariable& v : di.variables) m[v.name] = &v;
  return m;
}

DriveDescription testDrive(const std::string& file) {
  return loadDriveDescription(std::string(CHAINDRIVE_SOURCE_DIR) + "/tests/drives/" + file);
}

TEST(DriveInterface, DefaultDriveKeepsItsValueReferencesAndGuid) {
  const DriveInterface di = driveInterface(defaultDriveDescription());
  EXPECT_TRUE(di.defaultDrive);
  EXPECT_EQ(di.modelIdentifier, "ChainDrive");
  EXPECT_EQ(di.guid, kDefaultDriveGuid);
  const auto v = byName(di);
  const std::pair<const char*, unsigned> kept[] = {
      {"crankshaft.w", 1},          {"camshaftIntake.tau", 2},  {"camshaftExhaust.tau", 3},
      {"tensioner.supplyPressure", 4}, {"crankshaft.phi", 10},  {"crankshaft.tau", 11},
      {"camshaftIntake.phi", 12},   {"camshaftIntake.w", 13},   {"camshaftExhaust.phi", 14},
      {"camshaftExhaust.w", 15},    {"tensionGuide.phi", 16},   {"tensionGuide.w", 17},
      {"tensioner.F", 18},          {"chain.Ftight", 21},       {"solver.time", 34},
      {"contacts", 40},             {"solver.steps", 41},       {"driveFile", 100},
      {"tensioner.oilTemperature", 114}};
  for (const auto& [name, vr] : kept) {
    ASSERT_TRUE(v.count(name)) << name;
    EXPECT_EQ(v.at(name)->vr, vr) << name;
  }
  // the new outputs: the chain's torque on each camshaft, a force per span
  EXPECT_EQ(v.at("camshaftIntake.tauChain")->vr, 1013u);
  EXPECT_EQ(v.at("camshaftExhaust.tauChain")->vr, 1023u);
  EXPECT_EQ(v.at("chain.crankshaft.tensionGuide.F")->vr, 2000u);
  EXPECT_EQ(v.at("chain.fixedGuide.crankshaft.F")->vr, 2004u);
}

TEST(DriveInterface, EveryElementHasItsVariablesAndValueReferencesAreUnique) {
  const DriveInterface di = driveInterface(testDrive("diesel_pump.json"));
  EXPECT_FALSE(di.defaultDrive);
  EXPECT_EQ(di.modelIdentifier, "Diesel_pump");
  const auto v = byName(di);
  for (const char* name : {"hpPump.tau", "hpPump.phi", "hpPump.w", "hpPump.tauChain", "camshaftIntake.tau",
                           "camshaftExhaust.tau", "crankshaft.w", "crankshaft.tau", "tensionGuide.phi",
                           "chain.camshaftIntake.hpPump.F", "chain.hpPump.fixedGuide.F"})
    EXPECT_TRUE(v.count(name)) << name;
  // rotors from the crankshaft against the running direction: the pump is rotor 1, so it keeps
  // the compact numbers; the tension guide is rotor 4, in its block 1000 + 10 k
  EXPECT_EQ(v.at("hpPump.tau")->vr, 2u);
  EXPECT_EQ(v.at("hpPump.phi")->vr, 12u);
  EXPECT_EQ(v.at("tensionGuide.phi")->vr, 1041u);
  EXPECT_EQ(v.at("tensionGuide.w")->vr, 1042u);
  std::set<unsigned> vrs;
  std::set<std::string> names;
  for (const InterfaceVariable& var : di.variables) {
    EXPECT_TRUE(vrs.insert(var.vr).second) << var.name;
    EXPECT_TRUE(names.insert(var.name).second) << var.name;
  }
}

TEST(DriveInterface, AnIdlerHasNoLoadInputAndASpringDamperTensionerNoOil) {
  const auto idler = byName(driveInterface(testDrive("idler.json")));
  EXPECT_FALSE(idler.count("idler.tau"));
  EXPECT_TRUE(idler.count("idler.phi") && idler.count("idler.w") && idler.count("idler.tauChain"));
  const auto springDamper = byName(driveInterface(
      loadDriveDescription(std::string(CHAINDRIVE_SOURCE_DIR) + "/tests/data/drives/default_drive_spring_damper.json")));
  for (const char* name : {"tensioner.supplyPressure", "tensioner.chamberPressure", "tensioner.oilTemperature"})
    EXPECT_FALSE(springDamper.count(name)) << name;
  EXPECT_TRUE(springDamper.count("tensioner.damping"));
}

// The default drive with its exhaust camshaft renamed: a problem naming the element, or none.
std::vector<std::string> problemsOfName(const std::string& name) {
  std::string text(defaultDriveJson());
  for (std::size_t at = text.find("camshaftExhaust"); at != std::string::npos; at = text.find("camshaftExhaust", at))
    text.replace(at, 15, name), at += name.size();
  try {
    driveInterface(parseDriveDescription(text));
  } catch (const DescriptionError& e) {
    return e.problems();
  }
  return {};
}

TEST(DriveInterface, InvalidAndReservedNamesAreRefusedNamingTheElement) {
  EXPECT_TRUE(problemsOfName("exhaust_cam2").empty());
  for (const char* bad : {"exhaust cam", "2ndCam", "cam.exhaust", "chain", "tensioner", "solver"}) {
    const auto problems = problemsOfName(bad);
    ASSERT_EQ(problems.size(), 1u) << bad;
    EXPECT_NE(problems[0].find("sprockets[1].name"), std::string::npos) << problems[0];
    EXPECT_NE(problems[0].find(bad), std::string::npos) << problems[0];
  }
}

TEST(DriveInterface, TheDriveNameGivesTheModelIdentifierAndTheContentTheGuid) {
  std::string text(defaultDriveJson());
  const std::string name = "\"DOHC I4 timing drive (paper Fig. 11 layout)\"";
  text.replace(text.find(name), name.size(), "\"My drive: V6 bank 1\"");
  const DriveInterface a = driveInterface(parseDriveDescription(text));
  EXPECT_EQ(a.modelIdentifier, "My_drive_V6_bank_1");
  EXPECT_NE(a.guid, kDefaultDriveGuid);
  text.replace(text.find("\"linkMass\": 0.0039"), 18, "\"linkMass\": 0.0040");
  const DriveInterface b = driveInterface(parseDriveDescription(text));
  EXPECT_EQ(b.modelIdentifier, a.modelIdentifier);
  EXPECT_NE(b.guid, a.guid);
  EXPECT_EQ(b.guid.size(), 38u);
  text.replace(text.find("\"My drive: V6 bank 1\""), 21, "\"Chaindrive\"");
  EXPECT_THROW(driveInterface(parseDriveDescription(text)), DescriptionError);  // ChainDrive.fmu's identifier
}

TEST(FmuFiles, TheExportersFilesHoldTheDriveAndItsInterface) {
  const std::string dir = (std::filesystem::temp_directory_path() / "chaindrive_fmu_files_test").string();
  std::filesystem::remove_all(dir);
  const std::string drive = readDescriptionFile(std::string(CHAINDRIVE_SOURCE_DIR) + "/tests/drives/idler.json");
  const DriveInterface di = writeFmuFiles(dir, drive);
  std::ifstream table(dir + "/resources/interface.json");
  const nlohmann::json j = nlohmann::json::parse(table);
  EXPECT_EQ(j.at("guid"), di.guid);
  EXPECT_EQ(interfaceDifference(j.at("variables"), interfaceJson(di).at("variables"), false), "");
  std::stringstream copy;
  copy << std::ifstream(dir + "/resources/drive.json").rdbuf();
  EXPECT_EQ(copy.str(), drive);
  std::stringstream xml;
  xml << std::ifstream(dir + "/modelDescription.xml").rdbuf();
  EXPECT_NE(xml.str().find("modelIdentifier=\"Idler_drive\""), std::string::npos);
  EXPECT_NE(xml.str().find("name=\"idler.tauChain\""), std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(FmuFiles, InterfaceDifferenceNamesTheFirstVariableThatDiffers) {
  nlohmann::json a = interfaceJson(driveInterface(defaultDriveDescription())).at("variables");
  nlohmann::json b = a;
  b[3]["description"] = "changed";
  EXPECT_EQ(interfaceDifference(a, b, true), "");
  EXPECT_NE(interfaceDifference(a, b, false).find("variable 4"), std::string::npos);
  b[5]["valueReference"] = 999;
  EXPECT_NE(interfaceDifference(a, b, true).find("variable 6"), std::string::npos);
  nlohmann::json shorter = a;
  shorter.erase(shorter.size() - 1);
  EXPECT_NE(interfaceDifference(a, shorter, true).find("variables against"), std::string::npos);
}

}  // namespace
}  // namespace chaindrive
