#include "call_sequence.h"

#include <cinttypes>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "call_sequence_internal.h"

namespace chaindrive::fuzz {

const char* planName(std::uint32_t plan) {
  constexpr const char* kNames[kPlanCount] = {"poisoned", "cheap-init", "full-init", "other-method", "span", "drive"};
  return plan < kPlanCount ? kNames[plan] : "unknown";
}

SequenceStats runSequence(std::uint64_t seed, const FuzzPaths& paths, bool trace) {
  detail::CallSequence sequence(seed, paths, trace);
  return sequence.run();
}

namespace detail {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Shares of the plans. Only FullInit pays for the link model's start-state solve; it is the
// dominant cost per sequence under the sanitizers, hence its small share (it is the same code
// every time). Span initializes the span model, which measures its seating slack with the link
// model's start-state solve at rest (seconds under the sanitizers), so it is as rare as FullInit,
// and runs any integrator.
constexpr double kShareFullInit = 0.02;
constexpr double kShareOtherMethod = 0.14;
constexpr double kShareSpan = 0.01;
constexpr double kShareCheapInit = 0.43;
// An importer that follows the standard makes most calls; the rest are random (wrong order,
// wrong arguments).
constexpr double kShareNominalCalls = 0.7;

}  // namespace

void recordLogMessage(fmi2ComponentEnvironment environment, fmi2String instanceName, fmi2Status status,
                      fmi2String category, fmi2String message, ...) {
  LogRecord& log = *static_cast<LogRecord*>(environment);
  if (log.freed) log.problems.emplace_back("the logger was called after fmi2FreeInstance");
  if (!instanceName || !category || !message) {
    log.problems.emplace_back("the logger was called with a NULL string");
    return;
  }
  const int level = static_cast<int>(status);
  if (level < fmi2OK || level > fmi2Error) log.problems.push_back("log message with status " + std::to_string(level));
  if (!log.expectedName.empty() && log.expectedName != instanceName)
    log.problems.push_back(std::string("log message names the instance '") + instanceName + "'");
  // the FMU passes the message as a format string with '%' doubled and no arguments: formatting
  // it as the standard allows must neither read arguments nor change the text
  char text[8192];
  va_list arguments;
  va_start(arguments, message);
  std::vsnprintf(text, sizeof text, message, arguments);
  va_end(arguments);
  if (text[0] == '\0') log.problems.emplace_back("empty log message");
  if (level >= fmi2Discard && text[0] != '\0') ++log.explanations;
  log.lastMessage = text;
}

std::string statusText(fmi2Status s) {
  switch (s) {
    case fmi2OK: return "fmi2OK";
    case fmi2Warning: return "fmi2Warning";
    case fmi2Discard: return "fmi2Discard";
    case fmi2Error: return "fmi2Error";
    case fmi2Fatal: return "fmi2Fatal";
    case fmi2Pending: return "fmi2Pending";
  }
  return "status " + std::to_string(static_cast<int>(s));
}

// ---- the frame of a sequence ----

SequenceStats CallSequence::run() {
  if (paths_.drivePlanOnly) {
    stats_.plan = static_cast<std::uint32_t>(Plan::Drive);
    runDrive();
    return stats_;
  }
  choosePlan();
  checkVersionStrings();
  if (!instantiate()) {
    runWithoutInstance();
    return stats_;
  }
  applyPins();
  const std::size_t calls = 3 + rng_.below(45);
  for (std::size_t i = 0; i < calls; ++i) {
    if (rng_.chance(kShareNominalCalls)) nominalCall();
    else randomCall();
  }
  finish();
  return stats_;
}

void CallSequence::choosePlan() {
  const std::vector<Assignment> defaultMethods = {stringAssignment(fmu::kSolverMethod, "fixed-verlet"),
                                                  stringAssignment(fmu::kContactMethod, ""),
                                                  stringAssignment(fmu::kChainJointModel, ""),
                                                  stringAssignment(fmu::kFidelity, "link")};
  const double r = rng_.unit();
  if (r < kShareFullInit) {
    stats_.plan = static_cast<std::uint32_t>(Plan::FullInit);
    pins_ = defaultMethods;
  } else if (r < kShareFullInit + kShareOtherMethod) {
    stats_.plan = static_cast<std::uint32_t>(Plan::OtherMethod);
    stats_.combination = static_cast<std::uint32_t>(rng_.below(methodCombinationCount()));
    pins_ = methodAssignments(stats_.combination);
    springDamper_ = methodCombinationSpringDamper(stats_.combination);
    stepsLeft_ = methodCombinationSteps(stats_.combination);  // the slower methods: a step or two of 10 us
    shortestStep_ = longestStep_ = 1e-5;
  } else if (r < kShareFullInit + kShareOtherMethod + kShareSpan) {
    stats_.plan = static_cast<std::uint32_t>(Plan::Span);
    pins_ = spanAssignments(rng_);
  } else if (r < kShareFullInit + kShareOtherMethod + kShareSpan + kShareCheapInit) {
    stats_.plan = static_cast<std::uint32_t>(Plan::CheapInit);
    pins_ = defaultMethods;
    pins_.push_back(booleanAssignment(fmu::kSolverPreload, false));
  } else {
    stats_.plan = static_cast<std::uint32_t>(Plan::Poisoned);
    pins_ = poisonAssignments(rng_, paths_);
  }
}

void CallSequence::checkVersionStrings() {
  if (std::strcmp(fmi2GetTypesPlatform(), fmi2TypesPlatform) != 0) violation("fmi2GetTypesPlatform is not \"default\"");
  if (std::strcmp(fmi2GetVersion(), fmi2Version) != 0) violation("fmi2GetVersion is not \"2.0\"");
}

bool CallSequence::instantiate() {
  // 0: valid arguments; otherwise the one argument that is wrong
  enum Flaw : std::size_t { kNone, kWrongGuid, kNullGuid, kModelExchange, kNullCallbacks, kNullLogger, kNullName, kEmptyName };
  const std::size_t flaw = rng_.chance(0.85) ? kNone : 1 + rng_.below(7);
  const std::string name = rng_.chance(0.9) ? "fuzz" : "%s%n instance " + std::string(300, 'i');
  // the FMU of the default drive, or of its spring-damper variant for the methods that need it
  const std::string own = springDamper_ ? paths_.springDamperGuid : std::string(fmu::kGuid);
  const std::string guid = flaw == kWrongGuid ? rng_.pick({std::string("{00000000-0000-0000-0000-000000000000}"),
                                                          own.substr(1), std::string(), own + " "})
                                              : own;
  const ResourceLocation location =
      resourceLocation(rng_, springDamper_ ? paths_.springDamperResourceDir : paths_.resourceDir);
  const fmi2Boolean visible = rng_.chance(0.5) ? fmi2True : fmi2False;
  const fmi2Boolean loggingOn = rng_.chance(0.5) ? fmi2True : fmi2False;
  callbacks_.logger = flaw == kNullLogger ? nullptr : recordLogMessage;
  callbacks_.componentEnvironment = &log_;
  log_.expectedName = flaw == kNullName || flaw == kEmptyName ? "" : name;
  log_.explanations = 0;
  log_.lastMessage.clear();
  instance_ = fmi2Instantiate(flaw == kNullName ? nullptr : flaw == kEmptyName ? "" : name.c_str(),
                              flaw == kModelExchange ? fmi2ModelExchange : fmi2CoSimulation,
                              flaw == kNullGuid ? nullptr : guid.c_str(), location.uri ? location.uri->c_str() : nullptr,
                              flaw == kNullCallbacks ? nullptr : &callbacks_, visible, loggingOn);
  ++stats_.calls;
  const bool valid = flaw == kNone && location.valid;
  if (valid && !instance_) violation("fmi2Instantiate refused valid arguments");
  if (!valid && instance_)
    violation("fmi2Instantiate accepted invalid arguments (flaw " + std::to_string(flaw) + ", resources " +
              location.uri.value_or("NULL") + ")");
  const bool hasLogger = flaw != kNullCallbacks && flaw != kNullLogger;
  if (!instance_ && hasLogger && log_.explanations == 0) violation("fmi2Instantiate refused without an error message");
  checkStatus("fmi2Instantiate", fmi2OK);  // reports what the logger found wrong
  return instance_ != nullptr;
}

void CallSequence::runWithoutInstance() {
  const std::size_t calls = 1 + rng_.below(5);
  for (std::size_t i = 0; i < calls; ++i) nullInstanceCall();
  fmi2FreeInstance(nullptr);
}

void CallSequence::finish() {
  if (rng_.chance(0.3)) terminate();
  while (!states_.empty()) releaseState(states_.size() - 1);
  fmi2FreeInstance(instance_);
  ++stats_.calls;
  instance_ = nullptr;
  log_.freed = true;
  if (rng_.chance(0.1)) fmi2FreeInstance(nullptr);
}

// ---- the choice of the next call ----

void CallSequence::nominalCall() {
  switch (phase_) {
    // states taken before the initialization ends hold no solver state: restoring them later is
    // a case of its own
    case Phase::Instantiated:
      if (!setupDone_) return setupExperiment(true);
      if (rng_.chance(0.3)) return setVariables(true);
      if (rng_.chance(0.1)) return getState();
      return enterInitialization();
    case Phase::Initializing:
      if (rng_.chance(0.25)) return setVariables(true);
      if (rng_.chance(0.1)) return getVariables();
      if (rng_.chance(0.15)) return getState();
      if (rng_.chance(0.1)) return checkRollback();
      return exitInitialization();
    case Phase::Stepping: return nominalStep();
    case Phase::StepFailed:
      if (!states_.empty() && rng_.chance(0.6)) return setState();
      if (rng_.chance(0.3)) return getVariables();
      return rng_.chance(0.5) ? reset() : terminate();
    case Phase::Terminated: return rng_.chance(0.5) ? reset() : getVariables();
    case Phase::Failed: return reset();
  }
}

void CallSequence::nominalStep() {
  const double r = rng_.unit();
  if (r < 0.40) return doStep(true);
  if (r < 0.52) return getVariables();
  if (r < 0.60) return setReals(true, true);
  if (r < 0.67) return getState();
  if (r < 0.75) return setState();
  if (r < 0.82) return serializeState();
  if (r < 0.90) return deserializeState(rng_.chance(0.5));
  if (r < 0.94) return checkRollback();
  if (r < 0.97) return queryStatus();
  return terminate();
}

void CallSequence::randomCall() {
  const bool good = rng_.chance(0.5);
  switch (rng_.below(20)) {
    case 0: return setupExperiment(good);
    case 1: return enterInitialization();
    case 2: return exitInitialization();
    case 3:
    case 4: return setVariables(good);
    case 5: return getVariables();
    case 6:
    case 7: return doStep(good);
    case 8: return getState();
    case 9: return setState();
    case 10: return freeState();
    case 11: return serializeState();
    case 12: return deserializeState(good);
    case 13: return queryStatus();
    case 14: return reset();
    case 15: return terminate();
    case 16: return unsupportedCall();
    case 17: return debugLogging();
    case 18: return nullInstanceCall();
    default: return fmi2FreeInstance(nullptr);  // harmless by the standard
  }
}

// ---- setup and initialization ----

void CallSequence::setupExperiment(bool good) {
  double start = rng_.chance(0.7) ? 0.0 : rng_.uniform(-1.0, 1.0);
  fmi2Boolean stopDefined = rng_.chance(0.5) ? fmi2True : fmi2False;
  double stop = start + rng_.logUniform(1e-3, 10.0);
  if (!good && rng_.chance(0.5)) start = rng_.pick({kNaN, kInf, -kInf, 1e300, -1e300, 1e15, -0.0});
  if (!good && rng_.chance(0.5)) {
    stopDefined = rng_.chance(0.8) ? fmi2True : fmi2False;
    stop = rng_.pick({kNaN, -kInf, kInf, start - 1.0, start});
  }
  const fmi2Boolean toleranceDefined = rng_.chance(0.5) ? fmi2True : fmi2False;
  const double tolerance = rng_.pick({1e-5, 0.0, -1.0, kNaN});
  if (trace_) std::printf("  fmi2SetupExperiment(start %.17g, stop %.17g, defined %d):\n", start, stop, stopDefined);
  const fmi2Status s = invoke("fmi2SetupExperiment", [&] {
    return fmi2SetupExperiment(instance_, toleranceDefined, tolerance, start, stopDefined, stop);
  });
  if (s <= fmi2Warning) {
    setupDone_ = true;
    time_ = start;
  }
}

void CallSequence::enterInitialization() {
  const fmi2Status s = invoke("fmi2EnterInitializationMode", [&] { return fmi2EnterInitializationMode(instance_); });
  if (s <= fmi2Warning) phase_ = Phase::Initializing;
}

void CallSequence::exitInitialization() {
  const fmi2Status s = invoke("fmi2ExitInitializationMode", [&] { return fmi2ExitInitializationMode(instance_); });
  if (s > fmi2Warning) {
    if (phase_ == Phase::Initializing) phase_ = Phase::Failed;
    return;
  }
  phase_ = Phase::Stepping;
  ++stats_.initializations;
  // one start-state solve per sequence is enough: later initializations (after fmi2Reset) skip it
  if (static_cast<Plan>(stats_.plan) == Plan::FullInit && !pinFor(fmu::kSolverPreload))
    pins_.push_back(booleanAssignment(fmu::kSolverPreload, false));
}

void CallSequence::reset() {
  const fmi2Status s = invoke("fmi2Reset", [&] { return fmi2Reset(instance_); });
  if (s != fmi2OK) {
    violation("fmi2Reset returned " + statusText(s) + "; it is allowed in every state");
    return;
  }
  phase_ = Phase::Instantiated;
  setupDone_ = false;
  time_ = 0.0;
  applyPins();
}

void CallSequence::terminate() {
  const fmi2Status s = invoke("fmi2Terminate", [&] { return fmi2Terminate(instance_); });
  if (s <= fmi2Warning) phase_ = Phase::Terminated;
}

// ---- pinned parameters ----

void CallSequence::applyPins() {
  for (const Assignment& a : pins_) {
    const fmi2Status s = apply(a);
    if (s != fmi2OK)
      violation("setting parameter " + std::to_string(a.vr) + " after instantiation or reset returned " + statusText(s));
  }
}

fmi2Status CallSequence::apply(const Assignment& a) {
  const fmi2ValueReference vr[1] = {a.vr};
  switch (a.type) {
    case fmu::Type::Real: return invoke("fmi2SetReal", [&] { return fmi2SetReal(instance_, vr, 1, &a.real); });
    case fmu::Type::Integer:
      return invoke("fmi2SetInteger", [&] { return fmi2SetInteger(instance_, vr, 1, &a.integer); });
    case fmu::Type::Boolean:
      return invoke("fmi2SetBoolean", [&] { return fmi2SetBoolean(instance_, vr, 1, &a.boolean); });
    case fmu::Type::String: {
      const fmi2String text[1] = {a.text.c_str()};
      return invoke("fmi2SetString", [&] { return fmi2SetString(instance_, vr, 1, text); });
    }
  }
  return fmi2Error;
}

// ---- invariants ----

void CallSequence::traceCall(const char* function, fmi2Status status) const {
  std::printf("  %s -> %s%s%.200s\n", function, statusText(status).c_str(), status == fmi2OK ? "" : ": ",
              status == fmi2OK ? "" : log_.lastMessage.c_str());
  std::fflush(stdout);
}

void CallSequence::checkStatus(const char* function, fmi2Status status) {
  ++stats_.calls;
  const int level = static_cast<int>(status);
  if (level < fmi2OK || level > fmi2Error)
    violation(std::string(function) + " returned " + statusText(status) + "; ChainDrive uses OK, warning, discard, error");
  else
    ++stats_.statusCounts[level];
  if (instance_ && (status == fmi2Error || status == fmi2Discard) && log_.explanations == 0)
    violation(std::string(function) + " returned " + statusText(status) + " without a log message");
  for (const std::string& problem : log_.problems) violation(std::string(function) + ": " + problem);
  log_.problems.clear();
}

void CallSequence::violation(const std::string& what) {
  ++stats_.violations;
  std::printf("fmi_call_fuzz: seed %" PRIu64 " (%s): %s (last FMU message: \"%.300s\")%s%s\n", seed_,
              planName(stats_.plan), what.c_str(), log_.lastMessage.c_str(), driveMutation_.empty() ? "" : "; the drive: ",
              driveMutation_.c_str());
  std::fflush(stdout);
}

}  // namespace detail
}  // namespace chaindrive::fuzz
