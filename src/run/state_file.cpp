#include "run/state_file.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace chaindrive {

namespace {

using json = nlohmann::json;

// /4: the step means' accumulators at the end (model.h: ImpulseStates; /3 and /2 are the same
// without them, read with them zero); /3: a hydraulic chamber's state in the link model is its
// oil content; /2 held its pressure there (the same layout otherwise); /2 laid the state out
// component by component (model.h); /1 held 6 components per link
constexpr const char* kSchema = "chaindrive.state/4";
constexpr const char* kContentSchema = "chaindrive.state/3";
constexpr const char* kPressureSchema = "chaindrive.state/2";

std::string hex(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%a", v);
  return buf;
}

double fromHex(const std::string& path, const std::string& field, const json& j) {
  if (!j.is_string()) throw std::runtime_error(path + ": " + field + " must be a hexadecimal floating-point string");
  const std::string s = j.get<std::string>();
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0' || !std::isfinite(v))
    throw std::runtime_error(path + ": " + field + " = '" + s + "' is not a finite number");
  return v;
}

}  // namespace

void writeStateFile(const std::string& path, const Model& m, const StateSnapshot& s, Fidelity fidelity) {
  json j;
  j["schema"] = kSchema;
  j["drive"] = m.name;
  if (fidelity != Fidelity::Link) j["fidelity"] = choiceName(fidelity);
  j["links"] = m.chain.links;
  j["states"] = s.y.size();
  j["time"] = hex(s.time);
  j["time_s"] = s.time;
  json y = json::array();
  for (double v : s.y) y.push_back(hex(v));
  j["y"] = y;
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot be written");
  out << j.dump(1) << "\n";
  if (!out) throw std::runtime_error(path + ": write failed");
}

StateSnapshot readStateFile(const std::string& path, const Model& m, int states, Fidelity fidelity) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot be opened");
  json j;
  try {
    in >> j;
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": not valid JSON (" + e.what() + ")");
  }
  if (j.is_object() && j.value("schema", "") == "chaindrive.state/1")
    throw std::runtime_error(path + ": a state file of the earlier state layout (schema \"chaindrive.state/1\", 6 "
                             "components per link); this version reads \"" + std::string(kSchema) +
                             "\" (the link components by component): save the state again");
  const bool pressureState = j.is_object() && j.value("schema", "") == kPressureSchema;
  if (pressureState && fidelity == Fidelity::Link && m.stateChamberOil >= 0)
    throw std::runtime_error(path + ": a state file of the earlier state layout (schema \"" +
                             std::string(kPressureSchema) + "\": the hydraulic chamber's pressure as its state); "
                             "this version reads \"" + std::string(kSchema) + "\" (its oil content): save the state again");
  const bool earlier = pressureState || (j.is_object() && j.value("schema", "") == kContentSchema);
  if (!earlier && (!j.is_object() || j.value("schema", "") != kSchema))
    throw std::runtime_error(path + ": not a state file (schema must be \"" + std::string(kSchema) + "\")");
  const int accumulators = earlier ? static_cast<int>(m.rotors.size()) + 1 : 0;  // (appended, zero)
  states -= accumulators;
  const std::string fileFidelity = j.value("fidelity", "link");
  if (choiceOf<Fidelity>(fileFidelity) != fidelity)
    throw std::runtime_error(path + ": a state of the " + fileFidelity + " fidelity; this run is of the " +
                             choiceName(fidelity) + " fidelity");
  const int fileLinks = j.value("links", -1), fileStates = j.value("states", -1);
  if (fileLinks != m.chain.links || fileStates != states)
    throw std::runtime_error(path + ": a state of another drive (" + std::to_string(fileLinks) + " links, " +
                             std::to_string(fileStates) + " states; this drive has " + std::to_string(m.chain.links) +
                             " links, " + std::to_string(states) + " states)");
  StateSnapshot s;
  s.time = fromHex(path, "time", j["time"]);
  const json& y = j["y"];
  if (!y.is_array() || static_cast<int>(y.size()) != states)
    throw std::runtime_error(path + ": y must be an array of " + std::to_string(states) + " values");
  s.y.resize(y.size());
  for (std::size_t i = 0; i < y.size(); ++i) s.y[i] = fromHex(path, "y[" + std::to_string(i) + "]", y[i]);
  s.y.resize(y.size() + accumulators, 0.0);
  return s;
}

}  // namespace chaindrive
