// The protocol side of an FMU instance: logging with its categories, the state of the FMI 2.0
// co-simulation state machine, the communication times and the resources folder. Host owns this
// state, and every change of it is one of its methods: the public ones are what a model adapter
// and the FMI functions call (Reference-FMUs' model code reads the ModelInstance for the same
// things), the protected ones are the state machine's transitions, which only the protocol
// (Instance, instance.h) makes. It knows no model.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "fmi2Functions.h"

namespace chaindrive::fmu {

/// States of the FMI 2.0 co-simulation state machine (bit masks for the allowed-call tables).
enum State : unsigned {
  kInstantiated = 1u << 0,
  kInitializationMode = 1u << 1,
  kStepComplete = 1u << 2,
  kStepFailed = 1u << 3,
  kTerminated = 1u << 4,
  kError = 1u << 5,
};

constexpr unsigned kAllStates =
    kInstantiated | kInitializationMode | kStepComplete | kStepFailed | kTerminated | kError;

/// The protocol's part of an FMU state (fmu_state.h).
struct ProtocolSnapshot {
  unsigned state = kStepComplete;
  double time = 0.0;
  double lastSuccessfulTime = 0.0;
};

class Host {
 public:
  Host(const char* instanceName, const fmi2CallbackFunctions* callbacks, const char* resourceLocation, bool loggingOn);

  // logging (printf-style message; errors and warnings are always passed to the environment,
  // other categories when logging is on and the category is enabled)
  void log(fmi2Status status, const char* category, const char* fmt, ...);
  fmi2Status setDebugLogging(bool on, std::size_t n, const fmi2String categories[]);

  unsigned state() const { return state_; }
  /// Returns false after logging "<function>: not allowed in state <state>" if the current state
  /// is not in `allowedStates`.
  bool allowed(const char* function, unsigned allowedStates);
  /// Before the initialization ends (instantiated or initialization mode): parameters may change.
  bool initializing() const { return (state_ & (kInstantiated | kInitializationMode)) != 0; }

  /// The master's communication point: the start time, then cp + h of the last step as the
  /// master formed it.
  double time() const { return time_; }
  /// The model's run starts at time(): that is the last successful time from now on.
  void runStarted() { lastSuccessfulTime_ = time_; }

  /// The resources folder of the FMU (empty if the importer gave none).
  const std::string& resourceDir() const { return resourceDir_; }

 protected:
  // ---- the state machine's transitions ----
  /// fmi2SetupExperiment's times; false (logged) if they cannot start a run.
  bool setExperiment(double startTime, bool stopTimeDefined, double stopTime);
  fmi2Status enterInitializationMode();
  void startStepping() { state_ = kStepComplete; }  // the initialization succeeded
  /// fmi2DoStep's arguments against the FMU time and the stop time: the step's end in tEnd, or
  /// false (logged).
  bool stepAcceptable(double cp, double h, double& tEnd);
  void stepCompleted(double tEnd);
  void stepDiscarded();  // the model kept its last successful state
  fmi2Status terminate();
  void enterErrorState() { state_ = kError; }
  void resetProtocol();  // as instantiated

  // ---- the status queries (their state: this class's) ----
  fmi2Status getRealStatus(fmi2StatusKind kind, fmi2Real* value);
  fmi2Status getStatus(fmi2StatusKind kind, fmi2Status* value);

  // ---- the protocol's part of an FMU state ----
  ProtocolSnapshot protocolSnapshot() const { return {state_, time_, lastSuccessfulTime_}; }
  void restoreProtocol(const ProtocolSnapshot& s);

 private:
  unsigned state_ = kInstantiated;
  double time_ = 0.0, startTime_ = 0.0, stopTime_ = 0.0, lastSuccessfulTime_ = 0.0;
  bool stopTimeDefined_ = false;
  std::string name_;
  fmi2CallbackFunctions callbacks_;
  std::string resourceDir_;
  bool loggingOn_ = false;
  std::vector<std::string> categories_;  // enabled categories; empty = all
};

/// How a file URI's path reads as a path of the operating system.
enum class PathStyle { Posix, Windows };
#if defined(_WIN32)
constexpr PathStyle kNativePathStyle = PathStyle::Windows;
#else
constexpr PathStyle kNativePathStyle = PathStyle::Posix;
#endif

/// The resources directory from fmuResourceLocation (file:///dir, file:////dir,
/// file://localhost/dir, a trailing '/', percent-encoding, NULL) as a path of `style`: on Windows
/// file:///C:/dir is C:/dir and file://server/share a UNC path; empty if there is none.
std::string resourceDirectory(const char* location, PathStyle style);

}  // namespace chaindrive::fmu
