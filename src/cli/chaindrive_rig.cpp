// chaindrive-rig: the hydraulic tensioner alone on the suppliers' bench (src/rig/tensioner_rig.h):
// a force-displacement loop under a prescribed sinusoidal plunger motion, or a leak-down under a
// constant force with the supply closed. Writes the samples as CSV and prints a summary.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

#include "cli/arguments.h"
#include "description/drive_description.h"
#include "rig/tensioner_rig.h"

using namespace chaindrive;

namespace {

constexpr const char* kTool = "chaindrive-rig";

void usage() {
  std::puts(
      "usage: chaindrive-rig [--test loop|leak-down] [--drive FILE] [--csv FILE]\n"
      "                      [--frequency HZ] [--amplitude M] [--mean M] [--force N] [--duration S]\n"
      "                      [--temperature K] [--supply PA] [--clearance M] [--air-fraction X] [--no-relief]\n"
      "                      [--initial-pressure PA] [--integrator NAME] [--step S] [--rtol R] [--output-step S]\n"
      "  The tensioner of the drive's tensioner.hydraulic block (default: the embedded drive; its\n"
      "  block's defaults when it has none) on the bench:\n"
      "  loop       the plunger on x(t) = mean + amplitude sin(2 pi f t), the supply open\n"
      "             (defaults: 100 Hz, 0.1 mm, mean 0; duration max(0.25 s, 10 periods))\n"
      "  leak-down  a constant force (default 300 N) pushing the plunger in, the supply closed\n"
      "             (duration 0.3 s)\n"
      "  The overrides (SI: K, Pa gauge, m) replace the block's values. Integrator: arkode-erk at\n"
      "  rtol 1e-8 by default (--step: the fixed-step methods' step). CSV columns: time, stroke, rate,\n"
      "  pressure, force, the flows check, leak, relief, vapour [m3/s], the volumes that flowed\n"
      "  [m3], the cavity's volume [m3], supply and dissipated power [W]. The summary: the last period's peak and least\n"
      "  force and mean pressure (loop), the mean plunger speed of the last third and the leak's\n"
      "  speed at the mean pressure (leak-down).");
}

struct RigArguments {
  RigSetup setup;
  std::string drive, csv;
  double duration = -1.0, outputStep = -1.0;
  double temperature = -1.0, supply = -1.0, clearance = -1.0, airFraction = -1.0;
  bool noRelief = false;
  IntegratorSettings integrator;
};

RigArguments parseArguments(cli::Arguments& args) {
  RigArguments r;
  // Dormand-Prince at a tight tolerance: the rig is small, and fixed-verlet lags the pressure
  // behind the plunger (docs/hydraulic_tensioner.md, "The stable step")
  r.integrator.method = IntegratorMethod::ArkodeErk;
  r.integrator.adaptive.rtol = 1e-8;
  r.integrator.fixed.step = 2.5e-6;
  while (args.next()) {
    const std::string& a = args.current();
    if (a == "--test") r.setup.test = args.choice<RigTest>();
    else if (a == "--drive") r.drive = args.value();
    else if (a == "--csv") r.csv = args.value();
    else if (a == "--frequency") r.setup.frequency = args.number();
    else if (a == "--amplitude") r.setup.amplitude = args.number();
    else if (a == "--mean") r.setup.mean = args.number();
    else if (a == "--force") r.setup.force = args.number();
    else if (a == "--duration") r.duration = args.number();
    else if (a == "--output-step") r.outputStep = args.number();
    else if (a == "--temperature") r.temperature = args.number();
    else if (a == "--supply") r.supply = args.number();
    else if (a == "--clearance") r.clearance = args.number();
    else if (a == "--air-fraction") r.airFraction = args.number();
    else if (a == "--no-relief") r.noRelief = true;
    else if (a == "--initial-pressure") r.setup.initialPressure = args.number();
    else if (a == "--integrator") r.integrator.method = args.choice<IntegratorMethod>();
    else if (a == "--step") r.integrator.fixed.step = args.number();
    else if (a == "--rtol") r.integrator.adaptive.rtol = args.number();
    else throw std::invalid_argument("unknown argument '" + a + "'");
  }
  return r;
}

// The drive's device with the command line's overrides.
HydraulicTensionerDesc tensionerOf(const RigArguments& a) {
  HydraulicTensionerDesc t = cli::loadDrive(a.drive).tensioner.hydraulic;
  if (a.temperature >= 0.0) t.oilTemperature = a.temperature;
  if (a.supply >= 0.0) t.supplyPressure = a.supply;
  if (a.clearance >= 0.0) t.clearance = a.clearance;
  if (a.airFraction >= 0.0) t.oil.airFraction = a.airFraction;
  if (a.noRelief) t.reliefValve.present = false;
  return t;
}

void writeCsv(const std::string& path, const std::vector<RigSample>& samples) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path);
  f << "time,stroke,rate,pressure,force,check,leak,relief,vapour,volumeCheck,volumeLeak,volumeRelief,volumeVapour,"
       "vapourVolume,supplyPower,dissipatedPower\n";
  char line[512];
  for (const RigSample& s : samples) {
    const HydraulicFlows& q = s.device.flows;
    std::snprintf(line, sizeof line, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n",
                  s.time, s.stroke, s.rate, s.pressure, s.device.force, q.check, q.leak, q.relief, q.vapour,
                  s.volumeCheck, s.volumeLeak, s.volumeRelief, s.volumeVapour, s.device.vapourVolume, s.device.supplyPower,
                  s.device.dissipatedPower);
    f << line;
  }
}

