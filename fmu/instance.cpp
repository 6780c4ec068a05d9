#include "instance.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "description/drive_description.h"

namespace chaindrive::fmu {

namespace {

const char* stateName(unsigned s) {
  switch (s) {
    case kInstantiated: return "instantiated";
    case kInitializationMode: return "initialization mode";
    case kStepComplete: return "step complete";
    case kStepFailed: return "step failed";
    case kTerminated: return "terminated";
    case kError: return "error";
    default: return "unknown";
  }
}

constexpr const char* kKnownCategories[] = {"logEvents", "logStatusWarning", "logStatusDiscard",
                                            "logStatusError", "logStatusFatal", "logAll"};

bool fileExists(const std::string& p) {
  std::ifstream f(p);
  return f.good();
}

int hexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

std::string resourceDirectory(const char* location) {
  if (!location || !*location) return "";
  std::string s(location);
  const std::string scheme = "file:";
  if (s.compare(0, scheme.size(), scheme) != 0) return "";
  s = s.substr(scheme.size());
  // file:///dir, file:////dir, file://localhost/dir, file:/dir
  if (s.compare(0, 11, "//localhost") == 0) s = s.substr(11);
  while (s.size() > 1 && s[0] == '/' && s[1] == '/') s = s.substr(1);
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size() && hexValue(s[i + 1]) >= 0 && hexValue(s[i + 2]) >= 0) {
      out.push_back(static_cast<char>(16 * hexValue(s[i + 1]) + hexValue(s[i + 2])));
      i += 2;
    } else {
      out.push_back(s[i]);
    }
  }
  while (out.size() > 1 && out.back() == '/') out.pop_back();
  return out;
}

Instance::Instance(const char* instanceName, const fmi2CallbackFunctions* callbacks, const char* resourceLocation,
                   bool loggingOn)
    : name_(instanceName ? instanceName : ""), callbacks_(*callbacks), resourceDir_(resourceDirectory(resourceLocation)),
      loggingOn_(loggingOn) {}

void Instance::log(fmi2Status status, const char* category, const char* fmt, ...) {
  if (!callbacks_.logger) return;
  const bool always = status >= fmi2Warning;
  if (!always) {
    if (!loggingOn_) return;
    if (!categories_.empty()) {
      bool on = false;
      for (const auto& c : categories_) on = on || c == category || c == "logAll";
      if (!on) return;
    }
  }
  char buf[2048];
  va_list ap;
  va_start(ap, fmt);
  std::vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  // the message is passed as the format string with '%' doubled, so that importers that print it
  // without formatting show it as well as those that format it
  char escaped[4096];
  std::size_t k = 0;
  for (const char* p = buf; *p && k + 2 < sizeof escaped; ++p) {
    if (*p == '%') escaped[k++] = '%';
    escaped[k++] = *p;
  }
  escaped[k] = '\0';
  callbacks_.logger(callbacks_.componentEnvironment, name_.c_str(), status, category, escaped);
}

fmi2Status Instance::setDebugLogging(bool on, size_t n, const fmi2String categories[]) {
  loggingOn_ = on;
  categories_.clear();
  fmi2Status st = fmi2OK;
  for (size_t i = 0; i < n; ++i) {
    if (!categories || !categories[i]) continue;
    bool known = false;
    for (const char* k : kKnownCategories) known = known || std::strcmp(k, categories[i]) == 0;
    if (!known) {
      log(fmi2Warning, "logStatusWarning", "fmi2SetDebugLogging: unknown log category '%s'", categories[i]);
      st = fmi2Warning;
      continue;
    }
    categories_.emplace_back(categories[i]);
  }
  return st;
}

bool Instance::allowed(const char* function, unsigned allowedStates) {
  if (state_ & allowedStates) return true;
  log(fmi2Error, "logStatusError", "%s: not allowed in state '%s'", function, stateName(state_));
  return false;
}

