// The FMU state (fmi2GetFMUstate and friends): a copy of the protocol state of an instance and of
// its model's part, and its serialized form: magic, size of the solver state, the protocol
// fields, the model's fixed fields, the solver state. A deserialized state is checked field by
// field: bytes changed in storage or transfer must not become an instance state.
#pragma once

#include <cstddef>
#include <vector>

#include "host.h"
#include "model_adapter.h"

namespace chaindrive::fmu {

/// A copy of everything a rollback needs.
struct Snapshot {
  unsigned state = kStepComplete;
  double time = 0.0;
  double lastSuccessfulTime = 0.0;
  ModelAdapter::Snapshot model;
};

std::vector<char> serialize(const Snapshot& s);
/// fmi2Error (logged) if the bytes are not a state this binary can have written.
fmi2Status deserialize(Host& host, const char* data, std::size_t size, Snapshot& out);

}  // namespace chaindrive::fmu
