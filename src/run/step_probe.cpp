#include "run/step_probe.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>

#include <nlohmann/json.hpp>

#include "math/vec2.h"
#include "run/inputs.h"
#include "run/simulation.h"
#include "span/calibration_cache.h"
#include "utf8_path.h"

namespace chaindrive {

namespace {

using json = nlohmann::json;
constexpr int kCacheFormat = 1;

// The probe's inputs: the mean speed with its vibration, the load on every loaded sprocket.
std::unique_ptr<InputSignal> probeInputs(const Model& m) {
  const double w0 = kProbeSpeedRpm * 2.0 * kPi / 60.0;
  auto h = std::make_unique<HarmonicInputs>(m, w0);
  h->addOrder({kProbeVibrationOrder, kProbeVibrationDeg * kPi / 180.0, 0.0});
  for (const SprocketDesc& sp : m.description.sprockets)
    if (sp.loaded) h->setLoad(m.rotorIndex(sp.name), kProbeLoad);
  return h;
}

// (input work - dissipated energy - change of the stored energy) / dissipated energy between a and b.
double energyBalance(const EnergyTerms& a, const EnergyTerms& b) {
  const double dissipated = b.dissipated - a.dissipated;
  const double stored = (b.kinetic + b.elastic + b.gravity) - (a.kinetic + a.elastic + a.gravity);
  return (b.inputWork - a.inputWork - dissipated - stored) / dissipated;
}

std::string cacheFile(const Model& m, IntegratorMethod method, long long fromDivisions) {
  const std::string dir = span::calibrationCacheDir();
  if (dir.empty()) return "";
  return dir + "/step-" + span::calibrationKey(m) + "-" + choiceName(method) + "-" + std::to_string(fromDivisions) +
         ".json";
}

// The cached ladder, if the file holds one (a damaged or foreign file: none, probed afresh).
bool readCached(const std::string& file, ProbedStep& p) {
  json j;
  if (!span::readCacheFile(file, kCacheFormat, j)) return false;
  try {
    ProbedStep c;
    c.divisions = j.at("divisions");
    c.passed = j.at("passed");
    for (const json& r : j.at("runs"))
      c.runs.push_back({r.at("divisions"), r.at("blewUp"), r.at("energyBalance"), r.at("failure")});
    p = c;
    return true;
  } catch (const json::exception&) {
    return false;
  }
}

}  // namespace

json probeJson(const ProbedStep& p) {
  json runs = json::array();
  for (const ProbeRun& r : p.runs)
    runs.push_back({{"divisions", r.divisions}, {"blewUp", r.blewUp}, {"energyBalance", r.energyBalance},
                    {"failure", r.failure}});
  return {{"divisions", p.divisions}, {"passed", p.passed}, {"balanceLimit", kProbeBalanceLimit}, {"runs", runs}};
}

bool ProbeRun::passes() const { return !blewUp && std::fabs(energyBalance) <= kProbeBalanceLimit; }

ProbeRun probeRun(const Model& m, IntegratorMethod method, long long divisions) {
  SimulationOptions opt;
  opt.contactMethod = ContactMethod::Compliant;
  opt.integrator.method = method;
  opt.integrator.fixed.step = kStepInterval / static_cast<double>(divisions);
  opt.blowUpAdvice = false;  // (the advice would probe again)
  ProbeRun r;
  r.divisions = divisions;
  Simulation sim(std::make_shared<const Model>(m), opt, probeInputs(m));
  sim.start(0.0);
  const EnergyTerms start = sim.outputs().energy;
  try {
    sim.advanceTo(kProbeDuration);
  } catch (const IntegrationError& e) {
    r.blewUp = true;
    r.failure = e.what();
    return r;
  }
  r.energyBalance = energyBalance(start, sim.outputs().energy);
  if (!std::isfinite(r.energyBalance)) r.blewUp = true, r.failure = "the energy balance is not finite";
  return r;
}

ProbedStep probeStep(const Model& m, IntegratorMethod method, long long fromDivisions) {
  ProbedStep p;
  const std::string file = cacheFile(m, method, fromDivisions);
  if (!file.empty() && readCached(file, p)) return p;
  // the rungs from the estimate's division, each a tenth more steps, up to kProbeMostDivisions
  for (long long n = fromDivisions; static_cast<int>(p.runs.size()) < kProbeMaxRuns && !p.passed && n <= kProbeMostDivisions;
       n = std::max(n + 1, static_cast<long long>(std::ceil(kProbeLadderFactor * static_cast<double>(n))))) {
    p.runs.push_back(probeRun(m, method, n));
    p.passed = p.runs.back().passes();
  }
  p.divisions = p.runs.empty() ? fromDivisions : p.runs.back().divisions;  // (the last rung tried)
  if (!file.empty()) {
    json cached = probeJson(p);
    cached["format"] = kCacheFormat;
    span::writeCacheFile(span::calibrationCacheDir(), file, cached.dump(1) + "\n");
  }
  return p;
}

std::string describeProbe(const ProbedStep& p) {
  auto run = [](const ProbeRun& r) {
    if (r.blewUp) return "1e-4/" + std::to_string(r.divisions) + " blew up";
    char s[64];
    std::snprintf(s, sizeof s, "1e-4/%lld %+.2f %%", r.divisions, 100.0 * r.energyBalance);
    return std::string(s);
  };
  std::string text = p.runs.empty() ? "not run" : "energy balance " + run(p.runs.back());
  if (p.runs.size() > 1) {
    text += " (";
    for (std::size_t i = 0; i + 1 < p.runs.size(); ++i) text += (i ? ", " : "") + run(p.runs[i]);
    text += ")";
  }
  return text;
}

}  // namespace chaindrive