// The last period's extremes of the force and its mean pressure.
void printLoopSummary(const RigSetup& setup, const std::vector<RigSample>& samples) {
  const double tEnd = samples.back().time, tStart = tEnd - 1.0 / setup.frequency;
  double fMax = -1e300, fMin = 1e300, pSum = 0.0;
  int n = 0;
  for (const RigSample& s : samples)
    if (s.time > tStart + 1e-12) {
      fMax = std::max(fMax, s.device.force);
      fMin = std::min(fMin, s.device.force);
      pSum += s.pressure;
      ++n;
    }
  std::printf("loop: %.6g Hz, amplitude %.6g mm: last period force %.6g .. %.6g N, mean pressure %.6g bar\n",
              setup.frequency, setup.amplitude * 1e3, fMin, fMax, n ? pSum / n * 1e-5 : 0.0);
}

// The plunger's mean speed over the last third against the leak's speed at the mean pressure.
void printLeakDownSummary(const TensionerRig& rig, const std::vector<RigSample>& samples) {
  const RigSample& b = samples[samples.size() * 2 / 3];
  const RigSample& e = samples.back();
  double pSum = 0.0;
  int n = 0;
  for (std::size_t i = samples.size() * 2 / 3; i < samples.size(); ++i, ++n) pSum += samples[i].pressure;
  const double p = pSum / n, speed = (e.stroke - b.stroke) / (e.time - b.time);
  const double leakSpeed = -leakConductance(rig.tensioner(), rig.viscosity()) * p / plungerArea(rig.tensioner());
  std::printf("leak-down: mean pressure %.6g bar, plunger speed %.6g mm/s, leak flow over the area %.6g mm/s\n",
              p * 1e-5, speed * 1e3, leakSpeed * 1e3);
}

int runRigTool(RigArguments a) {
  a.setup.tensioner = tensionerOf(a);
  const bool loop = a.setup.test == RigTest::Loop;
  const double duration = a.duration >= 0.0 ? a.duration : loop ? std::max(0.25, 10.0 / a.setup.frequency) : 0.3;
  double outputStep = a.outputStep;
  if (outputStep <= 0.0) {  // about 400 samples a period (a whole number of fixed steps)
    const double want = loop ? 1.0 / (400.0 * a.setup.frequency) : 1e-4;
    const IntegratorMethod m = a.integrator.method;
    const bool adaptive = m == IntegratorMethod::ArkodeErk || m == IntegratorMethod::CvodeBdfKlu ||
                          m == IntegratorMethod::CvodeBdfBand;
    const double h = adaptive ? 0.0 : a.integrator.fixed.step;
    outputStep = h > 0.0 ? std::max(1.0, std::floor(want / h)) * h : want;
  }
  const std::vector<RigSample> samples = runRig(a.setup, a.integrator, duration, outputStep);
  if (!a.csv.empty()) writeCsv(a.csv, samples);
  if (loop) printLoopSummary(a.setup, samples);
  else printLeakDownSummary(TensionerRig(a.setup), samples);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return cli::runTool(kTool, argc, argv, usage, parseArguments, runRigTool); }
