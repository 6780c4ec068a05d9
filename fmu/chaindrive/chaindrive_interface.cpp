#include "chaindrive_interface.h"

#include <algorithm>
#include <fstream>
#include <iterator>

#include <nlohmann/json.hpp>

#include "interface/fmu_files.h"
#include "utf8_path.h"

namespace chaindrive::fmu {

namespace {

using json = nlohmann::json;

bool readText(const std::string& path, std::string& text) {
  std::ifstream in(utf8Path(path), std::ios::binary);
  if (!in) return false;
  text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return true;
}

Type protocolType(VarType t) {
  switch (t) {
    case VarType::Real: return Type::Real;
    case VarType::Integer: return Type::Integer;
    case VarType::Boolean: return Type::Boolean;
    case VarType::String: return Type::String;
  }
  return Type::Real;
}

Causality protocolCausality(VarCausality c) {
  switch (c) {
    case VarCausality::Input: return Causality::Input;
    case VarCausality::Output: return Causality::Output;
    case VarCausality::Parameter: return Causality::Parameter;
  }
  return Causality::Output;
}

}  // namespace

std::string FmuInterface::load(const std::string& resourceDir, const char* guid) {
  if (resourceDir.empty())
    return "no resources folder: the FMU's drive and its interface are in its resources/ (fmuResourceLocation must be "
           "the file URI of that folder)";
  std::string text;
  const std::string interfacePath = resourceDir + "/" + kInterfaceFile;
  if (!readText(interfacePath, text))
    return "the resources folder " + resourceDir + " has no " + kInterfaceFile + " (the FMU's variables; an FMU "
           "exported by python -m harness export has one)";
  std::string problem;
  try {
    problem = check(resourceDir, text, guid);
  } catch (const DescriptionError& e) {
    problem = "the FMU's drive " + drivePath_ + ":";
    for (const std::string& p : e.problems()) problem += " " + p + ";";
    problem.pop_back();
  } catch (const json::exception& e) {
    problem = "resources/" + std::string(kInterfaceFile) + " is not an interface table: " + e.what();
  }
  if (problem.empty()) index();
  return problem;
}

// The table against the GUID and the drive it names (its interface generated again).
std::string FmuInterface::check(const std::string& resourceDir, const std::string& interfaceText, const char* guid) {
  const json file = json::parse(interfaceText);
  const std::string where = "resources/" + std::string(kInterfaceFile);
  if (file.at("schema") != kInterfaceSchema)
    return where + ": schema " + file.at("schema").dump() + ", this binary reads " + kInterfaceSchema;
  const std::string fileGuid = file.at("guid").get<std::string>();
  if (!guid || fileGuid != guid)
    return std::string("the GUID ") + (guid ? guid : "(NULL)") + " does not match this FMU's " + fileGuid + " (" +
           where + "; wrong or mixed-up FMU files)";
  const std::string driveFile = file.at("drive").get<std::string>();
  drivePath_ = resourceDir + "/" + driveFile;
  std::string driveText;
  if (!readText(drivePath_, driveText)) return "resources/" + driveFile + " (the FMU's drive, named in " + where + ") cannot be read";
  drive_ = parseDriveDescription(driveText);
  table_ = driveInterface(drive_);
  const std::string difference = interfaceDifference(interfaceJson(table_).at("variables"), file.at("variables"), false);
  if (!difference.empty())
    return where + " does not match the interface of resources/" + driveFile + " (a drive or table changed after the "
           "export, or a binary of another version; export the FMU again): " + difference;
  return "";
}

void FmuInterface::index() {
  variables_.clear();
  unsigned top = 0;
  for (const InterfaceVariable& v : table_.variables) {
    variables_.push_back({v.name.c_str(), v.vr, protocolType(v.type), protocolCausality(v.causality), v.start.c_str()});
    top = std::max(top, v.vr);
  }
  byVr_.assign(top + 1, -1);
  for (std::size_t i = 0; i < variables_.size(); ++i) byVr_[variables_[i].vr] = static_cast<int>(i);
}

std::string interfaceMismatch(const DriveInterface& mine, const DriveDescription& other) {
  return interfaceDifference(interfaceJson(mine).at("variables"), interfaceJson(driveInterface(other)).at("variables"),
                             true);
}

}  // namespace chaindrive::fmu
