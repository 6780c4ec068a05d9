#include "chaindrive_model.h"

#include <cmath>
#include <fstream>

#include "description/drive_description.h"

namespace chaindrive::fmu {

namespace {

bool fileExists(const std::string& p) {
  std::ifstream f(p);
  return f.good();
}

// What a Real output is read from: the solver outputs at the current state, the rotors' roles
// and the solver time.
struct OutputView {
  const Outputs& out;
  const RotorRoles& roles;
  double solverTime;
};

// A rotor's quantity; 0 when the drive has no rotor of that role.
double rotor(int r, const std::vector<double>& a) { return r >= 0 ? a[r] : 0.0; }

struct RealOutput {
  unsigned vr;
  double (*read)(const OutputView& s);
};

// clang-format off
constexpr RealOutput kRealOutputs[] = {
  {kCrankshaftPhi,            [](const OutputView& s) { return rotor(s.roles.crank, s.out.rotorAngle); }},
  {kCrankshaftTau,            [](const OutputView& s) { return s.out.crankTorque; }},
  {kCamshaftIntakePhi,        [](const OutputView& s) { return rotor(s.roles.intake, s.out.rotorAngle); }},
  {kCamshaftIntakeW,          [](const OutputView& s) { return rotor(s.roles.intake, s.out.rotorRate); }},
  {kCamshaftExhaustPhi,       [](const OutputView& s) { return rotor(s.roles.exhaust, s.out.rotorAngle); }},
  {kCamshaftExhaustW,         [](const OutputView& s) { return rotor(s.roles.exhaust, s.out.rotorRate); }},
  {kTensionGuidePhi,          [](const OutputView& s) { return rotor(s.roles.tensionGuide, s.out.rotorAngle); }},
  {kTensionGuideW,            [](const OutputView& s) { return rotor(s.roles.tensionGuide, s.out.rotorRate); }},
  {kTensionerF,               [](const OutputView& s) { return s.out.tensionerForce; }},
  {kTensionerS,               [](const OutputView& s) { return s.out.tensionerStroke; }},
  {kTensionerV,               [](const OutputView& s) { return s.out.tensionerRate; }},
  {kChainFtight,              [](const OutputView& s) { return s.out.tightSpanForce; }},
  {kChainFslack,              [](const OutputView& s) { return s.out.slackSpanForce; }},
  {kLinkF,                    [](const OutputView& s) { return s.out.linkTension; }},
  {kLinkFn,                   [](const OutputView& s) { return s.out.linkNormalForce; }},
  {kLinkFnSprocket,           [](const OutputView& s) { return s.out.linkSprocketForce; }},
  {kLinkFnGuide,              [](const OutputView& s) { return s.out.linkGuideForce; }},
  {kLinkX,                    [](const OutputView& s) { return s.out.linkPosition.x; }},
  {kLinkY,                    [](const OutputView& s) { return s.out.linkPosition.y; }},
  {kEnergyKinetic,            [](const OutputView& s) { return s.out.energy.kinetic; }},
  {kEnergyElastic,            [](const OutputView& s) { return s.out.energy.elastic; }},
  {kEnergyDissipated,         [](const OutputView& s) { return s.out.energy.dissipated; }},
  {kEnergyInput,              [](const OutputView& s) { return s.out.energy.inputWork; }},
  {kChainMaxJointDeformation, [](const OutputView& s) { return s.out.maxJointDeformation; }},
  {kSolverTime,               [](const OutputView& s) { return s.solverTime; }},
};
// clang-format on

const RealOutput* findRealOutput(unsigned vr) {
  for (const RealOutput& o : kRealOutputs)
    if (o.vr == vr) return &o;
  return nullptr;
}

}  // namespace

// ---- preparation ----

// The model, the roles of its rotors and the start state, from the parameters: a table of
// contents of the steps below. Any failure is logged and leaves the instance unprepared.
fmi2Status ChainDriveModel::prepare() {
  dropSimulation();
  if (!parametersValid()) return fmi2Error;
  try {
    DriveDescription desc = driveDescription();
    if (!applyTensionerOverrides(desc)) return fmi2Error;
    model_ = std::make_shared<const Model>(assemble(desc));
    if (!assignRoles(*model_)) {
      dropSimulation();
      return fmi2Error;
    }
    startSimulation();
    prepared_ = true;
    return fmi2OK;
  } catch (const DescriptionError& e) {
    for (const auto& p : e.problems()) host_.log(fmi2Error, "logStatusError", "drive description: %s", p.c_str());
  } catch (const std::exception& e) {
    host_.log(fmi2Error, "logStatusError", "initialization failed: %s", e.what());
  }
  dropSimulation();
  return fmi2Error;
}

void ChainDriveModel::dropSimulation() {
  sim_.reset();
  held_ = nullptr;
  model_.reset();
  prepared_ = false;
  outputsValid_ = false;
}

void ChainDriveModel::reset() {
  dropSimulation();
  params_ = Parameters{};
  in_ = Inputs{};
  steps_ = 0;
  stepHint_ = 0.0;
}

// Every parameter problem is logged (all of them at once); false if there was one.
bool ChainDriveModel::parametersValid() {
  std::vector<std::string> problems;
  checkChoices(problems);
  checkRanges(problems);
  for (const auto& p : problems) host_.log(fmi2Error, "logStatusError", "%s", p.c_str());
  return problems.empty();
}

// The named choices: fidelity, integrator, contact method, joint model.
void ChainDriveModel::checkChoices(std::vector<std::string>& problems) const {
  const bool span = params_.fidelity == "span";
  if (!span && params_.fidelity != "link")
    problems.push_back("fidelity: '" + params_.fidelity + "' is unknown; allowed: link, span");
  bool knownMethod = false;
  std::string methods;
  for (const auto& n : integratorNames()) {
    knownMethod = knownMethod || n == params_.method;
    methods += (methods.empty() ? "" : ", ") + n;
  }
  if (!knownMethod) problems.push_back("solver.method: '" + params_.method + "' is unknown; allowed: " + methods);
  if (!params_.contactMethod.empty() && params_.contactMethod != "compliant" && params_.contactMethod != "event-driven" &&
      params_.contactMethod != "time-stepping")
    problems.push_back("contact.method: '" + params_.contactMethod +
                       "' is unknown; allowed: compliant, event-driven, time-stepping (or empty: the drive's)");
  if (!params_.jointModel.empty() && params_.jointModel != "journal-bearing" && params_.jointModel != "ideal")
    problems.push_back("chain.jointModel: '" + params_.jointModel +
                       "' is unknown; allowed: journal-bearing, ideal (or empty: the drive's)");
  // the span fidelity has spans, no contacts, and takes its span stiffness from journal bearings
  // (a drive description that asks for other ones is refused when the simulation is built)
  if (span && (params_.contactMethod == "event-driven" || params_.contactMethod == "time-stepping"))
    problems.push_back("contact.method: '" + params_.contactMethod +
                       "' does not apply to fidelity 'span'; allowed with it: compliant (or empty: the drive's)");
  const bool linkOnly = params_.method == "fixed-newmark" || params_.method.rfind("fixed-verlet-implicit", 0) == 0;
  if (span && linkOnly)
    problems.push_back("solver.method: '" + params_.method + "' does not apply to fidelity 'span' (its implicit part "
                       "is the links' joints and contacts); allowed with it: the other methods");
  if (span && params_.jointModel == "ideal")
    problems.push_back("chain.jointModel: 'ideal' does not apply to fidelity 'span'; allowed with it: journal-bearing "
                       "(or empty: the drive's)");
}

// The numbers: solver tolerance and step, the tensioner overrides (negative: as in the drive).
void ChainDriveModel::checkRanges(std::vector<std::string>& problems) const {
  if (!(params_.tolerance >= 1e-12 && params_.tolerance <= 0.1))
    problems.push_back("solver.tolerance: " + std::to_string(params_.tolerance) + " is out of range; allowed [1e-12, 0.1]");
  if (!(params_.step >= 1e-9 && params_.step <= 1e-3))
    problems.push_back("solver.step: " + std::to_string(params_.step) + " s is out of range; allowed [1e-9, 1e-3] s");
  if (!(params_.newmarkGamma >= 0.5 && params_.newmarkGamma <= 1.0))
    problems.push_back("solver.newmarkGamma: " + std::to_string(params_.newmarkGamma) + " is out of range; allowed [0.5, 1]");
  auto checkOverride = [&](double v, const char* name, double hi) {
    if (!std::isfinite(v) || v > hi)
      problems.push_back(std::string(name) + ": " + std::to_string(v) + " is out of range; allowed a negative value (as in "
                         "the drive description) or [0, " + std::to_string(hi) + "]");
  };
  checkOverride(params_.tensionerPreload, "tensioner.preload", 1e5);
  checkOverride(params_.tensionerStiffness, "tensioner.stiffness", 1e9);
  checkOverride(params_.tensionerDamping, "tensioner.damping", 1e7);
  checkOverride(params_.tensionerDampingExtension, "tensioner.dampingExtension", 1e7);
}

// The drive file of the parameter driveFile; empty: the resources' default drive, or the one
// built into the binary when the importer gave no resources folder.
DriveDescription ChainDriveModel::driveDescription() {
  if (!params_.driveFile.empty()) {
    DriveDescription desc = loadDriveDescription(params_.driveFile);
    host_.log(fmi2OK, "logEvents", "drive: %s", params_.driveFile.c_str());
    return desc;
  }
  const std::string& resourceDir = host_.resourceDir();
  const std::string res = resourceDir.empty() ? "" : resourceDir + "/default_drive.json";
  if (!res.empty() && fileExists(res)) {
    DriveDescription desc = loadDriveDescription(res);
    host_.log(fmi2OK, "logEvents", "drive: %s", res.c_str());
    return desc;
  }
  host_.log(fmi2Warning, "logStatusWarning",
            "no resources folder with default_drive.json (fmuResourceLocation '%s'); using the default drive built "
            "into the binary",
            resourceDir.c_str());
  return defaultDriveDescription();
}

// The tensioner parameters (negative: as in the drive); false if the drive has no tensioner.
bool ChainDriveModel::applyTensionerOverrides(DriveDescription& desc) {
  const bool overrides = params_.tensionerPreload >= 0 || params_.tensionerStiffness >= 0 ||
                         params_.tensionerDamping >= 0 || params_.tensionerDampingExtension >= 0;
  if (overrides && !desc.tensioner.present) {
    host_.log(fmi2Error, "logStatusError", "tensioner.*: the drive has no tensioner to apply the parameters to");
    return false;
  }
  if (params_.tensionerPreload >= 0) desc.tensioner.preload = params_.tensionerPreload;
  if (params_.tensionerStiffness >= 0) desc.tensioner.stiffness = params_.tensionerStiffness;
  if (params_.tensionerDamping >= 0) desc.tensioner.damping = params_.tensionerDamping;
  if (params_.tensionerDampingExtension >= 0) desc.tensioner.dampingExtension = params_.tensionerDampingExtension;
  return true;
}

// The rotors the FMU's inputs and outputs refer to, and the monitored link's range.
bool ChainDriveModel::assignRoles(const Model& m) {
  if (params_.linkIndex < -1 || params_.linkIndex >= m.chain.links) {
    host_.log(fmi2Error, "logStatusError", "link.index: %d is out of range; allowed -1 (as in the drive) or 0..%d",
              params_.linkIndex, m.chain.links - 1);
    return false;
  }
  roles_ = RotorRoles{};
  roles_.crank = m.drivenRotor;
  if (roles_.crank < 0) {
    host_.log(fmi2Error, "logStatusError", "the drive has no sprocket with motion 'prescribed' to follow crankshaft.w");
    return false;
  }
  roles_.intake = m.rotorIndex("camshaftIntake");
  roles_.exhaust = m.rotorIndex("camshaftExhaust");
  roles_.tensionGuide = m.tensioner.present ? m.tensioner.rotor : -1;
  if (roles_.intake < 0 || roles_.exhaust < 0)
    host_.log(fmi2Warning, "logStatusWarning",
              "the drive has no sprocket named camshaftIntake and/or camshaftExhaust: their inputs have no effect and "
              "their outputs are zero");
  return true;
}

// The simulation of model_ with the solver parameters, at its start state on the time grid.
void ChainDriveModel::startSimulation() {
  // the solver options from the parameters
  SimulationOptions opt;
  opt.fidelity = params_.fidelity;
  opt.integrator.method = params_.method;
  opt.integrator.adaptive.rtol = params_.tolerance;
  opt.integrator.fixed.step = params_.step;
  opt.integrator.newmark.gamma = params_.newmarkGamma;
  opt.integrator.adaptive.stopAtOutputs = true;
  opt.contactMethod = params_.contactMethod;
  opt.jointModel = params_.jointModel;
  opt.preload.enabled = params_.preload;
  opt.monitoredLink = params_.linkIndex;
  // the simulation, its inputs held at the values set through the FMI, from its start state
  auto held = std::make_unique<HeldInputs>(*model_);
  held_ = held.get();
  sim_ = std::make_unique<Simulation>(model_, opt, std::move(held));
  applyInputs();
  sim_->start(host_.time());
  // what the start state solve found, and the time grid the steps snap to
  const PreloadReport& rep = sim_->preloadReport();
  host_.log(rep.converged ? fmi2OK : fmi2Warning, rep.converged ? "logEvents" : "logStatusWarning",
            "start state: %s (%.3f s CPU)", rep.message.c_str(), rep.cpuSeconds);
  host_.log(fmi2OK, "logEvents", "fidelity: %s (%zu states)", sim_->fidelity().c_str(), sim_->state().size());
  const TimeGrid& grid = sim_->grid();
  host_.log(fmi2OK, "logEvents",
            "time grid: t_k = %.17g s + k %.17g s; a communication point within %.3g s of a grid point is that point, "
            "one farther off is integrated to the grid point before it (output solver.time)",
            grid.start, grid.unit, kSnapFraction * grid.unit);
  // the run's counters start over
  steps_ = 0;
  stepHint_ = 0.0;
  host_.runStarted();
}

void ChainDriveModel::applyInputs() {
  if (!held_) return;
  InputValues& v = held_->values;
  v.crankSpeed = in_.crankSpeed;
  if (roles_.intake >= 0) v.loadTorque[roles_.intake] = in_.tauIntake;
  if (roles_.exhaust >= 0) v.loadTorque[roles_.exhaust] = in_.tauExhaust;
}

// ---- values by value reference ----

double* ChainDriveModel::realSetting(unsigned vr) {
  switch (vr) {
    case kCrankshaftW: return &in_.crankSpeed;
    case kCamshaftIntakeTau: return &in_.tauIntake;
    case kCamshaftExhaustTau: return &in_.tauExhaust;
    case kSolverTolerance: return &params_.tolerance;
    case kSolverStep: return &params_.step;
    case kSolverNewmarkGamma: return &params_.newmarkGamma;
    case kTensionerPreload: return &params_.tensionerPreload;
    case kTensionerStiffness: return &params_.tensionerStiffness;
    case kTensionerDamping: return &params_.tensionerDamping;
    case kTensionerDampingExtension: return &params_.tensionerDampingExtension;
    default: return nullptr;
  }
}

std::string* ChainDriveModel::stringParameter(unsigned vr) {
  switch (vr) {
    case kDriveFile: return &params_.driveFile;
    case kSolverMethod: return &params_.method;
    case kContactMethod: return &params_.contactMethod;
    case kChainJointModel: return &params_.jointModel;
    case kFidelity: return &params_.fidelity;
    default: return nullptr;
  }
}

bool ChainDriveModel::outputsReady() {
  if (!prepared_) {
    if (host_.state() != kInitializationMode) return false;
    if (prepare() > fmi2Warning) return false;
  }
  if (!outputsValid_) {
    applyInputs();
    out_ = sim_->outputs();
    outputsValid_ = true;
  }
  return true;
}

fmi2Status ChainDriveModel::badVr(const char* function, fmi2ValueReference vr, const char* what) {
  host_.log(fmi2Error, "logStatusError", "%s: value reference %u %s", function, vr, what);
  return fmi2Error;
}

fmi2Status ChainDriveModel::notAvailable(const char* function, const Variable& v) {
  host_.log(fmi2Error, "logStatusError", "%s: '%s' is not available before the initialization succeeded", function,
            v.name);
  return fmi2Error;
}

fmi2Status ChainDriveModel::getReal(const fmi2ValueReference vr[], std::size_t n, fmi2Real v[]) {
  for (std::size_t i = 0; i < n; ++i) {
    const Variable* var = findVariable(vr[i]);
    if (!var || var->type != Type::Real) return badVr("fmi2GetReal", vr[i], "is not a Real variable");
    // parameters and inputs: their values at any time
    if (const double* setting = realSetting(vr[i])) {
      v[i] = *setting;
      continue;
    }
    // outputs: of the current state, prepared on demand in initialization mode
    if (!outputsReady()) return notAvailable("fmi2GetReal", *var);
    const RealOutput* output = findRealOutput(vr[i]);
    if (!output) return badVr("fmi2GetReal", vr[i], "is not readable");
    v[i] = output->read(OutputView{out_, roles_, sim_->time()});
  }
  return fmi2OK;
}

fmi2Status ChainDriveModel::getInteger(const fmi2ValueReference vr[], std::size_t n, fmi2Integer v[]) {
  for (std::size_t i = 0; i < n; ++i) {
    const Variable* var = findVariable(vr[i]);
    if (!var || var->type != Type::Integer) return badVr("fmi2GetInteger", vr[i], "is not an Integer variable");
    if (vr[i] == kLinkIndex) {
      v[i] = params_.linkIndex;
      continue;
    }
    if (!outputsReady()) return notAvailable("fmi2GetInteger", *var);
    v[i] = vr[i] == kContacts ? out_.contacts : static_cast<fmi2Integer>(steps_);
  }
  return fmi2OK;
}

fmi2Status ChainDriveModel::getBoolean(const fmi2ValueReference vr[], std::size_t n, fmi2Boolean v[]) {
  for (std::size_t i = 0; i < n; ++i) {
    if (vr[i] != kSolverPreload) return badVr("fmi2GetBoolean", vr[i], "is not a Boolean variable");
    v[i] = params_.preload ? fmi2True : fmi2False;
  }
  return fmi2OK;
}

fmi2Status ChainDriveModel::getString(const fmi2ValueReference vr[], std::size_t n, fmi2String v[]) {
  // the returned pointers stay valid until the next call that changes the strings
  for (std::size_t i = 0; i < n; ++i) {
    const std::string* value = stringParameter(vr[i]);
    if (!value) return badVr("fmi2GetString", vr[i], "is not a String variable");
    v[i] = value->c_str();
  }
  return fmi2OK;
}

fmi2Status ChainDriveModel::parameterChange(const Variable& v) {
  if (host_.initializing()) {
    prepared_ = false;
    return fmi2OK;
  }
  host_.log(fmi2Error, "logStatusError", "parameter '%s' is fixed: it can only be set before the initialization ends",
            v.name);
  return fmi2Error;
}

void ChainDriveModel::inputChange() {
  // the start state depends on the inputs at the start time
  if (host_.initializing()) prepared_ = false;
  outputsValid_ = false;  // crankshaft.tau and link.Fn depend directly on crankshaft.w
}

fmi2Status ChainDriveModel::setReal(const fmi2ValueReference vr[], std::size_t n, const fmi2Real v[]) {
  for (std::size_t i = 0; i < n; ++i) {
    const Variable* var = findVariable(vr[i]);
    if (!var || var->type != Type::Real || var->causality == Causality::Output)
      return badVr("fmi2SetReal", vr[i], "is not a settable Real variable");
    if (!std::isfinite(v[i])) {
      host_.log(fmi2Error, "logStatusError", "fmi2SetReal: %s = %g is not a finite value", var->name, v[i]);
      return fmi2Error;
    }
    if (var->causality == Causality::Input) {
      *realSetting(vr[i]) = v[i];
      inputChange();
      continue;
    }
    if (parameterChange(*var) != fmi2OK) return fmi2Error;
    double* parameter = realSetting(vr[i]);
    if (!parameter) return badVr("fmi2SetReal", vr[i], "is not settable");
    *parameter = v[i];
  }
  return fmi2OK;
}

fmi2Status ChainDriveModel::setInteger(const fmi2ValueReference vr[], std::size_t n, const fmi2Integer v[]) {
  for (std::size_t i = 0; i < n; ++i) {
    if (vr[i] != kLinkIndex) return badVr("fmi2SetInteger", vr[i], "is not a settable Integer variable");
    if (parameterChange(*findVariable(vr[i])) != fmi2OK) return fmi2Error;
    params_.linkIndex = v[i];
  }
  return fmi2OK;
}

fmi2Status ChainDriveModel::setBoolean(const fmi2ValueReference vr[], std::size_t n, const fmi2Boolean v[]) {
  for (std::size_t i = 0; i < n; ++i) {
    if (vr[i] != kSolverPreload) return badVr("fmi2SetBoolean", vr[i], "is not a settable Boolean variable");
    if (parameterChange(*findVariable(vr[i])) != fmi2OK) return fmi2Error;
    params_.preload = v[i] != fmi2False;
  }
  return fmi2OK;
}

fmi2Status ChainDriveModel::setString(const fmi2ValueReference vr[], std::size_t n, const fmi2String v[]) {
  for (std::size_t i = 0; i < n; ++i) {
    std::string* target = stringParameter(vr[i]);
    if (!target) return badVr("fmi2SetString", vr[i], "is not a settable String variable");
    if (!v[i]) {
      host_.log(fmi2Error, "logStatusError", "fmi2SetString: NULL string for value reference %u", vr[i]);
      return fmi2Error;
    }
    if (parameterChange(*findVariable(vr[i])) != fmi2OK) return fmi2Error;
    *target = v[i];
  }
  return fmi2OK;
}

// ---- the communication step ----

fmi2Status ChainDriveModel::doStep(double cp, double tEnd) {
  if (!sim_) {
    host_.log(fmi2Error, "logStatusError", "fmi2DoStep: the FMU is not initialized");
    return fmi2Error;
  }
  if (!sim_->grid().reaches(tEnd)) {
    host_.log(fmi2Error, "logStatusError", "fmi2DoStep: the step ends at %.17g s, beyond the range of the time grid",
              tEnd);
    return fmi2Error;
  }
  applyInputs();
  try {
    // Every communication step integrates from the current grid point to the grid point of
    // tEnd (src/run/time_grid.h: tEnd itself when it lies on the grid, else the point before it),
    // restarting the integrator there: a step depends on (state, inputs, grid points) only, so
    // a rollback with fmi2SetFMUstate is exact and every master that means the same
    // communication points gets the same bits, however it rounds them.
    sim_->restart(stepHint_);
    const long long base = sim_->integratorStats().steps;
    sim_->advanceTo(tEnd);
    const IntegratorStats st = sim_->integratorStats();
    steps_ += st.steps - base;
    if (st.lastStep > 0.0) stepHint_ = st.lastStep;
  } catch (const IntegrationError& e) {
    host_.log(fmi2Discard, "logStatusDiscard",
              "fmi2DoStep from t = %.9g s to %.9g s could not be completed: %s; the state is kept at t = %.9g s "
              "(fmi2SetFMUstate can restore an earlier one)",
              cp, tEnd, e.what(), sim_->time());
    return fmi2Discard;
  }
  outputsValid_ = false;
  return fmi2OK;
}

// ---- the model's part of an FMU state ----

ChainDriveModel::Snapshot ChainDriveModel::snapshot() const {
  Snapshot s;
  s.stepHint = stepHint_;
  s.steps = steps_;
  s.crankSpeed = in_.crankSpeed;
  s.tauIntake = in_.tauIntake;
  s.tauExhaust = in_.tauExhaust;
  if (sim_ && prepared_) {  // (parameters changed after the preparation: it runs again)
    s.y = sim_->state();
    s.gridStart = sim_->grid().start;
    s.gridUnit = sim_->grid().unit;
    s.gridIndex = sim_->gridIndex();
  }
  return s;
}

fmi2Status ChainDriveModel::restore(const Snapshot& s) {
  if (!s.y.empty()) {
    // the solver state must be one of this drive and fidelity (their state sizes differ), on
    // this instance's time grid
    const std::size_t size = sim_ ? sim_->state().size() : 0;
    if (s.y.size() != size) {
      host_.log(fmi2Error, "logStatusError", "fmi2SetFMUstate: the state has %zu components, this instance %zu "
                "(initialize the instance with the same drive and fidelity first)", s.y.size(), size);
      return fmi2Error;
    }
    const TimeGrid& grid = sim_->grid();
    if (s.gridStart != grid.start || s.gridUnit != grid.unit) {
      host_.log(fmi2Error, "logStatusError", "fmi2SetFMUstate: the state was taken on the time grid %.17g s + k %.17g "
                "s, this instance runs on %.17g s + k %.17g s (same start time and solver.step needed)", s.gridStart,
                s.gridUnit, grid.start, grid.unit);
      return fmi2Error;
    }
    sim_->restoreAt(s.gridIndex, s.y);
  } else {
    // A state taken before the model was prepared (instantiated, or initialization mode before
    // any output was asked for) holds no solver state: the solver state reached since is
    // dropped, and fmi2ExitInitializationMode prepares the start state again.
    dropSimulation();
  }
  stepHint_ = s.stepHint;
  steps_ = s.steps;
  in_.crankSpeed = s.crankSpeed;
  in_.tauIntake = s.tauIntake;
  in_.tauExhaust = s.tauExhaust;
  outputsValid_ = false;
  return fmi2OK;
}

void ChainDriveModel::writeFields(const Snapshot& s, std::vector<char>& out) {
  for (double v : {s.stepHint, s.crankSpeed, s.tauIntake, s.tauExhaust, s.gridStart, s.gridUnit}) putField(out, v);
  putField(out, s.steps);
  putField(out, s.gridIndex);
}

void ChainDriveModel::readFields(ByteReader& in, Snapshot& s) {
  for (double* v : {&s.stepHint, &s.crankSpeed, &s.tauIntake, &s.tauExhaust, &s.gridStart, &s.gridUnit}) in.field(*v);
  in.field(s.steps);
  in.field(s.gridIndex);
}

const char* ChainDriveModel::invalidField(const Snapshot& s, std::uint64_t components) {
  if (!std::isfinite(s.stepHint) || s.stepHint < 0.0) return "stepHint";
  if (s.steps < 0) return "steps";
  if (components == 0) return nullptr;
  if (!std::isfinite(s.gridStart) || !std::isfinite(s.gridUnit) || s.gridUnit <= 0.0) return "grid";
  return s.gridIndex < 0 ? "gridIndex" : nullptr;
}

}  // namespace chaindrive::fmu