fmi2Status Instance::setupExperiment(bool /*toleranceDefined*/, double /*tolerance*/, double startTime,
                                     bool stopTimeDefined, double stopTime) {
  if (!std::isfinite(startTime)) {
    log(fmi2Error, "logStatusError", "fmi2SetupExperiment: startTime %g is not finite", startTime);
    return fmi2Error;
  }
  if (stopTimeDefined && !(stopTime >= startTime)) {
    log(fmi2Error, "logStatusError", "fmi2SetupExperiment: stopTime %g is before startTime %g", stopTime, startTime);
    return fmi2Error;
  }
  // the tolerance argument is not used: the integrator's tolerance is the parameter solver.tolerance
  startTime_ = time_ = lastSuccessfulTime_ = startTime;
  stopTimeDefined_ = stopTimeDefined;
  stopTime_ = stopTime;
  prepared_ = false;
  return fmi2OK;
}

fmi2Status Instance::enterInitializationMode() {
  state_ = kInitializationMode;
  return fmi2OK;
}

fmi2Status Instance::exitInitializationMode() {
  if (!prepared_) {
    const fmi2Status s = prepare();
    if (s > fmi2Warning) {
      state_ = kError;
      return s;
    }
  }
  state_ = kStepComplete;
  return fmi2OK;
}

// The model, the roles of its rotors and the start state, from the parameters: a table of
// contents of the steps below. Any failure is logged and leaves the instance unprepared.
fmi2Status Instance::prepare() {
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
    for (const auto& p : e.problems()) log(fmi2Error, "logStatusError", "drive description: %s", p.c_str());
  } catch (const std::exception& e) {
    log(fmi2Error, "logStatusError", "initialization failed: %s", e.what());
  }
  dropSimulation();
  return fmi2Error;
}

void Instance::dropSimulation() {
  sim_.reset();
  inputs_ = nullptr;
  model_.reset();
  prepared_ = false;
  outputsValid_ = false;
}

// Every parameter problem is logged (all of them at once); false if there was one.
bool Instance::parametersValid() {
  std::vector<std::string> problems;
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
  if (!(params_.tolerance >= 1e-12 && params_.tolerance <= 0.1))
    problems.push_back("solver.tolerance: " + std::to_string(params_.tolerance) + " is out of range; allowed [1e-12, 0.1]");
  if (!(params_.step >= 1e-9 && params_.step <= 1e-3))
    problems.push_back("solver.step: " + std::to_string(params_.step) + " s is out of range; allowed [1e-9, 1e-3] s");
  auto checkOverride = [&](double v, const char* name, double hi) {
    if (!std::isfinite(v) || v > hi)
      problems.push_back(std::string(name) + ": " + std::to_string(v) + " is out of range; allowed a negative value (as in "
                         "the drive description) or [0, " + std::to_string(hi) + "]");
  };
  checkOverride(params_.tensionerPreload, "tensioner.preload", 1e5);
  checkOverride(params_.tensionerStiffness, "tensioner.stiffness", 1e9);
  checkOverride(params_.tensionerDamping, "tensioner.damping", 1e7);
  checkOverride(params_.tensionerDampingExtension, "tensioner.dampingExtension", 1e7);
  for (const auto& p : problems) log(fmi2Error, "logStatusError", "%s", p.c_str());
  return problems.empty();
}

// The drive file of the parameter driveFile; empty: the resources' default drive, or the one
// built into the binary when the importer gave no resources folder.
DriveDescription Instance::driveDescription() {
  if (!params_.driveFile.empty()) {
    DriveDescription desc = loadDriveDescription(params_.driveFile);
    log(fmi2OK, "logEvents", "drive: %s", params_.driveFile.c_str());
    return desc;
  }
  const std::string res = resourceDir_.empty() ? "" : resourceDir_ + "/default_drive.json";
  if (!res.empty() && fileExists(res)) {
    DriveDescription desc = loadDriveDescription(res);
    log(fmi2OK, "logEvents", "drive: %s", res.c_str());
    return desc;
  }
  log(fmi2Warning, "logStatusWarning",
      "no resources folder with default_drive.json (fmuResourceLocation '%s'); using the default drive built "
      "into the binary",
      resourceDir_.c_str());
  return defaultDriveDescription();
}

