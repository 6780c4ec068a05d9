// A simulation state on disk: the time and the state vector of a drive, bit-exact (hexadecimal
// floating point), so that a run can continue from where another one stopped (e.g. every method
// of a study from one settled state past the start transient).
#pragma once

#include <string>
#include <vector>

#include "assembly/model.h"

namespace chaindrive {

struct StateSnapshot {
  double time = 0.0;
  std::vector<double> y;
};

/// Writes the snapshot as JSON (schema "chaindrive.state/4"; "/3" and "/2" are read where they
/// are the same, the step means' accumulators zero) with the drive's name, number of links and of
/// states and the fidelity (written unless link), so that a
/// mismatching drive or fidelity is recognised on reading.
void writeStateFile(const std::string& path, const Model& m, const StateSnapshot& s,
                    Fidelity fidelity = Fidelity::Link);

/// Reads a snapshot of `states` values for drive m in `fidelity`. Throws std::runtime_error
/// naming the file and the problem (unreadable, not a state file, another fidelity, another
/// drive: links or state count differ, a non-finite or malformed value).
StateSnapshot readStateFile(const std::string& path, const Model& m, int states,
                            Fidelity fidelity = Fidelity::Link);

}  // namespace chaindrive
