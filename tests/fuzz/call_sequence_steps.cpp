// fmi2DoStep with good and bad communication points and step sizes; FMU states: get, set,
// free, serialize, deserialize from good, truncated and corrupted bytes.
#include <algorithm>
#include <cfloat>
#include <cinttypes>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>

#include "call_sequence_internal.h"

namespace chaindrive::fuzz::detail {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

Phase phaseAfterRestore(Phase saved) {
  // the FMU resumes a state taken after a failed step or an error as a completed step
  return saved == Phase::StepFailed || saved == Phase::Failed ? Phase::Stepping : saved;
}

std::uint64_t bitsOf(double v) {
  std::uint64_t b = 0;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

}  // namespace

// ---- communication steps ----

void CallSequence::doStep(bool good) {
  double communicationPoint = currentTime();
  double stepSize = rng_.logUniform(shortestStep_, longestStep_);
  if (good && stepsLeft_ > 0) {
    --stepsLeft_;
    // masters form communication points differently: an ulp of drift must be tolerated (where
    // an ulp is far below a step: at 1e15 s it is 0.125 s, and the FMU would integrate it)
    if (std::fabs(communicationPoint) < 1e6 && rng_.chance(0.2))
      communicationPoint = std::nextafter(communicationPoint, kInf);
  } else {
    scrambleStep(communicationPoint, stepSize);
  }
  const fmi2Boolean noPriorState = rng_.chance(0.5) ? fmi2True : fmi2False;
  if (trace_) std::printf("  fmi2DoStep(%.17g, %.17g):\n", communicationPoint, stepSize);
  const fmi2Status s = invoke("fmi2DoStep", [&] {
    return fmi2DoStep(instance_, communicationPoint, stepSize, noPriorState);
  });
  if (s == fmi2OK) {
    ++stats_.completedSteps;
    phase_ = Phase::Stepping;
    time_ = communicationPoint + stepSize;
  } else if (s == fmi2Discard) {
    phase_ = Phase::StepFailed;
  }
}

// Arguments the FMU must refuse, or accept without integrating (steps shorter than a grid unit).
void CallSequence::scrambleStep(double& communicationPoint, double& stepSize) {
  if (rng_.chance(0.5)) {
    // mismatches beyond any drift tolerance (the FMU accepts 1e-9 relative)
    const double t = communicationPoint, off = 1e-6 * std::max(1.0, std::fabs(t));
    communicationPoint = rng_.pick({kNaN, kInf, -kInf, t + off, t - off, t + 1e3 * off});
    return;
  }
  stepSize = rng_.pick({0.0, -0.0, -1e-5, -kInf, kNaN, kInf, 1e20, 1e300, DBL_MAX, 1e-300, 4.9e-324, 1e-12});
}

double CallSequence::currentTime() {
  fmi2Real t = kNaN;
  const fmi2Status s = invoke("fmi2GetRealStatus", [&] {
    return fmi2GetRealStatus(instance_, fmi2LastSuccessfulTime, &t);
  });
  return s == fmi2OK ? t : time_;
}

// ---- FMU states ----

void CallSequence::getState() {
  if (rng_.chance(0.05)) {
    invoke("fmi2GetFMUstate", [&] { return fmi2GetFMUstate(instance_, nullptr); });
    return;
  }
  const bool overwrite = !states_.empty() && (states_.size() >= kMaxStates || rng_.chance(0.3));
  if (overwrite) {
    SavedState& saved = states_[rng_.below(states_.size())];
    const fmi2Status s = invoke("fmi2GetFMUstate", [&] { return fmi2GetFMUstate(instance_, &saved.handle); });
    if (s == fmi2OK) saved = SavedState{saved.handle, phase_, time_};
    return;
  }
  SavedState saved{nullptr, phase_, time_};
  const fmi2Status s = invoke("fmi2GetFMUstate", [&] { return fmi2GetFMUstate(instance_, &saved.handle); });
  if (saved.handle) states_.push_back(saved);  // whatever was allocated gets freed
  if (s == fmi2OK && !saved.handle) violation("fmi2GetFMUstate returned fmi2OK and no state");
}

void CallSequence::setState() {
  const SavedState* saved = states_.empty() || rng_.chance(0.1) ? nullptr : &states_[rng_.below(states_.size())];
  const fmi2Status s = invoke("fmi2SetFMUstate", [&] { return fmi2SetFMUstate(instance_, saved ? saved->handle : nullptr); });
  if (s <= fmi2Warning && saved) {
    phase_ = phaseAfterRestore(saved->phase);
    time_ = saved->time;
    continueAfterRestore();
  }
}

// An importer restores a state to go on from it: often the next calls are a communication step
// (after the end of the initialization, if the state was taken before it). Not for the slow
// methods, whose sequences have only a step or two.
void CallSequence::continueAfterRestore() {
  if (static_cast<Plan>(stats_.plan) == Plan::OtherMethod || !rng_.chance(0.5)) return;
  if (phase_ == Phase::Initializing) exitInitialization();
  if (phase_ != Phase::Stepping) return;
  ++stepsLeft_;
  doStep(true);
}

void CallSequence::freeState() {
  if (states_.empty() || rng_.chance(0.15)) {  // nothing to free: a NULL pointer or a pointer to NULL
    fmi2FMUstate none = nullptr;
    const bool nullPointer = rng_.chance(0.5);
    invoke("fmi2FreeFMUstate", [&] { return fmi2FreeFMUstate(instance_, nullPointer ? nullptr : &none); });
    return;
  }
  releaseState(rng_.below(states_.size()));
}

void CallSequence::releaseState(std::size_t index) {
  fmi2FMUstate handle = states_[index].handle;
  states_.erase(states_.begin() + static_cast<std::ptrdiff_t>(index));
  const fmi2Status s = invoke("fmi2FreeFMUstate", [&] { return fmi2FreeFMUstate(instance_, &handle); });
  if (s != fmi2OK || handle) violation("fmi2FreeFMUstate of a state the FMU made returned " + statusText(s) +
                                       (handle ? " and left the pointer set" : ""));
}

// ---- serialized FMU states ----

void CallSequence::serializeState() {
  size_t size = 0;
  if (states_.empty() || rng_.chance(0.05)) {  // no state to serialize
    invoke("fmi2SerializedFMUstateSize", [&] { return fmi2SerializedFMUstateSize(instance_, nullptr, &size); });
    return;
  }
  const SavedState& saved = states_[rng_.below(states_.size())];
  const bool nullSize = rng_.chance(0.05);
  const fmi2Status sized = invoke("fmi2SerializedFMUstateSize", [&] {
    return fmi2SerializedFMUstateSize(instance_, saved.handle, nullSize ? nullptr : &size);
  });
  if (nullSize) return;
  if (sized != fmi2OK) return violation("fmi2SerializedFMUstateSize refused a state the FMU made");
  // 0: a buffer one byte short, 1: one byte long, 2: no buffer, otherwise the right size
  const std::size_t mode = rng_.below(8);
  std::vector<char> bytes(size + 1);
  const size_t passed = mode == 0 && size > 0 ? size - 1 : mode == 1 ? size + 1 : size;
  const fmi2Status s = invoke("fmi2SerializeFMUstate", [&] {
    return fmi2SerializeFMUstate(instance_, saved.handle, mode == 2 ? nullptr : bytes.data(), passed);
  });
  if (mode <= 2) return;
  if (s != fmi2OK) return violation("fmi2SerializeFMUstate refused a buffer of the size it asked for");
  bytes.resize(size);
  if (blobs_.size() >= kMaxBlobs) blobs_.erase(blobs_.begin());
  blobs_.push_back(Blob{std::move(bytes), saved.phase, saved.time});
}

void CallSequence::deserializeState(bool good) {
  const bool original = good && !blobs_.empty();
  Blob blob = blobs_.empty() ? Blob{} : rng_.pick(blobs_);
  if (!original) {
    corrupt(blob.bytes);
    blob.phase = Phase::Stepping;
  }
  const bool nullBytes = !good && rng_.chance(0.1);
  const bool nullTarget = !good && rng_.chance(0.05);
  const bool overwrite = !states_.empty() && (states_.size() >= kMaxStates || rng_.chance(0.3));
  SavedState fresh{nullptr, blob.phase, blob.time};
  SavedState& target = overwrite ? states_[rng_.below(states_.size())] : fresh;
  const fmi2Status s = invoke("fmi2DeSerializeFMUstate", [&] {
    return fmi2DeSerializeFMUstate(instance_, nullBytes ? nullptr : blob.bytes.data(), blob.bytes.size(),
                                   nullTarget ? nullptr : &target.handle);
  });
  if (fresh.handle) states_.push_back(fresh);  // whatever was allocated gets freed
  if (s == fmi2OK && overwrite) target = SavedState{target.handle, blob.phase, blob.time};
  if (original && s != fmi2OK) violation("fmi2DeSerializeFMUstate refused bytes of fmi2SerializeFMUstate");
  if (s != fmi2OK || nullTarget || !rng_.chance(0.75)) return;
  // what an importer deserializes, it restores
  const SavedState restored = overwrite ? target : states_.back();
  const fmi2Status set = invoke("fmi2SetFMUstate", [&] { return fmi2SetFMUstate(instance_, restored.handle); });
  if (set <= fmi2Warning) {
    phase_ = phaseAfterRestore(restored.phase);
    time_ = restored.time;
    continueAfterRestore();
  }
}

// Damage as a broken file or transfer would do it; some damage keeps the size and the header.
void CallSequence::corrupt(std::vector<char>& bytes) {
  // Offsets of the header fields as fmu::serialize writes them (magic, component count,
  // machine state (4 bytes), eight doubles, two counters); should the layout change, these
  // corruptions only become less targeted.
  constexpr std::size_t kHeaderFields[] = {8, 16, 20, 28, 36, 44, 52, 60, 68, 76, 84, 92};
  const std::uint64_t extremes[] = {0u, 3u, 64u, ~std::uint64_t{0}, std::uint64_t{1} << 63, (std::uint64_t{1} << 63) - 1,
                                    std::uint64_t{1} << 40, bitsOf(kNaN), bitsOf(-kInf), bitsOf(-1.0),
                                    bitsOf(1e10), bitsOf(-1e10), bitsOf(1e300)};
  auto overwrite = [&](std::size_t offset, std::uint64_t word, std::size_t width) {
    if (offset + width <= bytes.size()) std::memcpy(bytes.data() + offset, &word, width);  // little endian
  };
  switch (rng_.below(9)) {
    case 0: bytes.resize(rng_.below(bytes.size() + 1)); break;  // truncated
    case 1:                                                     // a few bytes flipped anywhere
      for (std::size_t k = 1 + rng_.below(4); k > 0 && !bytes.empty(); --k)
        bytes[rng_.below(bytes.size())] ^= static_cast<char>(1 + rng_.below(255));
      break;
    case 2:
    case 5:
    case 6:
    case 7: {  // one header field set to an extreme value: the size still fits
      const std::size_t offset = rng_.pick(kHeaderFields);
      const std::uint64_t word = rng_.pick(extremes);
      overwrite(offset, word, offset == 16 ? 4 : 8);
      if (trace_) std::printf("  (serialized state: header field at byte %zu set to 0x%016" PRIx64 ")\n", offset, word);
      break;
    }
    case 3: bytes.resize(bytes.size() + 1 + rng_.below(16), 'Z'); break;  // trailing bytes
    case 4:  // the magic number (if any) followed by garbage
      bytes.resize(std::min<std::size_t>(bytes.size(), 8) + rng_.below(200));
      for (std::size_t i = 8; i < bytes.size(); ++i) bytes[i] = static_cast<char>(rng_.bits());
      break;
    default: overwrite(8, rng_.pick({std::uint64_t{0}, std::uint64_t{1} << 61, ~std::uint64_t{0}}), 8); break;  // the count
  }
}

}  // namespace chaindrive::fuzz::detail