// The tensioner parameters (negative: as in the drive); false if the drive has no tensioner.
bool Instance::applyTensionerOverrides(DriveDescription& desc) {
  const bool overrides = params_.tensionerPreload >= 0 || params_.tensionerStiffness >= 0 ||
                         params_.tensionerDamping >= 0 || params_.tensionerDampingExtension >= 0;
  if (overrides && !desc.tensioner.present) {
    log(fmi2Error, "logStatusError", "tensioner.*: the drive has no tensioner to apply the parameters to");
    return false;
  }
  if (params_.tensionerPreload >= 0) desc.tensioner.preload = params_.tensionerPreload;
  if (params_.tensionerStiffness >= 0) desc.tensioner.stiffness = params_.tensionerStiffness;
  if (params_.tensionerDamping >= 0) desc.tensioner.damping = params_.tensionerDamping;
  if (params_.tensionerDampingExtension >= 0) desc.tensioner.dampingExtension = params_.tensionerDampingExtension;
  return true;
}

// The rotors the FMU's inputs and outputs refer to, and the monitored link's range.
bool Instance::assignRoles(const Model& m) {
  if (params_.linkIndex < -1 || params_.linkIndex >= m.chain.links) {
    log(fmi2Error, "logStatusError", "link.index: %d is out of range; allowed -1 (as in the drive) or 0..%d",
        params_.linkIndex, m.chain.links - 1);
    return false;
  }
  roles_ = Roles{};
  roles_.crank = m.drivenRotor;
  if (roles_.crank < 0) {
    log(fmi2Error, "logStatusError", "the drive has no sprocket with motion 'prescribed' to follow crankshaft.w");
    return false;
  }
  roles_.intake = m.rotorIndex("camshaftIntake");
  roles_.exhaust = m.rotorIndex("camshaftExhaust");
  roles_.tensionGuide = m.tensioner.present ? m.tensioner.rotor : -1;
  if (roles_.intake < 0 || roles_.exhaust < 0)
    log(fmi2Warning, "logStatusWarning",
        "the drive has no sprocket named camshaftIntake and/or camshaftExhaust: their inputs have no effect and their "
        "outputs are zero");
  return true;
}

// The simulation of model_ with the solver parameters, at its start state on the time grid.
void Instance::startSimulation() {
  SimulationOptions opt;
  opt.integrator.method = params_.method;
  opt.integrator.rtol = params_.tolerance;
  opt.integrator.fixedStep = params_.step;
  opt.integrator.stopAtOutputs = true;
  opt.contactMethod = params_.contactMethod;
  opt.jointModel = params_.jointModel;
  opt.preload.enabled = params_.preload;
  opt.monitoredLink = params_.linkIndex;
  auto held = std::make_unique<HeldInputs>(*model_);
  inputs_ = held.get();
  sim_ = std::make_unique<Simulation>(model_, opt, std::move(held));
  applyInputs();
  sim_->start(time_);
  const PreloadReport& rep = sim_->preloadReport();
  log(rep.converged ? fmi2OK : fmi2Warning, rep.converged ? "logEvents" : "logStatusWarning",
      "start state: %s (%.3f s CPU)", rep.message.c_str(), rep.cpuSeconds);
  const TimeGrid& grid = sim_->grid();
  log(fmi2OK, "logEvents",
      "time grid: t_k = %.17g s + k %.17g s; a communication point within %.3g s of a grid point is that point, "
      "one farther off is integrated to the grid point before it (output solver.time)",
      grid.start, grid.unit, kSnapFraction * grid.unit);
  steps_ = 0;
  stepHint_ = 0.0;
  lastSuccessfulTime_ = time_;
}

