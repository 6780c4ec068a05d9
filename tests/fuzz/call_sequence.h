// One random FMI 2.0 call sequence against ChainDrive.fmu's C interface, from fmi2Instantiate
// to fmi2FreeInstance, with the fuzz's own invariants checked after every call:
//   - every status is fmi2OK, fmi2Warning, fmi2Discard or fmi2Error (the FMU uses no other);
//   - every fmi2Error and fmi2Discard of an instance comes with a non-empty log message, and the
//     logger is called with non-NULL strings, the instance's name and never after it was freed;
//   - calls on a NULL instance return fmi2Error; unsupported functions return fmi2Error;
//   - valid instantiation arguments give an instance (whatever the resource location), invalid
//     ones give NULL and a message;
//   - fmi2Reset succeeds in every state, parameters can be set after it, FMU states taken
//     by fmi2GetFMUstate serialize and deserialize, and everything can be freed after any error;
//   - a communication step repeated from a restored state (taken after a step or in
//     initialization mode) gives the same outputs, bit for bit.
// The sanitizers check the rest (memory errors, leaks, undefined behaviour).
#pragma once

#include <cstdint>

#include "fuzz_values.h"

namespace chaindrive::fuzz {

/// How far a sequence may get, and so what it costs.
enum class Plan : std::uint32_t {
  Poisoned,     // a parameter the initialization rejects: arguments, values, call order, states
  CheapInit,    // initializes without the start-state solve; communication steps of 10..100 us
  FullInit,     // the default start with the kinetostatic preload (about 1 s under the sanitizers)
  OtherMethod,  // another integrator, contact method or joint model; communication steps of 10 us
  Span,         // the span fidelity with any integrator; communication steps of 10..100 us
  Drive,        // a random drive description (drive_mutations.h) through the export's files and the
                // FMU's instantiation and initialization, a step or two at a given solver step; only
                // where FuzzPaths::drivePlanOnly asks for it (fmi_call_fuzz --drives)
};
constexpr std::uint32_t kPlanCount = 6;
const char* planName(std::uint32_t plan);

/// What one sequence did. Trivially copyable: it travels through a pipe.
struct SequenceStats {
  std::uint32_t plan = 0;
  std::uint32_t combination = 0;       // method combination of Plan::OtherMethod
  std::uint32_t calls = 0;             // FMI calls made
  std::uint32_t initializations = 0;   // fmi2ExitInitializationMode returned fmi2OK or fmi2Warning
  std::uint32_t completedSteps = 0;    // fmi2DoStep returned fmi2OK
  std::uint32_t statusCounts[4] = {};  // returned fmi2OK, fmi2Warning, fmi2Discard, fmi2Error
  std::uint32_t violations = 0;        // failed invariants (each printed with the seed)
  std::uint32_t driveExported = 0;     // Plan::Drive: the export wrote the FMU's files for the drive
};

/// Runs the call sequence of `seed`; the same seed makes the same calls. trace: print every call
/// with its status (for replaying a failing seed).
SequenceStats runSequence(std::uint64_t seed, const FuzzPaths& paths, bool trace);

}  // namespace chaindrive::fuzz
