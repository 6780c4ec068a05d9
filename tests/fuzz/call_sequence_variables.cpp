// fmi2Set*/fmi2Get* with one to four value references of the model description (and invalid
// ones), good and bad values, NULL arrays and empty calls.
#include <cstring>
#include <limits>
#include <optional>

#include "call_sequence_internal.h"

namespace chaindrive::fuzz::detail {

const Assignment* CallSequence::pinFor(unsigned vr) const {
  for (const Assignment& a : pins_)
    if (a.vr == vr) return &a;
  return nullptr;
}

double CallSequence::realFor(unsigned vr, bool good) {
  // a pinned parameter only ever gets values that the initialization rejects or the setter
  // refuses: a sequence planned to fail its initialization (or to stay cheap) stays so
  if (pinFor(vr)) return badReal(rng_, vr);
  return good || rng_.chance(0.5) ? goodReal(rng_, vr) : badReal(rng_, vr);
}

void CallSequence::setVariables(bool good) {
  switch (rng_.below(4)) {
    case 0: return setReals(good, false);
    case 1: return setIntegers(good);
    case 2: return setBooleans();
    default: return setStrings(good);
  }
}

void CallSequence::setReals(bool good, bool inputsOnly) {
  const std::size_t n = arrayLength();
  std::vector<fmi2ValueReference> vrs(n);
  std::vector<fmi2Real> values(n);
  for (std::size_t i = 0; i < n; ++i) {
    vrs[i] = inputsOnly ? rng_.pick({fmu::kCrankshaftW, fmu::kCamshaftIntakeTau, fmu::kCamshaftExhaustTau,
                                     fmu::kTensionerSupplyPressure})
                        : valueReferenceFor(rng_, fmu::Type::Real);
    values[i] = realFor(vrs[i], good);
  }
  const bool nullVrs = n > 0 && !good && rng_.chance(0.1);
  const bool nullValues = n > 0 && !good && rng_.chance(0.1);
  invoke("fmi2SetReal", [&] {
    return fmi2SetReal(instance_, nullVrs ? nullptr : vrs.data(), n, nullValues ? nullptr : values.data());
  });
}

void CallSequence::setIntegers(bool good) {
  const std::size_t n = arrayLength();
  std::vector<fmi2ValueReference> vrs(n);
  std::vector<fmi2Integer> values(n);
  for (std::size_t i = 0; i < n; ++i) {
    vrs[i] = valueReferenceFor(rng_, fmu::Type::Integer);
    const bool bad = pinFor(vrs[i]) || (!good && rng_.chance(0.5));
    values[i] = bad ? badInteger(rng_) : goodInteger(rng_, vrs[i]);
  }
  const bool nullValues = n > 0 && !good && rng_.chance(0.1);
  invoke("fmi2SetInteger", [&] { return fmi2SetInteger(instance_, vrs.data(), n, nullValues ? nullptr : values.data()); });
}

void CallSequence::setBooleans() {
  const std::size_t n = arrayLength();
  std::vector<fmi2ValueReference> vrs(n);
  std::vector<fmi2Boolean> values(n);
  for (std::size_t i = 0; i < n; ++i) {
    vrs[i] = valueReferenceFor(rng_, fmu::Type::Boolean);
    const Assignment* pin = pinFor(vrs[i]);
    // fmi2Boolean is an int: C importers pass any value
    values[i] = pin ? pin->boolean : rng_.pick({fmi2True, fmi2False, 2, -1});
  }
  invoke("fmi2SetBoolean", [&] { return fmi2SetBoolean(instance_, vrs.data(), n, values.data()); });
}

void CallSequence::setStrings(bool good) {
  const std::size_t n = arrayLength();
  std::vector<fmi2ValueReference> vrs(n);
  std::vector<std::optional<std::string>> texts(n);
  for (std::size_t i = 0; i < n; ++i) {
    vrs[i] = valueReferenceFor(rng_, fmu::Type::String);
    const bool bad = pinFor(vrs[i]) || (!good && rng_.chance(0.5));
    texts[i] = bad ? badString(rng_, vrs[i], paths_) : goodString(rng_, vrs[i], paths_);
  }
  std::vector<fmi2String> values(n);
  for (std::size_t i = 0; i < n; ++i) values[i] = texts[i] ? texts[i]->c_str() : nullptr;
  const bool nullVrs = n > 0 && !good && rng_.chance(0.1);
  invoke("fmi2SetString", [&] { return fmi2SetString(instance_, nullVrs ? nullptr : vrs.data(), n, values.data()); });
}

void CallSequence::getVariables() {
  switch (rng_.below(4)) {
    case 0: return getReals();
    case 1: return getIntegers();
    case 2: return getBooleans();
    default: return getStrings();
  }
}

void CallSequence::getReals() {
  const std::size_t n = arrayLength();
  std::vector<fmi2ValueReference> vrs(n);
  for (auto& vr : vrs) vr = valueReferenceFor(rng_, fmu::Type::Real);
  std::vector<fmi2Real> values(n, std::numeric_limits<double>::quiet_NaN());
  const bool nullValues = n > 0 && rng_.chance(0.05);
  invoke("fmi2GetReal", [&] { return fmi2GetReal(instance_, vrs.data(), n, nullValues ? nullptr : values.data()); });
}

void CallSequence::getIntegers() {
  const std::size_t n = arrayLength();
  std::vector<fmi2ValueReference> vrs(n);
  for (auto& vr : vrs) vr = valueReferenceFor(rng_, fmu::Type::Integer);
  std::vector<fmi2Integer> values(n);
  const bool nullVrs = n > 0 && rng_.chance(0.05);
  invoke("fmi2GetInteger", [&] { return fmi2GetInteger(instance_, nullVrs ? nullptr : vrs.data(), n, values.data()); });
}

void CallSequence::getBooleans() {
  const std::size_t n = arrayLength();
  std::vector<fmi2ValueReference> vrs(n);
  for (auto& vr : vrs) vr = valueReferenceFor(rng_, fmu::Type::Boolean);
  std::vector<fmi2Boolean> values(n);
  invoke("fmi2GetBoolean", [&] { return fmi2GetBoolean(instance_, vrs.data(), n, values.data()); });
}

void CallSequence::getStrings() {
  const std::size_t n = arrayLength();
  std::vector<fmi2ValueReference> vrs(n);
  for (auto& vr : vrs) vr = valueReferenceFor(rng_, fmu::Type::String);
  std::vector<fmi2String> values(n, nullptr);
  const fmi2Status s = invoke("fmi2GetString", [&] { return fmi2GetString(instance_, vrs.data(), n, values.data()); });
  if (s != fmi2OK) return;
  for (fmi2String text : values) {
    if (!text) return violation("fmi2GetString returned fmi2OK and a NULL string");
    (void)std::strlen(text);  // the sanitizer checks that the whole string is readable
  }
}

}  // namespace chaindrive::fuzz::detail