void Instance::applyInputs() {
  if (!inputs_) return;
  InputValues& v = inputs_->values;
  v.crankSpeed = inCrankSpeed_;
  if (roles_.intake >= 0) v.loadTorque[roles_.intake] = inTauIntake_;
  if (roles_.exhaust >= 0) v.loadTorque[roles_.exhaust] = inTauExhaust_;
}

fmi2Status Instance::doStep(double cp, double h) {
  if (!std::isfinite(h) || h <= 0.0) {
    log(fmi2Error, "logStatusError", "fmi2DoStep: communicationStepSize %g must be positive and finite", h);
    return fmi2Error;
  }
  const double tol = 1e-9 * std::max(1.0, std::fabs(time_));
  if (!std::isfinite(cp) || std::fabs(cp - time_) > tol) {
    log(fmi2Error, "logStatusError", "fmi2DoStep: currentCommunicationPoint %.17g does not match the FMU time %.17g", cp,
        time_);
    return fmi2Error;
  }
  const double tEnd = cp + h;
  if (stopTimeDefined_ && tEnd > stopTime_ * (1.0 + 1e-12) + 1e-12) {
    log(fmi2Error, "logStatusError", "fmi2DoStep: the step ends at %.17g, after the stop time %.17g", tEnd, stopTime_);
    return fmi2Error;
  }
  if (!sim_) {
    log(fmi2Error, "logStatusError", "fmi2DoStep: the FMU is not initialized");
    return fmi2Error;
  }
  if (!sim_->grid().reaches(tEnd)) {
    log(fmi2Error, "logStatusError", "fmi2DoStep: the step ends at %.17g s, beyond the range of the time grid", tEnd);
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
    lastSuccessfulTime_ = time_;
    state_ = kStepFailed;
    log(fmi2Discard, "logStatusDiscard",
        "fmi2DoStep from t = %.9g s to %.9g s could not be completed: %s; the state is kept at t = %.9g s "
        "(fmi2SetFMUstate can restore an earlier one)",
        cp, tEnd, e.what(), sim_->time());
    return fmi2Discard;
  }
  time_ = tEnd;
  lastSuccessfulTime_ = tEnd;
  outputsValid_ = false;
  return fmi2OK;
}

fmi2Status Instance::terminate() {
  state_ = kTerminated;
  return fmi2OK;
}

fmi2Status Instance::reset() {
  dropSimulation();
  params_ = Parameters{};
  inCrankSpeed_ = 314.1592653589793;
  inTauIntake_ = inTauExhaust_ = 0.0;
  time_ = startTime_ = stopTime_ = lastSuccessfulTime_ = stepHint_ = 0.0;
  stopTimeDefined_ = false;
  steps_ = 0;
  state_ = kInstantiated;
  return fmi2OK;
}

bool Instance::outputsReady() {
  if (!prepared_) {
    if (state_ != kInitializationMode) return false;
    if (prepare() > fmi2Warning) return false;
  }
  if (!outputsValid_) {
    applyInputs();
    out_ = sim_->outputs();
    outputsValid_ = true;
  }
  return true;
}

fmi2Status Instance::badVr(const char* function, fmi2ValueReference vr, const char* what) {
  log(fmi2Error, "logStatusError", "%s: value reference %u %s", function, vr, what);
  return fmi2Error;
}

