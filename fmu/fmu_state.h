// The FMU state (fmi2GetFMUstate and friends): a copy of the protocol state of an instance and of
// its model's part, and its serialized form: magic, size of the solver state, the protocol
// fields, the model's fixed fields, the solver state. A deserialized state is checked field by
// field: bytes changed in storage or transfer must not become an instance state.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "adapter_contract.h"
#include "host.h"
#include "state_bytes.h"

namespace chaindrive::fmu {

/// A copy of everything a rollback needs.
template <CHAINDRIVE_MODEL_ADAPTER Model>
struct FmuState {
  ProtocolSnapshot protocol;
  typename Model::Snapshot model;
};

// the protocol's fields of a serialized state (fmu_state.cpp)
constexpr std::size_t kProtocolFieldBytes = sizeof(unsigned) + 2 * sizeof(double);  // state, the two times
void writeProtocolFields(const ProtocolSnapshot& s, std::vector<char>& out);
void readProtocolFields(ByteReader& in, ProtocolSnapshot& s);
/// The first field no instance can have written; nullptr if none.
const char* invalidProtocolField(const ProtocolSnapshot& s);

template <CHAINDRIVE_MODEL_ADAPTER Model>
std::vector<char> serialize(const FmuState<Model>& s) {
  std::vector<char> out;
  putBytes(out, Model::kStateMagic, sizeof Model::kStateMagic);
  const std::uint64_t n = s.model.y.size();
  putField(out, n);
  writeProtocolFields(s.protocol, out);
  Model::writeFields(s.model, out);
  if (n) putBytes(out, s.model.y.data(), n * sizeof(double));
  return out;
}

/// fmi2Error (logged) if the bytes are not a state this binary can have written.
template <CHAINDRIVE_MODEL_ADAPTER Model>
fmi2Status deserialize(Host& host, const char* data, std::size_t size, FmuState<Model>& s) {
  // the fixed part: magic, size of the solver state, protocol fields, the model's fields
  constexpr const char(&magic)[8] = Model::kStateMagic;
  const std::size_t head = sizeof magic + sizeof(std::uint64_t) + kProtocolFieldBytes + Model::kSnapshotFieldBytes;
  if (!data || size < head || std::memcmp(data, magic, sizeof magic) != 0) {
    host.log(fmi2Error, "logStatusError", "fmi2DeSerializeFMUstate: %zu bytes are not a serialized %s state", size,
             Model::kModelWord);
    return fmi2Error;
  }
  ByteReader in(data + sizeof magic);
  std::uint64_t n = 0;
  in.field(n);
  if ((size - head) % sizeof(double) != 0 || n != (size - head) / sizeof(double)) {  // no overflow in n * 8
    host.log(fmi2Error, "logStatusError", "fmi2DeSerializeFMUstate: %zu bytes do not match a state of %llu components",
             size, static_cast<unsigned long long>(n));
    return fmi2Error;
  }
  readProtocolFields(in, s.protocol);
  Model::readFields(in, s.model);
  const char* bad = invalidProtocolField(s.protocol);
  if (!bad) bad = Model::invalidField(s.model, n);
  if (bad) {
    host.log(fmi2Error, "logStatusError", "fmi2DeSerializeFMUstate: the serialized state is corrupt (field %s)", bad);
    return fmi2Error;
  }
  s.model.y.resize(n);
  if (n) in.get(s.model.y.data(), n * sizeof(double));
  return fmi2OK;
}

}  // namespace chaindrive::fmu
