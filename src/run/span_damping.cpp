#include "run/span_damping.h"

#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <stdexcept>
#include <vector>

#include <nlohmann/json.hpp>

#include "description/drive_description.h"
#include "math/elementary.h"
#include "run/simulation.h"
#include "span/calibration_cache.h"
#include "span/seat_calibration.h"
#include "span/span_calibration.h"
#include "utf8_path.h"

namespace chaindrive {

namespace {

using json = nlohmann::json;
constexpr int kDampingCacheFormat = 1;
constexpr double kFitMinHz = 111.0, kFitMaxHz = 2000.0;  // two periods in the window; above the modes
constexpr double kCommunicationStep = 1e-4;              // [s] the samples' spacing
constexpr double kRatioTolerance = 0.02, kMaxScale = 100.0;
constexpr int kMaxIterations = 10;

// The run's options: the drive's own defaults of the fidelity, compliant contacts.
SimulationOptions runOptions(const Model& m, Fidelity fidelity, const span::SpanModel* sm) {
  SimulationOptions opt;
  opt.fidelity = fidelity;
  opt.contactMethod = ContactMethod::Compliant;
  const SolverDefaults d = ownSolverDefaults(m, opt);
  opt.integrator.method = d.method;
  opt.integrator.fixed.step = d.step;
  if (sm) opt.spanModel = std::make_shared<const span::SpanModel>(*sm);
  return opt;
}

std::unique_ptr<HeldInputs> referenceInputs(const Model& m, double crankSpeed) {
  auto in = std::make_unique<HeldInputs>(m);
  in->values = span::seatReferenceInputs(m);
  in->values.crankSpeed = crankSpeed;
  return in;
}

int angleState(const Simulation& sim, int rotor) {
  return sim.spanModel() ? sim.spanModel()->stateAngle[rotor] : sim.model().rotors[rotor].stateAngle;
}

// The state after the run-in at the reference point.
std::vector<double> runIn(const std::shared_ptr<const Model>& m, const SimulationOptions& opt) {
  Simulation sim(m, opt, referenceInputs(*m, span::kSeatReferenceSpeed));
  sim.start(0.0);
  sim.advanceTo(kDampingRunInRevolutions * 2.0 * kPi / span::kSeatReferenceSpeed);
  return sim.state();
}

// From y0 at crankshaft speed w: the loaded sprockets' angles over the fit's window after the
// pulse (or at the same times without it).
std::vector<std::vector<double>> pulseRun(const std::shared_ptr<const Model>& m, const SimulationOptions& opt,
                                          const std::vector<double>& y0, double w, bool pulse) {
  auto owned = referenceInputs(*m, w);
  HeldInputs& in = *owned;
  Simulation sim(m, opt, std::move(owned));
  sim.startFrom(0.0, y0);
  const std::vector<int> loaded = span::loadedSprockets(*m);
  const long long pulseFrom = std::llround(kDampingWait / kCommunicationStep);
  const long long pulseSteps = std::llround(kDampingPulseLength / kCommunicationStep);
  const long long first = pulseFrom + std::llround(kDampingFitFrom / kCommunicationStep);
  const long long last = pulseFrom + std::llround(kDampingFitTo / kCommunicationStep);
  std::vector<std::vector<double>> angles(loaded.size());
  for (long long k = 0; k < last; ++k) {
    const bool on = pulse && k >= pulseFrom && k < pulseFrom + pulseSteps;
    for (int r : loaded) in.values.loadTorque[r] = span::kSeatReferenceLoad + (on ? kDampingPulse : 0.0);
    // the fit's samples are 0.1 ms apart: a solver step that does not divide it would sample elsewhere
    const double wanted = static_cast<double>(k + 1) * kCommunicationStep;
    if (std::fabs(sim.advanceTo(wanted) - wanted) > 1e-9 * kCommunicationStep)
      throw std::runtime_error("span damping: the solver's grid misses t = " + std::to_string(wanted) +
                               " s; its step must divide " + std::to_string(kCommunicationStep) + " s");
    if (k + 1 >= first)
      for (std::size_t c = 0; c < loaded.size(); ++c) angles[c].push_back(sim.state()[angleState(sim, loaded[c])]);
  }
  return angles;
}

// The mode of the pairs' mean response (pulsed less plain run) from y0.
MeasuredMode measureMode(const std::shared_ptr<const Model>& m, const SimulationOptions& opt,
                         const std::vector<double>& y0, int pairs) {
  std::vector<std::vector<double>> mean;
  double pairEnergy = 0.0;
  for (int p = 0; p < pairs; ++p) {
    const double w = span::kSeatReferenceSpeed * (1.0 + 1e-9 * p);
    const auto plain = pulseRun(m, opt, y0, w, false), pulsed = pulseRun(m, opt, y0, w, true);
    if (mean.empty()) mean.assign(plain.size(), std::vector<double>(plain[0].size(), 0.0));
    for (std::size_t c = 0; c < plain.size(); ++c)
      for (std::size_t i = 0; i < plain[c].size(); ++i) {
        const double response = pulsed[c][i] - plain[c][i];
        mean[c][i] += response / pairs;
        pairEnergy += response * response / pairs;
      }
  }
  std::vector<double> t;
  for (std::size_t i = 0; i < mean[0].size(); ++i) t.push_back(kDampingFitFrom + static_cast<double>(i) * kCommunicationStep);
  double meanEnergy = 0.0;
  for (const std::vector<double>& c : mean)
    for (double v : c) meanEnergy += v * v;
  MeasuredMode r;
  r.mode = fitDampedMode(t, mean, kFitMinHz, kFitMaxHz);
  r.coherent = pairEnergy > 0.0 ? meanEnergy / pairEnergy : 1.0;
  return r;
}

// The span model's mode with its dampers scaled.
MeasuredMode spanMode(const std::shared_ptr<const Model>& m, span::SpanModel sm, double scale) {
  span::setDampingScale(sm, scale);
  const SimulationOptions opt = runOptions(*m, Fidelity::Span, &sm);
  return measureMode(m, opt, runIn(m, opt), 1);
}

}  // namespace

SpanDampingCalibration identifySpanDamping(const std::shared_ptr<const Model>& m, const span::SpanModel& sm) {
  const std::clock_t t0 = std::clock();
  SpanDampingCalibration c;
  const SimulationOptions linkOpt = runOptions(*m, Fidelity::Link, nullptr);
  c.link = measureMode(m, linkOpt, runIn(m, linkOpt), kDampingLinkPairs);
  c.spanBefore = c.span = spanMode(m, sm, 1.0);
  auto finish = [&](const std::string& note) {
    c.note = note;
    c.cpuSeconds = static_cast<double>(std::clock() - t0) / CLOCKS_PER_SEC;
    return c;
  };
  const double target = c.link.mode.dampingRatio;
  if (c.link.mode.atBound || target > 0.3) return finish("the link model's response is not one mode");
  if (c.span.mode.dampingRatio >= target) {  // (the joints' dampers are the answer)
    c.identified = true;
    return finish("the spans' dampers damp the mode as much already");
  }
  // the secant method on ln(scale), from 1 and a proportional guess
  double s0 = 0.0, z0 = c.span.mode.dampingRatio;
  double s1 = math::log(std::min(kMaxScale, target / z0)), z1 = 0.0;
  for (c.iterations = 1; c.iterations <= kMaxIterations; ++c.iterations) {
    c.span = spanMode(m, sm, math::exp(s1));
    z1 = c.span.mode.dampingRatio;
    c.scale = math::exp(s1);
    if (std::fabs(z1 / target - 1.0) <= kRatioTolerance) {
      c.identified = true;
      return finish("");
    }
    const double next = z1 != z0 ? s1 + (target - z1) * (s1 - s0) / (z1 - z0) : s1 + 0.5;
    s0 = s1, z0 = z1;
    s1 = std::min(math::log(kMaxScale), std::max(0.0, next));
    if (s1 == s0) break;  // at a bound
  }
  return finish("the span model's damping ratio " + std::to_string(z1) + " at the scale " + std::to_string(c.scale) +
                " misses the link model's " + std::to_string(target) + " by more than 2 %");
}

std::string describeSpanDamping(const SpanDampingCalibration& c) {
  char line[600];
  std::snprintf(line, sizeof line,
                "damping: the link model's camshafts' mode in phase %.1f Hz, damping ratio %.4f (%d twin pairs, "
                "coherent %.2f, fit residual %.2f); the span model's %.1f Hz, %.4f with the joints' dampers, %.1f Hz, "
                "%.4f with them scaled by %.3g (%d runs); %s%.1f s CPU",
                c.link.mode.frequency, c.link.mode.dampingRatio, kDampingLinkPairs, c.link.coherent,
                c.link.mode.residual, c.spanBefore.mode.frequency, c.spanBefore.mode.dampingRatio,
                c.span.mode.frequency, c.span.mode.dampingRatio, c.scale, c.iterations,
                c.note.empty() ? "" : (c.note + "; ").c_str(), c.cpuSeconds);
  return line;
}

namespace {

double number(const json& j) { return span::fromHexNumber(j.get<std::string>()); }

json modeJson(const MeasuredMode& m) {
  return {{"frequency_Hz", span::hexNumber(m.mode.frequency)}, {"dampingRatio", span::hexNumber(m.mode.dampingRatio)},
          {"residual", span::hexNumber(m.mode.residual)}, {"atBound", m.mode.atBound},
          {"coherent", span::hexNumber(m.coherent)}};
}

MeasuredMode modeFrom(const json& j) {
  MeasuredMode m;
  m.mode.frequency = number(j.at("frequency_Hz"));
  m.mode.dampingRatio = number(j.at("dampingRatio"));
  m.mode.residual = number(j.at("residual"));
  m.mode.atBound = j.at("atBound");
  m.coherent = number(j.at("coherent"));
  return m;
}

bool readCachedDamping(const std::string& file, SpanDampingCalibration& c) {
  json j;
  if (!span::readCacheFile(file, kDampingCacheFormat, j)) return false;
  try {
    c.identified = j.at("identified");
    c.scale = number(j.at("scale"));
    c.link = modeFrom(j.at("link"));
    c.spanBefore = modeFrom(j.at("spanBefore"));
    c.span = modeFrom(j.at("span"));
    c.iterations = j.at("iterations");
    c.cpuSeconds = j.at("cpuSeconds");
    c.note = j.at("note");
    return true;
  } catch (const json::exception&) {
    return false;  // a damaged file: identified afresh
  }
}

std::string cachedJson(const SpanDampingCalibration& c) {
  const json j = {{"format", kDampingCacheFormat}, {"identified", c.identified}, {"scale", span::hexNumber(c.scale)},
                  {"link", modeJson(c.link)}, {"spanBefore", modeJson(c.spanBefore)}, {"span", modeJson(c.span)},
                  {"iterations", c.iterations}, {"cpuSeconds", c.cpuSeconds}, {"note", c.note}};
  return j.dump(1) + "\n";
}

}  // namespace

SpanDampingCalibration calibrateSpanDamping(const std::shared_ptr<const Model>& m, span::SpanModel& sm) {
  const SpanModelDesc& want = m->description.spanModel;
  SpanDampingCalibration c;
  if (want.damping != SpanModelDesc::Source::Identified) {  // the joints' dampers, or as the drive gives
    c.scale = want.damping == SpanModelDesc::Source::Given ? want.dampingScale : 1.0;
    span::setDampingScale(sm, c.scale);
    return c;
  }
  const std::string dir = span::calibrationCacheDir();
  const std::string file = dir.empty() ? "" : dir + "/spandamping-" + span::calibrationKey(*m) + ".json";
  const bool cached = !file.empty() && readCachedDamping(file, c);
  if (!cached) {
    c = identifySpanDamping(m, sm);
    if (!file.empty()) span::writeCacheFile(dir, file, cachedJson(c));
  }
  if (!c.identified)  // (a scale that misses the link model's mode is no identified one)
    throw DescriptionError({"spanModel.damping: \"identified\": " + c.note + "; give the scale as a number instead (the "
                            "spans' dampers over the joints' in series, 0 to 1000)"});
  span::setDampingScale(sm, c.scale);
  sm.notes.push_back("calibration: " + describeSpanDamping(c) + (cached ? " (from the cache " + file + ")" : ""));
  return c;
}

}  // namespace chaindrive