fmi2Status Instance::getReal(const fmi2ValueReference vr[], size_t n, fmi2Real v[]) {
  for (size_t i = 0; i < n; ++i) {
    const Variable* var = findVariable(vr[i]);
    if (!var || var->type != Type::Real) return badVr("fmi2GetReal", vr[i], "is not a Real variable");
    switch (vr[i]) {
      case kCrankshaftW: v[i] = inCrankSpeed_; continue;
      case kCamshaftIntakeTau: v[i] = inTauIntake_; continue;
      case kCamshaftExhaustTau: v[i] = inTauExhaust_; continue;
      case kSolverTolerance: v[i] = params_.tolerance; continue;
      case kSolverStep: v[i] = params_.step; continue;
      case kTensionerPreload: v[i] = params_.tensionerPreload; continue;
      case kTensionerStiffness: v[i] = params_.tensionerStiffness; continue;
      case kTensionerDamping: v[i] = params_.tensionerDamping; continue;
      case kTensionerDampingExtension: v[i] = params_.tensionerDampingExtension; continue;
      default: break;
    }
    if (!outputsReady()) {
      log(fmi2Error, "logStatusError", "fmi2GetReal: '%s' is not available before the initialization succeeded",
          var->name);
      return fmi2Error;
    }
    const Outputs& o = out_;
    auto rotor = [&](int r, const std::vector<double>& a) { return r >= 0 ? a[r] : 0.0; };
    switch (vr[i]) {
      case kCrankshaftPhi: v[i] = rotor(roles_.crank, o.rotorAngle); break;
      case kCrankshaftTau: v[i] = o.crankTorque; break;
      case kCamshaftIntakePhi: v[i] = rotor(roles_.intake, o.rotorAngle); break;
      case kCamshaftIntakeW: v[i] = rotor(roles_.intake, o.rotorRate); break;
      case kCamshaftExhaustPhi: v[i] = rotor(roles_.exhaust, o.rotorAngle); break;
      case kCamshaftExhaustW: v[i] = rotor(roles_.exhaust, o.rotorRate); break;
      case kTensionGuidePhi: v[i] = rotor(roles_.tensionGuide, o.rotorAngle); break;
      case kTensionGuideW: v[i] = rotor(roles_.tensionGuide, o.rotorRate); break;
      case kTensionerF: v[i] = o.tensionerForce; break;
      case kTensionerS: v[i] = o.tensionerStroke; break;
      case kTensionerV: v[i] = o.tensionerRate; break;
      case kChainFtight: v[i] = o.tightSpanForce; break;
      case kChainFslack: v[i] = o.slackSpanForce; break;
      case kLinkF: v[i] = o.linkTension; break;
      case kLinkFn: v[i] = o.linkNormalForce; break;
      case kLinkFnSprocket: v[i] = o.linkSprocketForce; break;
      case kLinkFnGuide: v[i] = o.linkGuideForce; break;
      case kLinkX: v[i] = o.linkPosition.x; break;
      case kLinkY: v[i] = o.linkPosition.y; break;
      case kEnergyKinetic: v[i] = o.energy.kinetic; break;
      case kEnergyElastic: v[i] = o.energy.elastic; break;
      case kEnergyDissipated: v[i] = o.energy.dissipated; break;
      case kEnergyInput: v[i] = o.energy.inputWork; break;
      case kChainMaxJointDeformation: v[i] = o.maxJointDeformation; break;
      case kSolverTime: v[i] = sim_->time(); break;
      default: return badVr("fmi2GetReal", vr[i], "is not readable");
    }
  }
  return fmi2OK;
}

fmi2Status Instance::getInteger(const fmi2ValueReference vr[], size_t n, fmi2Integer v[]) {
  for (size_t i = 0; i < n; ++i) {
    const Variable* var = findVariable(vr[i]);
    if (!var || var->type != Type::Integer) return badVr("fmi2GetInteger", vr[i], "is not an Integer variable");
    if (vr[i] == kLinkIndex) {
      v[i] = params_.linkIndex;
      continue;
    }
    if (!outputsReady()) {
      log(fmi2Error, "logStatusError", "fmi2GetInteger: '%s' is not available before the initialization succeeded",
          var->name);
      return fmi2Error;
    }
    v[i] = vr[i] == kContacts ? out_.contacts : static_cast<fmi2Integer>(steps_);
  }
  return fmi2OK;
}

fmi2Status Instance::getBoolean(const fmi2ValueReference vr[], size_t n, fmi2Boolean v[]) {
  for (size_t i = 0; i < n; ++i) {
    if (vr[i] != kSolverPreload) return badVr("fmi2GetBoolean", vr[i], "is not a Boolean variable");
    v[i] = params_.preload ? fmi2True : fmi2False;
  }
  return fmi2OK;
}

