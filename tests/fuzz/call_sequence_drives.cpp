// Plan::Drive of the call sequence (call_sequence.h): a random drive description through the
// export's C++ part (writeFmuFiles: the description reader, the interface, the model description
// and resources) and, where it is written, the FMU's instantiation from those resources and its
// initialization (the drive's assembly, closure, pose and, in some sequences, its preload), then a
// step or two. The invariants: the export refuses a drive with one line that is not a library's
// bare message; the FMU answers with statuses and one-line log messages; the sanitizers and the
// supervisor's watchdog see the rest (crashes, memory errors, leaks, hangs).
#include <cstdio>
#include <string>

#include "call_sequence_internal.h"
#include "drive_mutations.h"
#include "description/drive_description.h"
#include "interface/fmu_files.h"

namespace chaindrive::fuzz::detail {

namespace {

// Messages of a failure the code did not expect: a library's own text, not one naming the field.
const char* const kBareMessages[] = {"[json.exception.type_error", "[json.exception.out_of_range",
                                     "[json.exception.invalid_iterator", "std::bad_alloc", "bad_array_new_length",
                                     "vector::", "basic_string", "stod", "stoi", "map::at", "bad_optional_access"};

// The step the drive sequences run at: given, so that the FMU does not probe the drive's step
// (seconds of runs under the sanitizers, run/step_probe.h); the real-time method's default.
constexpr double kDriveStep = 1e-4 / 28;

// The share of drives initialized with the preload (the start-state solve: seconds under the
// sanitizers on a drive that initializes, the rest start from the nominal pose).
constexpr double kShareDrivePreload = 0.15;

}  // namespace

void CallSequence::checkOneLine(const std::string& where, const std::string& message) {
  if (message.empty()) violation(where + ": an empty message");
  if (message.find('\n') != std::string::npos) violation(where + ": a message of more than one line: " + message);
  for (const char* bare : kBareMessages)
    if (message.find(bare) != std::string::npos) violation(where + ": a library's message, not the field's: " + message);
}

bool CallSequence::exportDrive(std::string& guid) {
  const std::string text = mutatedDrive(rng_, paths_.driveBases, driveMutation_);
  if (trace_) std::printf("  drive: %s\n", driveMutation_.c_str());
  try {
    guid = writeFmuFiles(paths_.driveWorkDir, text).guid;
  } catch (const DescriptionError& e) {  // (every problem a line of its own; the tools join them)
    if (trace_) std::printf("  export refused: %s\n", e.what());
    if (e.problems().empty()) violation("the export refused the drive without a problem");
    for (const std::string& problem : e.problems()) checkOneLine("the export", problem);
    return false;
  } catch (const std::exception& e) {
    if (trace_) std::printf("  export refused: %s\n", e.what());
    checkOneLine("the export", e.what());
    return false;
  }
  ++stats_.driveExported;
  return true;
}

bool CallSequence::instantiateDrive(const std::string& guid) {
  callbacks_.logger = recordLogMessage;
  callbacks_.componentEnvironment = &log_;
  log_.expectedName = "fuzz";
  const std::string location = "file://" + paths_.driveWorkDir + "/resources";
  instance_ = fmi2Instantiate("fuzz", fmi2CoSimulation, guid.c_str(), location.c_str(), &callbacks_, fmi2False,
                              fmi2True);
  checkStatus("fmi2Instantiate", instance_ ? fmi2OK : fmi2Error);
  if (!instance_) {
    if (log_.explanations == 0) violation("fmi2Instantiate refused the exported drive without an error message");
    else checkOneLine("fmi2Instantiate", log_.lastMessage);
  }
  return instance_ != nullptr;
}

void CallSequence::runDrive() {
  std::string guid;
  if (!exportDrive(guid) || !instantiateDrive(guid)) return;
  pins_ = {realAssignment(fmu::kSolverStep, kDriveStep), booleanAssignment(fmu::kSolverPreload, rng_.chance(kShareDrivePreload))};
  applyPins();
  setupExperiment(true);
  enterInitialization();
  exitInitialization();
  if (phase_ != Phase::Stepping) checkOneLine("fmi2ExitInitializationMode", log_.lastMessage);
  for (std::size_t steps = 1 + rng_.below(2); phase_ == Phase::Stepping && steps > 0; --steps) {
    doStep(true);
    if (phase_ != Phase::Stepping) checkOneLine("fmi2DoStep", log_.lastMessage);
  }
  finish();
}

}  // namespace chaindrive::fuzz::detail
