// The call sequence of the fuzz (call_sequence.h), split over call_sequence.cpp (the frame,
// call choice, initialization, invariants), call_sequence_variables.cpp (get/set),
// call_sequence_steps.cpp (doStep, FMU states, serialization), call_sequence_rollback.cpp (the
// rollback check) and call_sequence_queries.cpp (status queries, unsupported functions, NULL
// instances, logging).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "call_sequence.h"

namespace chaindrive::fuzz::detail {

constexpr std::size_t kMaxStates = 4;  // FMU states held at once
constexpr std::size_t kMaxBlobs = 3;   // serialized states kept for deserialization

/// Where the sequence believes the FMU is, from the statuses it returned. It only steers the
/// choice of the next call; the FMU must cope with every call in every state anyway.
enum class Phase { Instantiated, Initializing, Stepping, StepFailed, Terminated, Failed };

/// The logger's view of one instance (its componentEnvironment).
struct LogRecord {
  std::string expectedName;           // the instanceName passed to fmi2Instantiate ("": not checked)
  bool freed = false;                 // fmi2FreeInstance was called: no message may follow
  int explanations = 0;               // non-empty messages of status fmi2Discard or worse in the current call
  std::string lastMessage;            // the last message of the current call, for reports and traces
  std::vector<std::string> problems;  // what was wrong with the logger calls
};

/// The fmi2CallbackLogger of the fuzz: checks and records every message in the LogRecord.
void recordLogMessage(fmi2ComponentEnvironment environment, fmi2String instanceName, fmi2Status status,
                      fmi2String category, fmi2String message, ...);

struct SavedState {
  fmi2FMUstate handle = nullptr;
  Phase phase = Phase::Stepping;  // where the FMU was when the state was taken
  double time = 0.0;
};

struct Blob {
  std::vector<char> bytes;
  Phase phase = Phase::Stepping;
  double time = 0.0;
};

std::string statusText(fmi2Status s);

struct Outputs;  // call_sequence_rollback.cpp

class CallSequence {
 public:
  CallSequence(std::uint64_t seed, const FuzzPaths& paths, bool trace)
      : rng_(seed), seed_(seed), paths_(paths), trace_(trace) {}
  SequenceStats run();

 private:
  // the frame of a sequence
  void choosePlan();
  void checkVersionStrings();
  bool instantiate();
  void runWithoutInstance();
  void finish();
  // Plan::Drive (call_sequence_drives.cpp)
  void runDrive();
  bool exportDrive(std::string& guid);
  bool instantiateDrive(const std::string& guid);
  void checkOneLine(const std::string& where, const std::string& message);
  // the choice of the next call
  void nominalCall();
  void nominalStep();
  void randomCall();
  // one FMI call each; good: arguments an importer that follows the standard would pass
  void setupExperiment(bool good);
  void enterInitialization();
  void exitInitialization();
  void reset();
  void terminate();
  void setVariables(bool good);
  void setReals(bool good, bool inputsOnly);
  void setIntegers(bool good);
  void setBooleans();
  void setStrings(bool good);
  void getVariables();
  void getReals();
  void getIntegers();
  void getBooleans();
  void getStrings();
  void doStep(bool good);
  void scrambleStep(double& communicationPoint, double& stepSize);
  double currentTime();
  void getState();
  void setState();
  void continueAfterRestore();
  void checkRollback();
  bool stepFrom(bool endInitialization, double stepSize, double& communicationPoint);
  bool readOutputs(Outputs& o);
  void freeState();
  void releaseState(std::size_t index);
  void serializeState();
  void deserializeState(bool good);
  void corrupt(std::vector<char>& bytes);
  void queryStatus();
  void unsupportedCall();
  void nullInstanceCall();
  void debugLogging();
  // values and pinned parameters
  std::size_t arrayLength() { return rng_.chance(0.1) ? 0 : 1 + rng_.below(4); }
  const Assignment* pinFor(unsigned vr) const;
  void applyPins();
  fmi2Status apply(const Assignment& a);
  double realFor(unsigned vr, bool good);
  // invariants
  template <class Call>
  fmi2Status invoke(const char* function, Call&& call) {
    log_.explanations = 0;
    log_.lastMessage.clear();
    const fmi2Status status = call();
    if (trace_) traceCall(function, status);
    checkStatus(function, status);
    return status;
  }
  void traceCall(const char* function, fmi2Status status) const;
  void checkStatus(const char* function, fmi2Status status);
  void violation(const std::string& what);

  Rng rng_;
  std::uint64_t seed_;
  const FuzzPaths& paths_;
  bool trace_;
  SequenceStats stats_;
  LogRecord log_;
  fmi2CallbackFunctions callbacks_{};
  fmi2Component instance_ = nullptr;
  std::vector<Assignment> pins_;  // parameters that only ever get values that keep a run cheap or failing
  Phase phase_ = Phase::Instantiated;
  bool setupDone_ = false;
  double time_ = 0.0;  // communication point the sequence believes the FMU is at
  int stepsLeft_ = 8;  // doSteps with good arguments still allowed (they cost integration)
  bool springDamper_ = false;  // the instance is the FMU of the spring-damper variant (FuzzPaths)
  double shortestStep_ = 1e-5, longestStep_ = 1e-4;
  std::vector<SavedState> states_;
  std::vector<Blob> blobs_;
  std::string driveMutation_;  // Plan::Drive: what was changed, for the reports
};

}  // namespace chaindrive::fuzz::detail
