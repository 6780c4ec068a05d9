#include "interface/fmu_files.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "utf8_path.h"

namespace chaindrive {

namespace {

using json = nlohmann::json;

// The fields of a variable that make the interface (the rest describes it).
constexpr const char* kInterfaceFields[] = {"name", "valueReference", "type", "causality"};

json variableJson(const InterfaceVariable& v) {
  json j = {{"name", v.name}, {"valueReference", v.vr}, {"type", typeName(v.type)},
            {"causality", causalityName(v.causality)}};
  auto put = [&](const char* key, const std::string& value) {
    if (!value.empty()) j[key] = value;
  };
  put("variability", v.variability);
  put("initial", v.initial);
  put("declaredType", v.declaredType);
  put("unit", v.unit);
  put("displayUnit", v.displayUnit);
  put("start", v.start);
  put("min", v.min);
  put("max", v.max);
  put("description", v.description);
  if (v.dependsOnCrankSpeed) j["dependsOnCrankSpeed"] = true;
  return j;
}

std::string escaped(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string attribute(const char* name, const std::string& value) {
  return value.empty() ? "" : std::string(" ") + name + "=\"" + escaped(value) + "\"";
}

// clang-format off
constexpr const char* kCoSimulation = R"xml(
  <CoSimulation
    modelIdentifier="%ID%"
    needsExecutionTool="false"
    canHandleVariableCommunicationStepSize="true"
    canInterpolateInputs="false"
    maxOutputDerivativeOrder="0"
    canRunAsynchronuously="false"
    canBeInstantiatedOnlyOncePerProcess="false"
    canNotUseMemoryManagementFunctions="true"
    canGetAndSetFMUstate="true"
    canSerializeFMUstate="true"
    providesDirectionalDerivative="false"/>

  <UnitDefinitions>
    <Unit name="rad"><BaseUnit rad="1"/><DisplayUnit name="deg" factor="57.29577951308232"/></Unit>
    <Unit name="rad/s"><BaseUnit s="-1" rad="1"/><DisplayUnit name="rpm" factor="9.549296585513721"/><DisplayUnit name="deg/s" factor="57.29577951308232"/></Unit>
    <Unit name="N"><BaseUnit kg="1" m="1" s="-2"/></Unit>
    <Unit name="N.m"><BaseUnit kg="1" m="2" s="-2"/></Unit>
    <Unit name="m"><BaseUnit m="1"/><DisplayUnit name="mm" factor="1000"/></Unit>
    <Unit name="m/s"><BaseUnit m="1" s="-1"/></Unit>
    <Unit name="J"><BaseUnit kg="1" m="2" s="-2"/></Unit>
    <Unit name="s"><BaseUnit s="1"/><DisplayUnit name="us" factor="1000000"/></Unit>
    <Unit name="N/m"><BaseUnit kg="1" s="-2"/><DisplayUnit name="N/mm" factor="0.001"/></Unit>
    <Unit name="N.s/m"><BaseUnit kg="1" s="-1"/></Unit>
    <Unit name="Pa"><BaseUnit kg="1" m="-1" s="-2"/><DisplayUnit name="bar" factor="1e-5"/></Unit>
    <Unit name="m3/s"><BaseUnit m="3" s="-1"/><DisplayUnit name="l/min" factor="60000"/></Unit>
    <Unit name="K"><BaseUnit K="1"/><DisplayUnit name="degC" offset="-273.15"/></Unit>
  </UnitDefinitions>

  <TypeDefinitions>
    <SimpleType name="Angle"><Real quantity="Angle" unit="rad" displayUnit="deg"/></SimpleType>
    <SimpleType name="AngularVelocity"><Real quantity="AngularVelocity" unit="rad/s" displayUnit="rpm"/></SimpleType>
    <SimpleType name="Force"><Real quantity="Force" unit="N"/></SimpleType>
    <SimpleType name="Torque"><Real quantity="Torque" unit="N.m"/></SimpleType>
    <SimpleType name="Length"><Real quantity="Length" unit="m" displayUnit="mm"/></SimpleType>
    <SimpleType name="Velocity"><Real quantity="Velocity" unit="m/s"/></SimpleType>
    <SimpleType name="Energy"><Real quantity="Energy" unit="J"/></SimpleType>
  </TypeDefinitions>

  <LogCategories>
    <Category name="logEvents" description="Start-state solve, integrator restarts, parameter choices"/>
    <Category name="logStatusWarning" description="Warnings"/>
    <Category name="logStatusDiscard" description="Steps that could not be completed numerically"/>
    <Category name="logStatusError" description="Errors: bad parameters, inputs, call order, drive files"/>
    <Category name="logStatusFatal" description="Fatal errors (not used)"/>
    <Category name="logAll" description="Everything"/>
  </LogCategories>

  <DefaultExperiment startTime="0" stopTime="0.08" stepSize="1e-4" tolerance="1e-5"/>
)xml";
// clang-format on

// Inputs and parameters have a start value, an empty string one too.
std::string startAttribute(const InterfaceVariable& v) {
  return v.causality == VarCausality::Output ? "" : " start=\"" + escaped(v.start) + "\"";
}

std::string scalarVariable(const InterfaceVariable& v, std::size_t index) {
  std::string s = "    <!-- " + std::to_string(index) + " --><ScalarVariable" + attribute("name", v.name) +
                  attribute("valueReference", std::to_string(v.vr)) + attribute("causality", causalityName(v.causality)) +
                  attribute("variability", v.variability) + attribute("initial", v.initial) +
                  attribute("description", v.description) + "><" + typeName(v.type) +
                  attribute("declaredType", v.declaredType) + attribute("unit", v.unit) +
                  attribute("displayUnit", v.displayUnit) + startAttribute(v) + attribute("min", v.min) +
                  attribute("max", v.max) + "/></ScalarVariable>\n";
  return s;
}

// The outputs (1-based indices into ModelVariables) and what they depend on directly: the
// crankshaft-speed input or nothing.
std::string modelStructure(const DriveInterface& di) {
  std::size_t crankSpeed = 0;
  for (std::size_t i = 0; i < di.variables.size(); ++i)
    if (di.variables[i].binding == Binding::CrankSpeed) crankSpeed = i + 1;
  std::string outputs, unknowns;
  for (std::size_t i = 0; i < di.variables.size(); ++i) {
    const InterfaceVariable& v = di.variables[i];
    if (v.causality != VarCausality::Output) continue;
    const std::string index = std::to_string(i + 1);
    outputs += "      <Unknown index=\"" + index + "\" dependencies=\"" +
               (v.dependsOnCrankSpeed ? std::to_string(crankSpeed) + "\" dependenciesKind=\"dependent" : "") + "\"/>\n";
    unknowns += "      <Unknown index=\"" + index + "\"/>\n";
  }
  return "  <ModelStructure>\n    <Outputs>\n" + outputs + "    </Outputs>\n    <InitialUnknowns>\n" + unknowns +
         "    </InitialUnknowns>\n  </ModelStructure>\n";
}

void writeText(const std::string& path, const std::string& text) {
  std::ofstream out(utf8Path(path), std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace

json interfaceJson(const DriveInterface& di) {
  json vars = json::array();
  for (const InterfaceVariable& v : di.variables) vars.push_back(variableJson(v));
  return {{"schema", kInterfaceSchema}, {"modelIdentifier", di.modelIdentifier}, {"guid", di.guid},
          {"drive", kDriveFile}, {"variables", vars}};
}

std::string interfaceDifference(const json& mine, const json& theirs, bool namesOnly) {
  const std::size_t n = std::min(mine.size(), theirs.size());
  for (std::size_t i = 0; i < n; ++i) {
    const json& a = mine[i];
    const json& b = theirs[i];
    bool same = true;
    if (namesOnly)
      for (const char* key : kInterfaceFields) same = same && a.value(key, json()) == b.value(key, json());
    else
      same = a == b;
    if (!same)
      return "variable " + std::to_string(i + 1) + ": " + a.dump() + " against " + b.dump();
  }
  if (mine.size() != theirs.size())
    return std::to_string(mine.size()) + " variables against " + std::to_string(theirs.size());
  return "";
}

std::string modelDescriptionXml(const DriveInterface& di) {
  std::string xml = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<fmiModelDescription\n  fmiVersion=\"2.0\"\n"
                    "  modelName=\"" + escaped(di.modelName) + "\"\n  guid=\"" + di.guid + "\"\n  description=\"" +
                    escaped(di.description) + "\"\n  generationTool=\"ChainDrive\"\n  version=\"0.1.0\"\n"
                    "  variableNamingConvention=\"structured\"\n  numberOfEventIndicators=\"0\">\n";
  std::string coSimulation = kCoSimulation;
  coSimulation.replace(coSimulation.find("%ID%"), 4, di.modelIdentifier);
  xml += coSimulation + "\n  <ModelVariables>\n";
  for (std::size_t i = 0; i < di.variables.size(); ++i) xml += scalarVariable(di.variables[i], i + 1);
  xml += "  </ModelVariables>\n\n" + modelStructure(di) + "</fmiModelDescription>\n";
  return xml;
}

DriveInterface writeFmuFiles(const std::string& dir, const std::string& driveText) {
  const DriveInterface di = driveInterface(parseDriveDescription(driveText));
  const std::string resources = dir + "/resources";
  std::error_code ec;
  std::filesystem::create_directories(utf8Path(resources), ec);
  if (ec) throw std::runtime_error("cannot create " + resources + ": " + ec.message());
  writeText(dir + "/modelDescription.xml", modelDescriptionXml(di));
  writeText(resources + "/" + kInterfaceFile, interfaceJson(di).dump(1) + "\n");
  writeText(resources + "/" + kDriveFile, driveText);
  return di;
}

}  // namespace chaindrive
