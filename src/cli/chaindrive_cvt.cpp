// chaindrive-cvt: the chain CVT (paper example 4.1) alone, no FMU: a stationary run at a driving
// speed and a load torque, its outputs as CSV (the paper's Figure 9 quantities for one pin among
// them) and a summary with the checks of a stationary state as JSON on stdout.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/arguments.h"
#include "cli/contact_stats.h"
#include "cvt/cvt_assembly.h"
#include "cvt/cvt_run.h"

using namespace chaindrive;

namespace {

constexpr const char* kTool = "chaindrive-cvt";
constexpr double kPi = 3.14159265358979323846;

void usage() {
  const SolverDefaults& defaults = solverDefaults(Scene::Cvt);
  std::fprintf(stderr,
               "usage: chaindrive-cvt [--cvt FILE] [--rpm R] [--load-torque T] [--duration S | --revolutions R]\n"
               "                      [--output-step S] [--method NAME] [--step S] [--rtol R] [--monitored-link K]\n"
               "                      [--friction-facets N] [--state-in FILE] [--state-out FILE] [--csv FILE]\n"
               "                      [--quiet]\n"
               "  --cvt FILE           CVT description (chaindrive.cvt/1); default: the embedded default CVT\n"
               "  --rpm R              driving-pulley speed [rpm] (default 2000)\n"
               "  --load-torque T      load torque on the driven pulley [N m] (default 0)\n"
               "  --duration S         simulated time [s] (default 0.2); the means over its second half\n"
               "  --revolutions R      simulated time in chain revolutions (and an output step more, so that\n"
               "                       the last one ends on the output grid), instead of --duration\n"
               "  --method NAME        fixed-verlet, fixed-verlet-implicit-joint-damping, arkode-erk,\n"
               "                       arkode-erk-fixed (compliant pins: their friction a regularized law), or\n"
               "                       time-stepping (Moreau-Jean: the pins' friction a complementarity problem),\n"
               "                       time-stepping-rigid-pins (the same with the pins axially rigid: unilateral\n"
               "                       contacts with Newton impacts at pulley entry); default %s\n"
               "  --friction-facets N  time-stepping: facets of the polygon that linearizes a pin's friction\n"
               "                       disc (default 8)\n"
               "  --step S             fixed step [s] (default %g); arkode-erk: its largest step\n"
               "  --rtol R             relative tolerance of arkode-erk (default %g)\n"
               "  --state-in FILE      start from this saved state (chaindrive.state/3; default: the nominal\n"
               "                       state at t = 0); the run lasts the duration from its time\n"
               "  --state-out FILE     save the last state (for another method to continue from)\n"
               "  --csv FILE           the outputs at every output step (default step 5e-5 s)\n"
               "Prints the assembly and the summary (means and checks) as JSON. The defaults of method, step\n"
               "and tolerance are CVTChain.fmu's (chaindrive-info --defaults).\n",
               choiceName(cvtMethodOf(CvtRunOptions{})), defaults.step, defaults.tolerance);
}

struct CvtArguments {
  std::string cvt, csv, stateIn, stateOut;
  CvtRunOptions run;
  double revolutions = 0.0;  // > 0: the duration in chain revolutions (and an output step more)
  bool quiet = false;
};

CvtArguments parseArguments(cli::Arguments& args) {
  CvtArguments r;
  while (args.next()) {
    const std::string& a = args.current();
    if (a == "--cvt") r.cvt = args.value();
    else if (a == "--rpm") r.run.drivingSpeed = args.number() * kPi / 30.0;
    else if (a == "--load-torque") r.run.loadTorque = args.number();
    else if (a == "--duration") r.run.duration = args.number();
    else if (a == "--revolutions") r.revolutions = args.number();
    else if (a == "--output-step") r.run.outputStep = args.number();
    else if (a == "--method") setCvtMethod(args.choice<CvtMethod>(), r.run);
    else if (a == "--friction-facets") r.run.integrator.rigid.frictionFacets = static_cast<int>(args.number());
    else if (a == "--step") r.run.integrator.fixed.step = r.run.integrator.adaptive.maxStep = args.number();
    else if (a == "--rtol") r.run.integrator.adaptive.rtol = args.number();
    else if (a == "--monitored-link") r.run.monitoredLink = static_cast<int>(args.number());
    else if (a == "--csv") r.csv = args.value();
    else if (a == "--state-in") r.stateIn = args.value();
    else if (a == "--state-out") r.stateOut = args.value();
    else if (a == "--quiet") r.quiet = true;
    else throw std::invalid_argument("unknown argument '" + a + "'");
  }
  if (!(r.run.duration > 0.0 && r.run.outputStep > 0.0 && r.run.outputStep <= r.run.duration))
    throw std::invalid_argument("--duration and --output-step must be positive, the output step at most the duration");
  return r;
}

void writeCsv(const std::string& path, const CvtRunResult& r) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path);
  f << "time,drivingSpeed,drivenSpeed,slip,tightStrandForce,slackStrandForce,clampingForceDriving,"
       "clampingForceDriven,drivingTorque,drivenTorque,powerLoss,pinPulley,pinNormalForce,pinRadialFriction,"
       "pinCircumferentialFriction,pinAxialForce,linkTension,inputWork,dissipatedEnergy\n";
  char line[640];
  for (const CvtSample& s : r.samples) {
    const CvtOutputs& c = s.cvt;
    std::snprintf(line, sizeof line, "%.9g,%.9g,%.9g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%d,%.6g,%.6g,%.6g,%.6g,%.6g,%.12g,%.12g\n",
                  s.time, c.drivingSpeed, c.drivenSpeed, c.slip, c.tightStrandForce, c.slackStrandForce,
                  c.clampingForce[0], c.clampingForce[1], c.drivingTorque, c.drivenTorque, c.powerLoss, c.pinPulley,
                  c.pinNormalForce, c.pinRadialFriction, c.pinCircumferentialFriction, c.pinAxialForce, c.linkTension,
                  s.energy.inputWork, s.energy.dissipated);
    f << line;
  }
}

