// chaindrive-run: the solver alone (no FMU). Runs a drive at a mean engine speed for a number of
// engine cycles with constant or tabulated inputs, writes the outputs as CSV and prints CPU time
// and the real-time factor (CPU seconds per simulated second).
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/arguments.h"
#include "cli/contact_stats.h"
#include "description/drive_description.h"
#include "run/defaults.h"
#include "run/inputs.h"
#include "assembly/model.h"
#include "run/simulation.h"
#include "run/state_file.h"

using namespace chaindrive;

namespace {

constexpr const char* kTool = "chaindrive-run";

double secondsOf(clockid_t clock) {
  timespec ts{};
  clock_gettime(clock, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}
double cpuSeconds() { return secondsOf(CLOCK_PROCESS_CPUTIME_ID); }  // (every thread's)
double wallSeconds() { return secondsOf(CLOCK_MONOTONIC); }

void usage() {
  const std::string names = listOfNames(choiceNames<IntegratorMethod>());
  const SolverDefaults& link = solverDefaults(Scene::TimingDrive, Fidelity::Link);
  const SolverDefaults& span = solverDefaults(Scene::TimingDrive, Fidelity::Span);
  const SolverDefaults& clearance = solverDefaults(Scene::TimingDrive, Fidelity::Link, true);
  std::printf(
      "usage: chaindrive-run [options]\n"
      "  --drive FILE            drive description (default: the embedded default drive)\n"
      "  --rpm N                 mean crankshaft speed [rpm] (default 3000)\n"
      "  --cycles N              engine cycles to simulate, 720 deg crank each (default 2)\n"
      "  --duration S            simulated time [s] instead of --cycles\n"
      "  --integrator NAME       %s (default %s)\n"
      "  --contact-method M      compliant, event-driven or time-stepping (default: the drive's)\n"
      "  --joint-model J         journal-bearing or ideal (default: the drive's)\n"
      "  --fidelity F            link (the link-by-link model, default) or span (the span model:\n"
      "                          rotors and spans, src/span/)\n"
      "  --rtol X                relative tolerance of adaptive integrators and of the event-driven\n"
      "                          method (default %g)\n"
      "  --step S                step of fixed-step integrators and of time stepping [s] (default: the\n"
      "                          drive's own, from its stability estimate; the default drive's: the\n"
      "                          fidelity's, link %g, span %g); they step on the grid t0 + k S\n"
      "  --newmark-gamma G       fixed-newmark: 0.5 keeps every mode's amplitude, up to 1 damps the\n"
      "                          modes the step cannot resolve (default 0.5)\n"
      "  --threads N             threads of each evaluation of the link model (default 1; the same\n"
      "                          results for every N; fixed-verlet and its implicit-joint-damping variant)\n"
      "  --max-step S            largest step of adaptive integrators [s] (default unlimited)\n"
      "  --min-step S            adaptive integrators: a smaller step is a step-size collapse [s] (1e-10)\n"
      "  --output-step S         output interval [s] (default 1e-4), rounded to whole grid steps (the\n"
      "                          fixed step, or 1 us for adaptive methods)\n"
      "  --load NAME=TORQUE      constant load torque [N m] on a free sprocket (+ opposes rotation)\n"
      "  --crank-vibration K:A   rotational vibration of engine order K (per crank rev) with angle\n"
      "                          amplitude A [deg]; repeatable\n"
      "  --inputs FILE.csv       time series instead: time,<crank>.w,<sprocket>.tau,... (SI); also\n"
      "                          <pivoting guide>.tau (a torque on it, + in its output sense) and\n"
      "                          tensioner.supplyPressure (gauge, a hydraulic tensioner's)\n"
      "  --link N                monitored link (default: from the drive)\n"
      "  --rebound-threshold V   event driven: rebounds slower than V [m/s] close the contact (0.05)\n"
      "  --gap-tolerance G       rigid contacts: closed within G [m] (1e-8)\n"
      "  --max-event-rate R      event driven: more events per second (over any 100 events) is a\n"
      "                          runaway-event failure (2e5)\n"
      "  --record-lcps DIR:N     rigid contacts: write the first N LCPs to DIR (Siconos format),\n"
      "                          and every LCP not solved (lcp_failed_K.dat)\n"
      "  --no-preload            start from the unloaded nominal pose\n"
      "  --out FILE.csv          write outputs (default: no file)\n"
      "  --initial-state FILE    start from a saved state (its time and state vector; no preload);\n"
      "                          --cycles/--duration then count from that time\n"
      "  --save-state FILE       save the final state (for --initial-state)\n"
      "  --summary FILE.json     write the run's figures (CPU time, counters, failure and its kind)\n"
      "  --quiet                 print the summary only\n"
      "The defaults of method, step and tolerance are the FMU's (chaindrive-info --defaults [--drive\n"
      "FILE]; a drive whose joints have clearance, or rigid contacts: %s, the default drive at %g s).\n"
      "The run prints its step and why; a blow-up names the step it ran with and the step to try.\n",
      names.c_str(), choiceName(link.method), link.tolerance, link.step, span.step, choiceName(clearance.method),
      clearance.step);
}

// ---- the command line ----

struct RunArguments {
  std::string drive, inputsCsv, outPath, initialState, saveState, summaryPath;
  double rpm = 3000.0, cycles = 2.0, duration = -1.0, outputStep = 1e-4;
  SimulationOptions opt;
  // given on the command line; otherwise the fidelity's defaults (run/defaults.h)
  std::optional<IntegratorMethod> method;
  std::optional<double> step, rtol;
  std::string stepReason;  // why the run has its step (run/drive_defaults.h)
  std::vector<std::pair<std::string, double>> loads;
  std::vector<HarmonicInputs::Order> orders;
  bool quiet = false;
};

using cli::Arguments;

void recordLcps(Arguments& args, RunArguments& r) {
  const std::string spec = args.value();  // DIR:COUNT
  const auto c = spec.rfind(':');
  if (c == std::string::npos) throw std::invalid_argument("--record-lcps expects DIRECTORY:COUNT");
  r.opt.integrator.rigid.recordLcpDirectory = spec.substr(0, c);
  r.opt.integrator.rigid.recordLcpCount = static_cast<int>(args.number(spec.substr(c + 1)));
}

void addLoad(Arguments& args, RunArguments& r) {
  const std::string s = args.value();
  const auto eq = s.find('=');
  if (eq == std::string::npos) throw std::invalid_argument("--load expects NAME=TORQUE, got '" + s + "'");
  r.loads.emplace_back(s.substr(0, eq), args.number(s.substr(eq + 1)));
}

void addCrankVibration(Arguments& args, RunArguments& r) {
  const std::string s = args.value();
  const auto c = s.find(':');
  if (c == std::string::npos) throw std::invalid_argument("--crank-vibration expects ORDER:AMPLITUDE_DEG");
  HarmonicInputs::Order o;
  o.order = args.number(s.substr(0, c));
  o.amplitude = args.number(s.substr(c + 1)) * kPi / 180.0;
  r.orders.push_back(o);
}

struct Option {
  const char* name;
  void (*apply)(Arguments& args, RunArguments& r);
};

// clang-format off
const Option kOptions[] = {
  {"--drive",             [](Arguments& a, RunArguments& r) { r.drive = a.value(); }},
  {"--rpm",               [](Arguments& a, RunArguments& r) { r.rpm = a.number(); }},
  {"--cycles",            [](Arguments& a, RunArguments& r) { r.cycles = a.number(); }},
  {"--duration",          [](Arguments& a, RunArguments& r) { r.duration = a.number(); }},
  {"--integrator",        [](Arguments& a, RunArguments& r) { r.method = a.choice<IntegratorMethod>(); }},
  {"--contact-method",    [](Arguments& a, RunArguments& r) { r.opt.contactMethod = a.choice<ContactMethod>(); }},
  {"--joint-model",       [](Arguments& a, RunArguments& r) { r.opt.jointModel = a.choice<JointModel>(); }},
  {"--fidelity",          [](Arguments& a, RunArguments& r) { r.opt.fidelity = a.choice<Fidelity>(); }},
  {"--rebound-threshold", [](Arguments& a, RunArguments& r) { r.opt.integrator.eventDriven.reboundThreshold = a.number(); }},
  {"--gap-tolerance",     [](Arguments& a, RunArguments& r) { r.opt.integrator.rigid.gapTolerance = a.number(); }},
  {"--record-lcps",       recordLcps},
  {"--max-event-rate",    [](Arguments& a, RunArguments& r) { r.opt.integrator.eventDriven.maxEventsPerSecond = a.number(); }},
  {"--rtol",              [](Arguments& a, RunArguments& r) { r.rtol = a.number(); }},
  {"--step",              [](Arguments& a, RunArguments& r) { r.step = a.number(); }},
  {"--newmark-gamma",     [](Arguments& a, RunArguments& r) { r.opt.integrator.newmark.gamma = a.number(); }},
  {"--threads",           [](Arguments& a, RunArguments& r) { r.opt.threads = a.wholeNumber(1, StagePool::kMaxThreads); }},
  {"--max-step",          [](Arguments& a, RunArguments& r) { r.opt.integrator.adaptive.maxStep = a.number(); }},
  {"--min-step",          [](Arguments& a, RunArguments& r) { r.opt.integrator.adaptive.minStep = a.number(); }},
  {"--output-step",       [](Arguments& a, RunArguments& r) { r.outputStep = a.number(); }},
  {"--inputs",            [](Arguments& a, RunArguments& r) { r.inputsCsv = a.value(); }},
  {"--out",               [](Arguments& a, RunArguments& r) { r.outPath = a.value(); }},
  {"--initial-state",     [](Arguments& a, RunArguments& r) { r.initialState = a.value(); }},
  {"--save-state",        [](Arguments& a, RunArguments& r) { r.saveState = a.value(); }},
  {"--summary",           [](Arguments& a, RunArguments& r) { r.summaryPath = a.value(); }},
  {"--link",              [](Arguments& a, RunArguments& r) { r.opt.monitoredLink = static_cast<int>(a.number()); }},
  {"--no-preload",        [](Arguments&, RunArguments& r) { r.opt.preload.enabled = false; }},
  {"--quiet",             [](Arguments&, RunArguments& r) { r.quiet = true; }},
  {"--load",              addLoad},
  {"--crank-vibration",   addCrankVibration},
};
// clang-format on

// The fidelity's solver defaults (run/defaults.h: the row of runs with joints with clearance or
// rigid contacts, or not) where the command line gave no method, step or tolerance: the table's
// (the default drive's) while the command line is read.
void applyDefaults(RunArguments& r, const SolverDefaults& own) {
  applySolverDefaults(own, r.opt.integrator);
  r.opt.integrator.method = r.method.value_or(r.opt.integrator.method);
  r.opt.integrator.fixed.step = r.step.value_or(defaultStep(own, r.opt.integrator.method));
  r.opt.integrator.adaptive.rtol = r.rtol.value_or(r.opt.integrator.adaptive.rtol);
}

// The same for the drive m: its own row (run/drive_defaults.h), the step of the row its method
// takes unless one was given, and why.
void applyDriveDefaults(RunArguments& r, const Model& m) {
  applyDefaults(r, ownTableRow(m, r.opt));
  const StepChoice step = defaultStepChoice(m, r.opt, r.opt.integrator.method, r.step);
  r.opt.integrator.fixed.step = step.step;
  r.stepReason = step.reason;
  r.opt.stepName = "--step";
}

// The options in any order, -h/--help ends the reading; then the ranges of the numbers. A bad
// argument throws (std::invalid_argument, or std::stod's exceptions).
RunArguments parseArguments(Arguments& args) {
  RunArguments r;
  while (args.next()) {
    const auto option = std::find_if(std::begin(kOptions), std::end(kOptions),
                                     [&](const Option& o) { return args.current() == o.name; });
    if (option == std::end(kOptions)) throw std::invalid_argument("unknown argument '" + args.current() + "'");
    option->apply(args, r);
  }
  if (args.help()) return r;
  applyDefaults(r, solverDefaults(Scene::TimingDrive, r.opt.fidelity));
  if (!(r.rpm > 0.0 && r.rpm <= 20000.0)) throw std::invalid_argument("--rpm must be in (0, 20000]");
  if (!(r.outputStep > 0.0)) throw std::invalid_argument("--output-step must be positive");
  if (!(r.opt.integrator.adaptive.rtol > 0.0 && r.opt.integrator.adaptive.rtol < 1.0)) throw std::invalid_argument("--rtol must be in (0, 1)");
  if (!(r.opt.integrator.fixed.step > 0.0)) throw std::invalid_argument("--step must be positive");
  return r;
}

// ---- building the run ----

// "a, b" of the sprockets that take a load (motion "free"; not the prescribed one, not an idler).
std::string loadedSprockets(const DriveDescription& desc) {
  std::string names;
  for (const SprocketDesc& sp : desc.sprockets)
    if (sp.loaded) names += (names.empty() ? "" : ", ") + sp.name;
  return names.empty() ? "none" : names;
}

// The inputs: the table of --inputs, else the mean crank speed with its vibration orders and
// constant load torques on free sprockets.
std::unique_ptr<InputSignal> makeInputs(const Model& m, const RunArguments& r, double w0) {
  if (!r.inputsCsv.empty()) return std::make_unique<TableInputs>(m, r.inputsCsv);
  auto h = std::make_unique<HarmonicInputs>(m, w0);
  for (const auto& o : r.orders) h->addOrder(o);
  for (const auto& [name, tau] : r.loads) {
    const int k = m.rotorIndex(name);
    const int s = m.description.sprocketIndex(name);
    if (k < 0 || s < 0 || !m.description.sprockets[s].loaded)
      throw std::invalid_argument("--load: '" + name + "' is not a loaded sprocket of the drive; its loaded sprockets: " +
                                  loadedSprockets(m.description));
    h->setLoad(k, tau);
  }
  return h;
}

// The start: the saved state of --initial-state, else the preloaded start state at t = 0 (the
// start time is returned); then, unless --quiet, the drive and how the start was found.
double startRun(Simulation& sim, const Model& m, const RunArguments& r) {
  const double cpu0 = cpuSeconds();
  double t0 = 0.0;
  if (!r.initialState.empty()) {
    const StateSnapshot snap = readStateFile(r.initialState, m, static_cast<int>(sim.state().size()), sim.fidelity());
    t0 = snap.time;
    sim.startFrom(t0, snap.y);
  } else {
    sim.start(0.0);
  }
  const double cpuPreload = cpuSeconds() - cpu0;
  if (!r.quiet) {
    std::printf("drive: %s (%d links, %zu rotors, %s fidelity, %zu states)\n", m.name.c_str(), m.chain.links,
                m.rotors.size(), choiceName(sim.fidelity()), sim.state().size());
    if (sim.integratorFixedStep() > 0.0) std::printf("%s\n", r.stepReason.c_str());
    if (const span::SpanModel* sm = sim.spanModel())
      for (const std::string& note : sm->notes) std::printf("  %s\n", note.c_str());
    if (r.initialState.empty())
      std::printf("start: %s, %.3f s CPU\n", sim.preloadReport().message.c_str(), cpuPreload);
    else
      std::printf("start: state of %s at t = %.6f s\n", r.initialState.c_str(), t0);
  }
  return t0;
}

// ---- writing results ----

// The outputs as CSV (--out): a header, then one row per output time; nothing without --out.
class CsvOutput {
 public:
  CsvOutput(const std::string& path, const Model& m) : m_(m) {
    if (path.empty()) return;
    csv_.open(path);
    if (!csv_) throw std::runtime_error("cannot write " + path);
    csv_ << "time";
    for (const auto& r : m.rotors) csv_ << "," << r.name << ".phi," << r.name << ".w";
    csv_ << "," << (m.drivenRotor >= 0 ? m.rotors[m.drivenRotor].name : std::string("crankshaft")) << ".tau";
    csv_ << ",tensioner.F,tensioner.s,chain.Ftight,chain.Fslack,link.F,link.Fn,link.FnSprocket,link.FnGuide,link.x,link.y"
            ",energy.kinetic,energy.elastic,energy.gravity,energy.dissipated,energy.input,contacts\n";
    csv_.precision(10);
  }

  void write(const Outputs& o) {
    if (!csv_.is_open()) return;
    csv_ << o.time;
    for (std::size_t r = 0; r < m_.rotors.size(); ++r) csv_ << "," << o.rotorAngle[r] << "," << o.rotorRate[r];
    csv_ << "," << o.crankTorque << "," << o.tensionerForce << "," << o.tensionerStroke << "," << o.tightSpanForce << ","
         << o.slackSpanForce << "," << o.linkTension << "," << o.linkNormalForce << "," << o.linkSprocketForce << ","
         << o.linkGuideForce << "," << o.linkPosition.x << "," << o.linkPosition.y << "," << o.energy.kinetic << ","
         << o.energy.elastic << "," << o.energy.gravity << "," << o.energy.dissipated << "," << o.energy.inputWork << ","
         << o.contacts << "\n";
  }

 private:
  const Model& m_;
  std::ofstream csv_;
};

// How far a run got, at what cost, and why it stopped early if it did.
struct RunResult {
  int status = 0;               // the exit code: 0, or 3 when the integration failed
  double tReached = 0.0;        // simulated time from the start [s]
  double cpu = 0.0;             // CPU time of the integration [s], every thread's
  double wall = 0.0;            // its wall-clock time [s]
  double outputInterval = 0.0;  // [s] whole grid steps
  std::string failure, failureKind;
  double failureTime = 0.0;
};

// Outputs every `stride` points of the run's time grid (whole fixed steps, or whole quanta
// of the adaptive methods), so that every output time is a grid point and every step is whole.
RunResult integrate(Simulation& sim, const RunArguments& r, double t0, double tEnd, CsvOutput& csv) {
  // the output times: whole grid steps, none past tEnd
  RunResult res;
  const TimeGrid& grid = sim.grid();
  const long long stride = std::max(1LL, std::llround(r.outputStep / grid.unit));
  res.outputInterval = static_cast<double>(stride) * grid.unit;
  const long nOut = std::max(1L, static_cast<long>(std::floor(tEnd / res.outputInterval + 1e-9)));  // not past tEnd
  if (std::fabs(res.outputInterval - r.outputStep) > 1e-9 * r.outputStep)
    std::fprintf(stderr, "chaindrive-run: note: the output step %g s is not a whole number of grid steps of %g s; "
                 "outputs every %g s\n", r.outputStep, grid.unit, res.outputInterval);
  // the integration, output by output, up to a failure
  const double cpuRun0 = cpuSeconds(), wallRun0 = wallSeconds();
  for (long k = 1; k <= nOut; ++k) {
    try {
      sim.advanceTo(grid.time(k * stride));
    } catch (const IntegrationError& e) {
      res.failure = e.what();
      res.failureKind = e.kind();
      res.failureTime = e.time();
      res.status = 3;
      break;
    }
    res.tReached = sim.time() - t0;
    csv.write(sim.outputs());
  }
  res.cpu = cpuSeconds() - cpuRun0;
  res.wall = wallSeconds() - wallRun0;
  return res;
}

// The method that ran: the integrator for compliant contacts, else the contact method.
std::string methodName(const Simulation& sim, const RunArguments& r) {
  if (sim.contactMethod() == ContactMethod::Compliant) return choiceName(r.opt.integrator.method);
  return choiceName(sim.contactMethod());
}

void printContactStats(const Simulation& sim, const ns::NsStats& cs, double tReached) {
  const double per = tReached > 0 ? 1.0 / tReached : 0.0;
  auto f = [](long long v) { return static_cast<double>(v); };
  std::printf("contact method %s: per simulated second %.0f steps, %.0f events, %.0f impacts, %.0f LCP solves, "
              "mean LCP size %.1f, max %lld, %.0f pivots, %.0f regularized LCPs\n",
              choiceName(sim.contactMethod()), f(cs.steps) * per, f(cs.events) * per, f(cs.impacts) * per,
              f(cs.lcpSolves) * per, cs.lcpSolves ? f(cs.lcpSizeSum) / f(cs.lcpSolves) : 0.0, cs.lcpSizeMax,
              f(cs.pivots) * per, f(cs.regularizedLcps) * per);
}

// The run's figures on stdout: the failure, the cost, the contact method's and the integrator's counters.
void printReport(const Simulation& sim, const RunArguments& r, const RunResult& res, double w0) {
  const IntegratorStats st = sim.integratorStats();
  if (res.status != 0) std::printf("FAILED: %s\n", res.failure.c_str());
  std::printf("integrator %s: simulated %.6f s (%.3f engine cycles at %.0f rpm) in %.3f s CPU -> %.3f CPU s per simulated s\n",
              methodName(sim, r).c_str(), res.tReached, res.tReached * w0 / (4.0 * kPi), r.rpm, res.cpu,
              res.tReached > 0 ? res.cpu / res.tReached : 0.0);
  if (const ns::NsStats* cs = sim.contactStats()) printContactStats(sim, *cs, res.tReached);
  std::printf("steps %lld, rhs evaluations %lld (model count %lld), jacobians %lld, error-test failures %lld, "
              "convergence failures %lld, last step %.3e s\n",
              st.steps, st.rhsEvaluations, sim.rhsEvaluations(), st.jacobianEvaluations, st.errorTestFailures,
              st.convergenceFailures, st.lastStep);
}

// The run's figures as JSON (--summary): CPU time, counters, the failure and its kind.
void writeSummary(const Simulation& sim, const RunArguments& r, const RunResult& res, double t0, double tEnd) {
  // what ran, how far and at what cost
  const IntegratorStats st = sim.integratorStats();
  nlohmann::json j;
  j["status"] = res.status == 0 ? "ok" : "failed";
  j["fidelity"] = choiceName(sim.fidelity());
  j["contactMethod"] = choiceName(sim.contactMethod());
  j["method"] = methodName(sim, r);
  j["rpm"] = r.rpm;
  j["startTime"] = t0;
  j["simulated"] = res.tReached;
  j["requested"] = tEnd;
  j["cpuSeconds"] = res.cpu;
  if (res.tReached > 0) j["cpuPerSimulatedSecond"] = res.cpu / res.tReached;
  j["wallSeconds"] = res.wall;
  if (res.tReached > 0) j["wallPerSimulatedSecond"] = res.wall / res.tReached;
  j["threads"] = r.opt.threads;
  if (st.steps > 0) j["barriersPerStep"] = static_cast<double>(sim.threadBarriers()) / static_cast<double>(st.steps);
  // the integrator's counters
  j["steps"] = st.steps;
  if (sim.integratorFixedStep() > 0.0) {
    j["step"] = sim.integratorFixedStep();
    j["stepReason"] = r.stepReason;
  }
  j["outputStep"] = res.outputInterval;
  j["rhsEvaluations"] = sim.rhsEvaluations();
  j["jacobianEvaluations"] = st.jacobianEvaluations;
  j["errorTestFailures"] = st.errorTestFailures;
  j["convergenceFailures"] = st.convergenceFailures;
  // why it stopped early, the contact method's counters
  if (res.status != 0) {
    j["failure"] = res.failure;
    j["failureKind"] = res.failureKind;
    j["failureTime"] = res.failureTime;
  }
  if (const ns::NsStats* cs = sim.contactStats()) cli::addContactStats(*cs, j);
  std::ofstream sj(r.summaryPath);
  if (!sj) throw std::runtime_error("cannot write " + r.summaryPath);
  sj << j.dump(1) << "\n";
}

// The whole run; returns the exit code (0, or 3 when the integration failed).
int run(RunArguments r) {
  // the drive, its inputs and the time to simulate
  const DriveDescription desc = cli::loadDrive(r.drive);
  auto model = std::make_shared<const Model>(assemble(desc));
  const Model& m = *model;
  applyDriveDefaults(r, m);
  const double w0 = r.rpm * 2.0 * kPi / 60.0;
  const double tEnd = r.duration > 0.0 ? r.duration : r.cycles * 2.0 * 2.0 * kPi / w0;
  Simulation sim(model, r.opt, makeInputs(m, r, w0));
  // the start, the integration with its outputs, the figures
  const double t0 = startRun(sim, m, r);
  CsvOutput csv(r.outPath, m);
  csv.write(sim.outputs());
  const RunResult res = integrate(sim, r, t0, tEnd, csv);
  printReport(sim, r, res, w0);
  if (!r.summaryPath.empty()) writeSummary(sim, r, res, t0, tEnd);
  // a run that reached its end: the state to continue from, the final forces
  if (res.status == 0 && !r.saveState.empty())
    writeStateFile(r.saveState, m, StateSnapshot{sim.time(), sim.state()}, sim.fidelity());
  if (res.status == 0 && !r.quiet) {
    const Outputs& o = sim.outputs();
    std::printf("final: tensioner %.2f N, tight span %.2f N, slack span %.2f N, crank torque %.3f N m, contacts %d\n",
                o.tensionerForce, o.tightSpanForce, o.slackSpanForce, o.crankTorque, o.contacts);
  }
  return res.status;
}

}  // namespace

int main(int argc, char** argv) {
  return cli::runTool(kTool, argc, argv, usage, parseArguments, run);
}