fmi2Status Instance::getString(const fmi2ValueReference vr[], size_t n, fmi2String v[]) {
  // the returned pointers stay valid until the next call that changes the strings
  for (size_t i = 0; i < n; ++i) {
    if (vr[i] == kDriveFile) v[i] = params_.driveFile.c_str();
    else if (vr[i] == kSolverMethod) v[i] = params_.method.c_str();
    else if (vr[i] == kContactMethod) v[i] = params_.contactMethod.c_str();
    else if (vr[i] == kChainJointModel) v[i] = params_.jointModel.c_str();
    else return badVr("fmi2GetString", vr[i], "is not a String variable");
  }
  return fmi2OK;
}

fmi2Status Instance::parameterChange(const Variable& v) {
  if (state_ & (kInstantiated | kInitializationMode)) {
    prepared_ = false;
    return fmi2OK;
  }
  log(fmi2Error, "logStatusError", "parameter '%s' is fixed: it can only be set before the initialization ends",
      v.name);
  return fmi2Error;
}

fmi2Status Instance::setReal(const fmi2ValueReference vr[], size_t n, const fmi2Real v[]) {
  for (size_t i = 0; i < n; ++i) {
    const Variable* var = findVariable(vr[i]);
    if (!var || var->type != Type::Real || var->causality == Causality::Output)
      return badVr("fmi2SetReal", vr[i], "is not a settable Real variable");
    if (!std::isfinite(v[i])) {
      log(fmi2Error, "logStatusError", "fmi2SetReal: %s = %g is not a finite value", var->name, v[i]);
      return fmi2Error;
    }
    if (var->causality == Causality::Input) {
      if (vr[i] == kCrankshaftW) inCrankSpeed_ = v[i];
      else if (vr[i] == kCamshaftIntakeTau) inTauIntake_ = v[i];
      else inTauExhaust_ = v[i];
      // the start state depends on the inputs at the start time
      if (state_ & (kInstantiated | kInitializationMode)) prepared_ = false;
      outputsValid_ = false;  // crankshaft.tau and link.Fn depend directly on crankshaft.w
      continue;
    }
    if (parameterChange(*var) != fmi2OK) return fmi2Error;
    switch (vr[i]) {
      case kSolverTolerance: params_.tolerance = v[i]; break;
      case kSolverStep: params_.step = v[i]; break;
      case kTensionerPreload: params_.tensionerPreload = v[i]; break;
      case kTensionerStiffness: params_.tensionerStiffness = v[i]; break;
      case kTensionerDamping: params_.tensionerDamping = v[i]; break;
      case kTensionerDampingExtension: params_.tensionerDampingExtension = v[i]; break;
      default: return badVr("fmi2SetReal", vr[i], "is not settable");
    }
  }
  return fmi2OK;
}

fmi2Status Instance::setInteger(const fmi2ValueReference vr[], size_t n, const fmi2Integer v[]) {
  for (size_t i = 0; i < n; ++i) {
    if (vr[i] != kLinkIndex) return badVr("fmi2SetInteger", vr[i], "is not a settable Integer variable");
    if (parameterChange(*findVariable(vr[i])) != fmi2OK) return fmi2Error;
    params_.linkIndex = v[i];
  }
  return fmi2OK;
}

fmi2Status Instance::setBoolean(const fmi2ValueReference vr[], size_t n, const fmi2Boolean v[]) {
  for (size_t i = 0; i < n; ++i) {
    if (vr[i] != kSolverPreload) return badVr("fmi2SetBoolean", vr[i], "is not a settable Boolean variable");
    if (parameterChange(*findVariable(vr[i])) != fmi2OK) return fmi2Error;
    params_.preload = v[i] != fmi2False;
  }
  return fmi2OK;
}