// [s] of one chain revolution at the driving speed, without slip
double chainRevolution(const Model& m, const CvtLayout& layout, double drivingSpeed) {
  return m.chain.links * m.chain.pitch / (drivingSpeed * layout.runningRadius[0]);
}

nlohmann::json summaryJson(const Model& m, const CvtLayout& layout, const CvtRunOptions& run, const CvtRunResult& r) {
  const CvtSummary& s = r.summary;
  const double revolution = chainRevolution(m, layout, run.drivingSpeed);
  nlohmann::json j;
  j["cvt"] = m.name;
  j["assembly"] = {{"runningRadius", {layout.runningRadius[0], layout.runningRadius[1]}},
                   {"wrapAngle", {layout.wrapAngle[0], layout.wrapAngle[1]}},
                   {"pretension", layout.pretension},
                   {"clampingForce", {layout.clampingForce[0], layout.clampingForce[1]}},
                   {"closureResidual", m.assembly.closureResidual}};
  j["run"] = {{"method", choiceName(cvtMethodOf(run))}, {"step", run.integrator.fixed.step},
              {"rtol", run.integrator.adaptive.rtol},
              {"drivingSpeed_rpm", run.drivingSpeed * 30.0 / kPi}, {"loadTorque", run.loadTorque},
              {"duration", run.duration}, {"steps", r.steps}, {"cpuSeconds", r.cpuSeconds},
              {"chainRevolution", revolution}, {"cpuPerChainRevolution", r.cpuSeconds * revolution / run.duration}};
  if (r.contactStats) {
    j["run"]["frictionFacets"] = run.integrator.rigid.frictionFacets;
    cli::addContactStats(*r.contactStats, j["run"]);
  }
  j["means"] = {{"from", s.from}, {"to", s.to}, {"drivingSpeed", s.drivingSpeed}, {"drivenSpeed", s.drivenSpeed},
                {"slip", s.slip}, {"speedRatio", s.speedRatio}, {"geometricRatio", s.geometricRatio},
                {"tightStrandForce", s.tightStrandForce}, {"slackStrandForce", s.slackStrandForce},
                {"clampingForce", {s.clampingForce[0], s.clampingForce[1]}}, {"drivingTorque", s.drivingTorque},
                {"drivenTorque", s.drivenTorque}, {"powerLoss", s.powerLoss}, {"netInputPower", s.netInputPower}};
  j["checks"] = {{"speedRatioError", s.speedRatioError}, {"torqueBalanceDriven", s.torqueBalanceDriven},
                 {"torqueBalanceDriving", s.torqueBalanceDriving}, {"energyBalanceError", s.energyBalanceError},
                 {"pinsInContact", {s.pinsInContact[0], s.pinsInContact[1]}}};
  return j;
}

int run(const CvtArguments& a) {
  const CvtDescription desc = a.cvt.empty() ? defaultCvtDescription() : loadCvtDescription(a.cvt);
  CvtLayout layout;
  auto model = std::make_shared<const Model>(assembleCvt(desc, &layout));
  CvtRunOptions run = a.run;
  if (a.revolutions > 0.0) run.duration = a.revolutions * chainRevolution(*model, layout, run.drivingSpeed) + run.outputStep;
  if (!a.stateIn.empty()) run.start = readStateFile(a.stateIn, *model, model->nStates);
  const CvtRunResult r = runCvt(model, run);
  if (!a.stateOut.empty()) writeStateFile(a.stateOut, *model, r.end);
  if (!a.csv.empty()) writeCsv(a.csv, r);
  if (!a.quiet) std::printf("%s\n", summaryJson(*model, layout, run, r).dump(2).c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return cli::runTool(kTool, argc, argv, usage, parseArguments, run); }
