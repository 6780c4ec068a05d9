// Helpers for the C++ tests: drives derived from the default one, and short runs.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "description/drive_description.h"
#include "run/inputs.h"
#include "assembly/model.h"
#include "run/simulation.h"
#include "dynamics/dynamics.h"
#include "statics/preload.h"

namespace chaindrive::test {

/// A choice by its name, as the boundary parses it (the tests read better with the names).
template <class E>
E named(const std::string& name) {
  return parseChoice<E>(name, "test choice");
}
/// The same, an empty name for none (the drive's).
template <class E>
std::optional<E> namedOrDrive(const std::string& name) {
  if (name.empty()) return std::nullopt;
  return named<E>(name);
}

inline nlohmann::json defaultJson() { return nlohmann::json::parse(defaultDriveJson(), nullptr, true, true); }

/// The default drive with a modification applied to its JSON.
inline DriveDescription modifiedDefault(const std::function<void(nlohmann::json&)>& edit) {
  nlohmann::json j = defaultJson();
  edit(j);
  return parseDriveDescription(j.dump());
}

/// The problems reported for a modified default drive (empty if it is valid and assembles).
inline std::vector<std::string> problemsOf(const std::function<void(nlohmann::json&)>& edit) {
  try {
    assemble(modifiedDefault(edit));
  } catch (const DescriptionError& e) {
    return e.problems();
  }
  return {};
}

// A description's problems one per line, for a failed assertion's message.
inline std::string problemLines(const std::vector<std::string>& problems) {
  std::string lines;
  for (const auto& problem : problems) lines += problem + "\n";
  return lines;
}

inline nlohmann::json& sprocketJson(nlohmann::json& j, const std::string& name) {
  for (auto& s : j["sprockets"])
    if (s["name"] == name) return s;
  throw std::runtime_error("no sprocket " + name);
}

inline nlohmann::json& guideJson(nlohmann::json& j, const std::string& name) {
  for (auto& g : j["guides"])
    if (g["name"] == name) return g;
  throw std::runtime_error("no guide " + name);
}

/// The default drive, assembled once per test program (immutable).
/// The default drive with the spring-damper tensioner law it had before its hydraulic tensioner
/// (harness/drive/design.py: spring_damper_variant), for the methods and checks the law serves.
inline void useSpringDamperTensioner(nlohmann::json& j) {
  auto& t = j["tensioner"];
  t.erase("model");
  t.erase("hydraulic");
  t["preload"] = 60.0;
  t["damping"] = 3000.0;
  t["dampingExtension"] = 300.0;
}

inline std::shared_ptr<const Model> defaultModel() {
  static const std::shared_ptr<const Model> m = std::make_shared<const Model>(assemble(defaultDriveDescription()));
  return m;
}

/// Constant crankshaft speed and constant camshaft load torques (3 N m each by default).
inline std::unique_ptr<InputSignal> constantLoads(const Model& m, double rpm, double tauIntake = 3.0,
                                                  double tauExhaust = 3.0) {
  auto in = std::make_unique<HarmonicInputs>(m, rpm * 2.0 * kPi / 60.0);
  in->setLoad(m.rotorIndex("camshaftIntake"), tauIntake);
  in->setLoad(m.rotorIndex("camshaftExhaust"), tauExhaust);
  return in;
}

// A running state: the nominal pose at 3000 rpm, advanced by a short explicit integration so
// that contacts are closed and joints stretched.
inline std::vector<double> runningState(const Model& m, const InputSignal& in) {
  std::vector<double> y = nominalState(m, 314.159);
  Data d(m);
  std::vector<double> f(m.nStates);
  const double h = 2e-7;
  for (int k = 0; k < 2000; ++k) {  // 0.4 ms, symplectic Euler with small steps
    forwardCompliant(m, d, in, k * h, y.data(), f.data());
    // (the link velocities are the state's entries from 3 links on, model.h)
    const int n3 = 3 * m.chain.links;
    for (int i = n3; i < m.nStates; ++i) y[i] += h * f[i];
    for (int i = 0; i < n3; ++i) y[i] += h * y[i + n3];
  }
  return y;
}

/// The tensioner force every 0.1 ms of a 3000 rpm run from the preload with `integrator`.
inline std::vector<double> tensionerRun(const std::shared_ptr<const Model>& m, const IntegratorSettings& integrator,
                                        double tEnd) {
  SimulationOptions opt;
  opt.integrator = integrator;
  Simulation sim(m, opt, constantLoads(*m, 3000.0));
  sim.start(0.0);
  std::vector<double> tension;
  for (int k = 1; k * 1e-4 <= tEnd + 1e-12; ++k) {
    sim.advanceTo(1e-4 * k);
    tension.push_back(sim.outputs().tensionerForce);
  }
  return tension;
}

/// Series of one output sampled at every output step.
struct Series {
  std::vector<double> t, value;
};

}  // namespace chaindrive::test
