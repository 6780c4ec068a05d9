// Runs the call sequences in child processes, so that a crash, a sanitizer report, a leak found
// at exit or a hang is pinned to the seed of the sequence that caused it (the child reports the
// start and end of every sequence through a pipe), and the remaining sequences still run.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "call_sequence.h"

namespace chaindrive::fuzz {

struct FuzzOptions {
  std::uint64_t seed = 1;        // sequence k runs with seed + k
  std::uint64_t count = 0;       // number of sequences
  std::uint64_t batch = 100;     // sequences per child process
  double timeoutSeconds = 60;    // longest a sequence may take before it counts as a hang
  std::size_t maxFailures = 10;  // stop after this many failing sequences
  bool inProcess = false;        // no child processes (for a debugger); a crash ends the run
  bool trace = false;            // print every call with its status
};

/// What the sequences did, summed.
struct FuzzTotals {
  struct Reach {
    std::uint64_t sequences = 0, initialized = 0, stepped = 0;
  };
  Reach plans[kPlanCount];
  std::vector<Reach> combinations;  // of Plan::OtherMethod
  std::uint64_t calls = 0, initializations = 0, completedSteps = 0;
  std::uint64_t drivesExported = 0;  // Plan::Drive: drives whose FMU files the export wrote
  std::uint64_t statusCounts[4] = {};

  void add(const SequenceStats& s);
  Reach all() const;
};

struct FuzzFailure {
  std::uint64_t seed;
  std::string reason;
};

/// Runs options.count sequences; failures are printed as they are found (with the replay command).
std::vector<FuzzFailure> runSequences(const FuzzOptions& options, const FuzzPaths& paths, FuzzTotals& totals);

}  // namespace chaindrive::fuzz
