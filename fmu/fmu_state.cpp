#include "fmu_state.h"

#include <cmath>
#include <cstdint>
#include <cstring>

#include "state_bytes.h"

namespace chaindrive::fmu {

namespace {

constexpr const char (&kMagic)[8] = ModelAdapter::kStateMagic;

// The first protocol field of a deserialized state that no instance can have written, else the
// model's (nullptr if none).
const char* invalidHeaderField(const Snapshot& s, std::uint64_t components) {
  if (s.state == 0 || (s.state & (s.state - 1)) != 0 || (s.state & ~kAllStates) != 0) return "state";
  if (!std::isfinite(s.time) || !std::isfinite(s.lastSuccessfulTime)) return "time";
  return ModelAdapter::invalidField(s.model, components);
}

}  // namespace

std::vector<char> serialize(const Snapshot& s) {
  std::vector<char> out;
  putBytes(out, kMagic, sizeof kMagic);
  const std::uint64_t n = s.model.y.size();
  putField(out, n);
  putField(out, s.state);
  putField(out, s.time);
  putField(out, s.lastSuccessfulTime);
  ModelAdapter::writeFields(s.model, out);
  if (n) putBytes(out, s.model.y.data(), n * sizeof(double));
  return out;
}

fmi2Status deserialize(Host& host, const char* data, std::size_t size, Snapshot& s) {
  // the fixed part: magic, size of the solver state, protocol fields, the model's fields
  const std::size_t head = sizeof kMagic + sizeof(std::uint64_t) + sizeof(unsigned) + 2 * sizeof(double) +
                           ModelAdapter::kSnapshotFieldBytes;
  if (!data || size < head || std::memcmp(data, kMagic, sizeof kMagic) != 0) {
    host.log(fmi2Error, "logStatusError", "fmi2DeSerializeFMUstate: %zu bytes are not a serialized %s state", size,
             kModelIdentifier);
    return fmi2Error;
  }
  ByteReader in(data + sizeof kMagic);
  std::uint64_t n = 0;
  in.field(n);
  if ((size - head) % sizeof(double) != 0 || n != (size - head) / sizeof(double)) {  // no overflow in n * 8
    host.log(fmi2Error, "logStatusError", "fmi2DeSerializeFMUstate: %zu bytes do not match a state of %llu components",
             size, static_cast<unsigned long long>(n));
    return fmi2Error;
  }
  in.field(s.state);
  in.field(s.time);
  in.field(s.lastSuccessfulTime);
  ModelAdapter::readFields(in, s.model);
  if (const char* bad = invalidHeaderField(s, n)) {
    host.log(fmi2Error, "logStatusError", "fmi2DeSerializeFMUstate: the serialized state is corrupt (field %s)", bad);
    return fmi2Error;
  }
  s.model.y.resize(n);
  if (n) in.get(s.model.y.data(), n * sizeof(double));
  return fmi2OK;
}

}  // namespace chaindrive::fmu