fmi2Status Instance::setString(const fmi2ValueReference vr[], size_t n, const fmi2String v[]) {
  for (size_t i = 0; i < n; ++i) {
    std::string* target = vr[i] == kDriveFile        ? &params_.driveFile
                          : vr[i] == kSolverMethod    ? &params_.method
                          : vr[i] == kContactMethod   ? &params_.contactMethod
                          : vr[i] == kChainJointModel ? &params_.jointModel
                                                      : nullptr;
    if (!target) return badVr("fmi2SetString", vr[i], "is not a settable String variable");
    if (!v[i]) {
      log(fmi2Error, "logStatusError", "fmi2SetString: NULL string for value reference %u", vr[i]);
      return fmi2Error;
    }
    if (parameterChange(*findVariable(vr[i])) != fmi2OK) return fmi2Error;
    *target = v[i];
  }
  return fmi2OK;
}

fmi2Status Instance::getRealStatus(fmi2StatusKind kind, fmi2Real* value) {
  if (kind == fmi2LastSuccessfulTime) {
    *value = lastSuccessfulTime_;
    return fmi2OK;
  }
  log(fmi2Error, "logStatusError", "fmi2GetRealStatus: status kind %d is not provided", static_cast<int>(kind));
  return fmi2Discard;
}

fmi2Status Instance::getStatus(fmi2StatusKind kind, fmi2Status* value) {
  if (kind == fmi2DoStepStatus) {
    *value = state_ == kStepFailed ? fmi2Discard : fmi2OK;
    return fmi2OK;
  }
  log(fmi2Error, "logStatusError", "fmi2GetStatus: status kind %d is not provided", static_cast<int>(kind));
  return fmi2Discard;
}

Snapshot Instance::snapshot() const {
  Snapshot s;
  s.state = state_;
  s.time = time_;
  s.lastSuccessfulTime = lastSuccessfulTime_;
  s.stepHint = stepHint_;
  s.steps = steps_;
  s.crankSpeed = inCrankSpeed_;
  s.tauIntake = inTauIntake_;
  s.tauExhaust = inTauExhaust_;
  if (sim_ && prepared_) {  // (parameters changed after the preparation: it runs again)
    s.y = sim_->state();
    s.gridStart = sim_->grid().start;
    s.gridUnit = sim_->grid().unit;
    s.gridIndex = sim_->gridIndex();
  }
  return s;
}

fmi2Status Instance::restore(const Snapshot& s) {
  if (!s.y.empty()) {
    if (!sim_ || static_cast<int>(s.y.size()) != model_->nStates) {
      log(fmi2Error, "logStatusError", "fmi2SetFMUstate: the state has %zu components, this instance %d (initialize "
          "the instance with the same drive first)", s.y.size(), sim_ ? model_->nStates : 0);
      return fmi2Error;
    }
    const TimeGrid& grid = sim_->grid();
    if (s.gridStart != grid.start || s.gridUnit != grid.unit) {
      log(fmi2Error, "logStatusError", "fmi2SetFMUstate: the state was taken on the time grid %.17g s + k %.17g s, this "
          "instance runs on %.17g s + k %.17g s (same start time and solver.step needed)", s.gridStart, s.gridUnit,
          grid.start, grid.unit);
      return fmi2Error;
    }
    sim_->restoreAt(s.gridIndex, s.y);
  } else {
    // A state taken before the model was prepared (instantiated, or initialization mode before
    // any output was asked for) holds no solver state: the solver state reached since is
    // dropped, and fmi2ExitInitializationMode prepares the start state again.
    dropSimulation();
  }
  state_ = s.state == kStepFailed || s.state == kError ? kStepComplete : s.state;
  time_ = s.time;
  lastSuccessfulTime_ = s.lastSuccessfulTime;
  stepHint_ = s.stepHint;
  steps_ = s.steps;
  inCrankSpeed_ = s.crankSpeed;
  inTauIntake_ = s.tauIntake;
  inTauExhaust_ = s.tauExhaust;
  outputsValid_ = false;
  log(fmi2OK, "logEvents", "state restored at t = %.9g s", time_);
  return fmi2OK;
}

