// chaindrive-run: the solver alone (no FMU). Runs a drive at a mean engine speed for a number of
// engine cycles with constant or tabulated inputs, writes the outputs as CSV and prints CPU time
// and the real-time factor (CPU seconds per simulated second).
#include <time.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "description/drive_description.h"
#include "run/inputs.h"
#include "assembly/model.h"
#include "run/simulation.h"
#include "run/state_file.h"

using namespace chaindrive;

namespace {

double cpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

void usage() {
  std::string names;
  for (const auto& n : integratorNames()) names += (names.empty() ? "" : ", ") + n;
  std::printf(
      "usage: chaindrive-run [options]\n"
      "  --drive FILE            drive description (default: the embedded default drive)\n"
      "  --rpm N                 mean crankshaft speed [rpm] (default 3000)\n"
      "  --cycles N              engine cycles to simulate, 720 deg crank each (default 2)\n"
      "  --duration S            simulated time [s] instead of --cycles\n"
      "  --integrator NAME       %s (default arkode-erk)\n"
      "  --contact-method M      compliant, event-driven or time-stepping (default: the drive's)\n"
      "  --joint-model J         journal-bearing or ideal (default: the drive's)\n"
      "  --rtol X                relative tolerance of adaptive integrators and of the event-driven\n"
      "                          method (default 1e-5)\n"
      "  --step S                step of fixed-step integrators and of time stepping [s] (default 2e-6);\n"
      "                          they step on the grid t0 + k S\n"
      "  --max-step S            largest step of adaptive integrators [s] (default unlimited)\n"
      "  --min-step S            adaptive integrators: a smaller step is a step-size collapse [s] (1e-10)\n"
      "  --output-step S         output interval [s] (default 1e-4), rounded to whole grid steps (the\n"
      "                          fixed step, or 1 us for adaptive methods)\n"
      "  --load NAME=TORQUE      constant load torque [N m] on a free sprocket (+ opposes rotation)\n"
      "  --crank-vibration K:A   rotational vibration of engine order K (per crank rev) with angle\n"
      "                          amplitude A [deg]; repeatable\n"
      "  --inputs FILE.csv       time series instead: time,<crank>.w,<sprocket>.tau,... (SI)\n"
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
      "  --quiet                 print the summary only\n",
      names.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  std::string drive, inputsCsv, outPath, initialState, saveState, summaryPath;
  double rpm = 3000.0, cycles = 2.0, duration = -1.0, outputStep = 1e-4;
  SimulationOptions opt;
  std::vector<std::pair<std::string, double>> loads;
  std::vector<HarmonicInputs::Order> orders;
  bool quiet = false;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto next = [&]() -> std::string {
        if (i + 1 >= argc) throw std::invalid_argument("option " + a + " needs a value");
        return argv[++i];
      };
      auto num = [&](const std::string& s) {
        size_t pos = 0;
        const double v = std::stod(s, &pos);
        if (pos != s.size() || !std::isfinite(v)) throw std::invalid_argument("option " + a + ": '" + s + "' is not a number");
        return v;
      };
      if (a == "--drive") drive = next();
      else if (a == "--rpm") rpm = num(next());
      else if (a == "--cycles") cycles = num(next());
      else if (a == "--duration") duration = num(next());
      else if (a == "--integrator") opt.integrator.method = next();
      else if (a == "--contact-method") opt.contactMethod = next();
      else if (a == "--joint-model") opt.jointModel = next();
      else if (a == "--rebound-threshold") opt.integrator.reboundThreshold = num(next());
      else if (a == "--gap-tolerance") opt.integrator.gapTolerance = num(next());
      else if (a == "--record-lcps") {
        const std::string spec = next();  // DIR:COUNT
        const auto c = spec.rfind(':');
        if (c == std::string::npos) throw std::invalid_argument("--record-lcps expects DIRECTORY:COUNT");
        opt.integrator.recordLcpDirectory = spec.substr(0, c);
        opt.integrator.recordLcpCount = static_cast<int>(num(spec.substr(c + 1)));
      }
      else if (a == "--max-event-rate") opt.integrator.maxEventsPerSecond = num(next());
      else if (a == "--rtol") opt.integrator.rtol = num(next());
      else if (a == "--step") opt.integrator.fixedStep = num(next());
      else if (a == "--max-step") opt.integrator.maxStep = num(next());
      else if (a == "--min-step") opt.integrator.minStep = num(next());
      else if (a == "--output-step") outputStep = num(next());
      else if (a == "--inputs") inputsCsv = next();
      else if (a == "--out") outPath = next();
      else if (a == "--initial-state") initialState = next();
      else if (a == "--save-state") saveState = next();
      else if (a == "--summary") summaryPath = next();
      else if (a == "--link") opt.monitoredLink = static_cast<int>(num(next()));
      else if (a == "--no-preload") opt.preload.enabled = false;
      else if (a == "--quiet") quiet = true;
      else if (a == "--load") {
        const std::string s = next();
        const auto eq = s.find('=');
        if (eq == std::string::npos) throw std::invalid_argument("--load expects NAME=TORQUE, got '" + s + "'");
        loads.emplace_back(s.substr(0, eq), num(s.substr(eq + 1)));
      } else if (a == "--crank-vibration") {
        const std::string s = next();
        const auto c = s.find(':');
        if (c == std::string::npos) throw std::invalid_argument("--crank-vibration expects ORDER:AMPLITUDE_DEG");
        HarmonicInputs::Order o;
        o.order = num(s.substr(0, c));
        o.amplitude = num(s.substr(c + 1)) * kPi / 180.0;
        orders.push_back(o);
      } else if (a == "-h" || a == "--help") {
        usage();
        return 0;
      } else {
        throw std::invalid_argument("unknown argument '" + a + "'");
      }
    }
    if (!(rpm > 0.0 && rpm <= 20000.0)) throw std::invalid_argument("--rpm must be in (0, 20000]");
    if (!(outputStep > 0.0)) throw std::invalid_argument("--output-step must be positive");
    if (!(opt.integrator.rtol > 0.0 && opt.integrator.rtol < 1.0)) throw std::invalid_argument("--rtol must be in (0, 1)");
    if (!(opt.integrator.fixedStep > 0.0)) throw std::invalid_argument("--step must be positive");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "chaindrive-run: %s\n", e.what());
    usage();
    return 2;
  }

  try {
    const DriveDescription d = drive.empty() ? defaultDriveDescription() : loadDriveDescription(drive);
    auto model = std::make_shared<const Model>(assemble(d));
    const Model& m = *model;
    const double w0 = rpm * 2.0 * kPi / 60.0;
    const double tEnd = duration > 0.0 ? duration : cycles * 2.0 * 2.0 * kPi / w0;
    std::unique_ptr<InputSignal> in;
    if (!inputsCsv.empty()) {
      in = std::make_unique<TableInputs>(m, inputsCsv);
    } else {
      auto h = std::make_unique<HarmonicInputs>(m, w0);
      for (const auto& o : orders) h->addOrder(o);
      for (const auto& [name, tau] : loads) {
        const int r = m.rotorIndex(name);
        if (r < 0 || !m.rotors[r].isSprocket || m.rotors[r].prescribed)
          throw std::invalid_argument("--load: '" + name + "' is not a free sprocket of the drive");
        h->setLoad(r, tau);
      }
      in = std::move(h);
    }
    Simulation sim(model, opt, std::move(in));
    const double cpu0 = cpuSeconds();
    double t0 = 0.0;
    if (!initialState.empty()) {
      const StateSnapshot snap = readStateFile(initialState, m);
      t0 = snap.time;
      sim.startFrom(t0, snap.y);
    } else {
      sim.start(0.0);
    }
    const double cpuPreload = cpuSeconds() - cpu0;
    if (!quiet) {
      std::printf("drive: %s (%d links, %zu rotors, %d states)\n", m.name.c_str(), m.chain.links, m.rotors.size(), m.nStates);
      if (initialState.empty())
        std::printf("start: %s, %.3f s CPU\n", sim.preloadReport().message.c_str(), cpuPreload);
      else
        std::printf("start: state of %s at t = %.6f s\n", initialState.c_str(), t0);
    }
    std::ofstream csv;
    if (!outPath.empty()) {
      csv.open(outPath);
      if (!csv) throw std::runtime_error("cannot write " + outPath);
      csv << "time";
      for (const auto& r : m.rotors) csv << "," << r.name << ".phi," << r.name << ".w";
      csv << "," << (m.drivenRotor >= 0 ? m.rotors[m.drivenRotor].name : std::string("crankshaft")) << ".tau";
      csv << ",tensioner.F,tensioner.s,chain.Ftight,chain.Fslack,link.F,link.Fn,link.FnSprocket,link.FnGuide,link.x,link.y"
             ",energy.kinetic,energy.elastic,energy.gravity,energy.dissipated,energy.input,contacts\n";
      csv.precision(10);
    }
    auto write = [&](const Outputs& o) {
      if (!csv.is_open()) return;
      csv << o.time;
      for (std::size_t r = 0; r < m.rotors.size(); ++r) csv << "," << o.rotorAngle[r] << "," << o.rotorRate[r];
      csv << "," << o.crankTorque << "," << o.tensionerForce << "," << o.tensionerStroke << "," << o.tightSpanForce << ","
          << o.slackSpanForce << "," << o.linkTension << "," << o.linkNormalForce << "," << o.linkSprocketForce << ","
          << o.linkGuideForce << "," << o.linkPosition.x << "," << o.linkPosition.y << "," << o.energy.kinetic << ","
          << o.energy.elastic << "," << o.energy.gravity << "," << o.energy.dissipated << "," << o.energy.inputWork << ","
          << o.contacts << "\n";
    };
    write(sim.outputs());
    // Outputs every `stride` points of the run's time grid (whole fixed steps, or whole quanta
    // of the adaptive methods), so that every output time is a grid point and every step is whole.
    const TimeGrid& grid = sim.grid();
    const long long stride = std::max(1LL, std::llround(outputStep / grid.unit));
    const double outputInterval = static_cast<double>(stride) * grid.unit;
    const long nOut = std::max(1L, static_cast<long>(std::floor(tEnd / outputInterval + 1e-9)));  // not past tEnd
    if (std::fabs(outputInterval - outputStep) > 1e-9 * outputStep)
      std::fprintf(stderr, "chaindrive-run: note: the output step %g s is not a whole number of grid steps of %g s; "
                   "outputs every %g s\n", outputStep, grid.unit, outputInterval);
    const double cpuRun0 = cpuSeconds();
    int status = 0;
    std::string failure;
    double tReached = 0.0;
    std::string failureKindName;
    double failureTime = 0.0;
    for (long k = 1; k <= nOut; ++k) {
      try {
        sim.advanceTo(grid.time(k * stride));
      } catch (const IntegrationError& e) {
        failure = e.what();
        failureKindName = e.kind();
        failureTime = e.time();
        status = 3;
        break;
      }
      tReached = sim.time() - t0;
      write(sim.outputs());
    }
    const double cpu = cpuSeconds() - cpuRun0;
    const IntegratorStats st = sim.integratorStats();
    if (status != 0) std::printf("FAILED: %s\n", failure.c_str());
    const std::string method = sim.contactMethod() == "compliant" ? opt.integrator.method : sim.contactMethod();
    std::printf("integrator %s: simulated %.6f s (%.3f engine cycles at %.0f rpm) in %.3f s CPU -> %.3f CPU s per simulated s\n",
                method.c_str(), tReached, tReached * w0 / (4.0 * kPi), rpm, cpu, tReached > 0 ? cpu / tReached : 0.0);
    if (const ns::NsStats* cs = sim.contactStats()) {
      const double per = tReached > 0 ? 1.0 / tReached : 0.0;
      auto f = [](long long v) { return static_cast<double>(v); };
      std::printf("contact method %s: per simulated second %.0f steps, %.0f events, %.0f impacts, %.0f LCP solves, "
                  "mean LCP size %.1f, max %lld, %.0f pivots, %.0f regularized LCPs\n",
                  sim.contactMethod().c_str(), f(cs->steps) * per, f(cs->events) * per, f(cs->impacts) * per,
                  f(cs->lcpSolves) * per, cs->lcpSolves ? f(cs->lcpSizeSum) / f(cs->lcpSolves) : 0.0, cs->lcpSizeMax,
                  f(cs->pivots) * per, f(cs->regularizedLcps) * per);
    }
    std::printf("steps %lld, rhs evaluations %lld (model count %lld), jacobians %lld, error-test failures %lld, "
                "convergence failures %lld, last step %.3e s\n",
                st.steps, st.rhsEvaluations, sim.rhsEvaluations(), st.jacobianEvaluations, st.errorTestFailures,
                st.convergenceFailures, st.lastStep);
    if (!summaryPath.empty()) {
      nlohmann::json j;
      j["status"] = status == 0 ? "ok" : "failed";
      j["contactMethod"] = sim.contactMethod();
      j["method"] = method;
      j["rpm"] = rpm;
      j["startTime"] = t0;
      j["simulated"] = tReached;
      j["requested"] = tEnd;
      j["cpuSeconds"] = cpu;
      if (tReached > 0) j["cpuPerSimulatedSecond"] = cpu / tReached;
      j["steps"] = st.steps;
      if (sim.integratorFixedStep() > 0.0) j["step"] = sim.integratorFixedStep();
      j["outputStep"] = outputInterval;
      j["rhsEvaluations"] = sim.rhsEvaluations();
      j["jacobianEvaluations"] = st.jacobianEvaluations;
      j["errorTestFailures"] = st.errorTestFailures;
      j["convergenceFailures"] = st.convergenceFailures;
      if (status != 0) {
        j["failure"] = failure;
        j["failureKind"] = failureKindName;
        j["failureTime"] = failureTime;
      }
      if (const ns::NsStats* cs = sim.contactStats()) {
        j["events"] = cs->events;
        j["impacts"] = cs->impacts;
        j["lcpSolves"] = cs->lcpSolves;
        j["lcpSizeMean"] = cs->lcpSolves ? static_cast<double>(cs->lcpSizeSum) / static_cast<double>(cs->lcpSolves) : 0.0;
        j["lcpSizeMax"] = cs->lcpSizeMax;
        j["pivots"] = cs->pivots;
        j["regularizedLcps"] = cs->regularizedLcps;
        j["contactSteps"] = cs->steps;
      }
      std::ofstream sj(summaryPath);
      if (!sj) throw std::runtime_error("cannot write " + summaryPath);
      sj << j.dump(1) << "\n";
    }
    if (status == 0 && !saveState.empty()) writeStateFile(saveState, m, StateSnapshot{sim.time(), sim.state()});
    if (status == 0 && !quiet) {
      const Outputs& o = sim.outputs();
      std::printf("final: tensioner %.2f N, tight span %.2f N, slack span %.2f N, crank torque %.3f N m, contacts %d\n",
                  o.tensionerForce, o.tightSpanForce, o.slackSpanForce, o.crankTorque, o.contacts);
    }
    return status;
  } catch (const DescriptionError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "chaindrive-run: %s\n", e.what());
    return 1;
  }
}