namespace {
constexpr char kMagic[8] = {'C', 'H', 'D', 'R', 'V', 'S', 'T', '2'};
}

std::vector<char> Instance::serialize(const Snapshot& s) {
  std::vector<char> out;
  auto put = [&](const void* p, std::size_t n) {
    const char* c = static_cast<const char*>(p);
    out.insert(out.end(), c, c + n);
  };
  put(kMagic, sizeof kMagic);
  const uint64_t n = s.y.size();
  put(&n, sizeof n);
  put(&s.state, sizeof s.state);
  for (double v : {s.time, s.lastSuccessfulTime, s.stepHint, s.crankSpeed, s.tauIntake, s.tauExhaust, s.gridStart,
                   s.gridUnit})
    put(&v, sizeof v);
  put(&s.steps, sizeof s.steps);
  put(&s.gridIndex, sizeof s.gridIndex);
  if (n) put(s.y.data(), n * sizeof(double));
  return out;
}

namespace {

// The first header field of a deserialized state that no instance can have written (nullptr if
// none): bytes changed in storage or transfer must not become an instance state.
const char* invalidHeaderField(const Snapshot& s, std::uint64_t components) {
  const unsigned states = kInstantiated | kInitializationMode | kStepComplete | kStepFailed | kTerminated | kError;
  if (s.state == 0 || (s.state & (s.state - 1)) != 0 || (s.state & ~states) != 0) return "state";
  if (!std::isfinite(s.time) || !std::isfinite(s.lastSuccessfulTime)) return "time";
  if (!std::isfinite(s.stepHint) || s.stepHint < 0.0) return "stepHint";
  if (s.steps < 0) return "steps";
  if (components == 0) return nullptr;
  if (!std::isfinite(s.gridStart) || !std::isfinite(s.gridUnit) || s.gridUnit <= 0.0) return "grid";
  return s.gridIndex < 0 ? "gridIndex" : nullptr;
}

}  // namespace

fmi2Status Instance::deserialize(const char* data, size_t size, Snapshot& s) {
  const std::size_t head = sizeof kMagic + sizeof(uint64_t) + sizeof(unsigned) + 8 * sizeof(double) + 2 * sizeof(long long);
  if (!data || size < head || std::memcmp(data, kMagic, sizeof kMagic) != 0) {
    log(fmi2Error, "logStatusError", "fmi2DeSerializeFMUstate: %zu bytes are not a serialized ChainDrive state", size);
    return fmi2Error;
  }
  std::size_t pos = sizeof kMagic;
  auto get = [&](void* p, std::size_t n) {
    std::memcpy(p, data + pos, n);
    pos += n;
  };
  uint64_t n = 0;
  get(&n, sizeof n);
  if ((size - head) % sizeof(double) != 0 || n != (size - head) / sizeof(double)) {  // no overflow in n * 8
    log(fmi2Error, "logStatusError", "fmi2DeSerializeFMUstate: %zu bytes do not match a state of %llu components", size,
        static_cast<unsigned long long>(n));
    return fmi2Error;
  }
  get(&s.state, sizeof s.state);
  for (double* v : {&s.time, &s.lastSuccessfulTime, &s.stepHint, &s.crankSpeed, &s.tauIntake, &s.tauExhaust,
                    &s.gridStart, &s.gridUnit})
    get(v, sizeof *v);
  get(&s.steps, sizeof s.steps);
  get(&s.gridIndex, sizeof s.gridIndex);
  if (const char* bad = invalidHeaderField(s, n)) {
    log(fmi2Error, "logStatusError", "fmi2DeSerializeFMUstate: the serialized state is corrupt (field %s)", bad);
    return fmi2Error;
  }
  s.y.resize(n);
  if (n) get(s.y.data(), n * sizeof(double));
  return fmi2OK;
}

}  // namespace chaindrive::fmu
