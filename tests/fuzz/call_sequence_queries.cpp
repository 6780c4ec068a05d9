// Status queries, the unsupported functions, calls on a NULL instance, debug logging.
#include <string>
#include <vector>

#include "call_sequence_internal.h"

namespace chaindrive::fuzz::detail {

namespace {

// Arguments for the calls that take them only to refuse them.
struct SpareArguments {
  fmi2ValueReference vr[2] = {fmu::kCrankshaftW, fmu::kCrankshaftPhi};
  fmi2Real reals[2] = {1.0, 2.0};
  fmi2Integer integers[2] = {1, 1};
  fmi2Boolean booleans[2] = {fmi2False, fmi2False};
  fmi2String strings[2] = {"logAll", nullptr};
  fmi2EventInfo eventInfo{};
  fmi2Status status = fmi2OK;
  fmi2FMUstate state = nullptr;
  fmi2Byte bytes[64] = {};
  size_t size = 0;
};

struct NamedCall {
  const char* name;
  fmi2Status (*call)(fmi2Component, SpareArguments&);
};

// Functions ChainDrive.fmu exports only because importers resolve them: each returns fmi2Error.
constexpr NamedCall kUnsupportedCalls[] = {
    {"fmi2GetDirectionalDerivative",
     [](fmi2Component c, SpareArguments& a) {
       return fmi2GetDirectionalDerivative(c, a.vr, 1, a.vr + 1, 1, a.reals, a.reals + 1);
     }},
    {"fmi2SetRealInputDerivatives",
     [](fmi2Component c, SpareArguments& a) { return fmi2SetRealInputDerivatives(c, a.vr, 1, a.integers, a.reals); }},
    {"fmi2GetRealOutputDerivatives",
     [](fmi2Component c, SpareArguments& a) { return fmi2GetRealOutputDerivatives(c, a.vr, 2, a.integers, a.reals); }},
    {"fmi2CancelStep", [](fmi2Component c, SpareArguments&) { return fmi2CancelStep(c); }},
    {"fmi2GetIntegerStatus",
     [](fmi2Component c, SpareArguments& a) { return fmi2GetIntegerStatus(c, fmi2DoStepStatus, a.integers); }},
    {"fmi2GetStringStatus",
     [](fmi2Component c, SpareArguments& a) { return fmi2GetStringStatus(c, fmi2PendingStatus, a.strings); }},
    {"fmi2EnterEventMode", [](fmi2Component c, SpareArguments&) { return fmi2EnterEventMode(c); }},
    {"fmi2NewDiscreteStates", [](fmi2Component c, SpareArguments& a) { return fmi2NewDiscreteStates(c, &a.eventInfo); }},
    {"fmi2EnterContinuousTimeMode", [](fmi2Component c, SpareArguments&) { return fmi2EnterContinuousTimeMode(c); }},
    {"fmi2CompletedIntegratorStep",
     [](fmi2Component c, SpareArguments& a) {
       return fmi2CompletedIntegratorStep(c, fmi2True, a.booleans, a.booleans + 1);
     }},
    {"fmi2SetTime", [](fmi2Component c, SpareArguments&) { return fmi2SetTime(c, 0.5); }},
    {"fmi2SetContinuousStates", [](fmi2Component c, SpareArguments& a) { return fmi2SetContinuousStates(c, a.reals, 2); }},
    {"fmi2GetDerivatives", [](fmi2Component c, SpareArguments& a) { return fmi2GetDerivatives(c, a.reals, 2); }},
    {"fmi2GetEventIndicators", [](fmi2Component c, SpareArguments& a) { return fmi2GetEventIndicators(c, a.reals, 0); }},
    {"fmi2GetContinuousStates", [](fmi2Component c, SpareArguments& a) { return fmi2GetContinuousStates(c, a.reals, 2); }},
    {"fmi2GetNominalsOfContinuousStates",
     [](fmi2Component c, SpareArguments& a) { return fmi2GetNominalsOfContinuousStates(c, a.reals, 2); }},
};

// Functions of the co-simulation interface, called on a NULL instance: each returns fmi2Error.
constexpr NamedCall kNullInstanceCalls[] = {
    {"fmi2SetDebugLogging",
     [](fmi2Component c, SpareArguments& a) { return fmi2SetDebugLogging(c, fmi2True, 1, a.strings); }},
    {"fmi2SetupExperiment",
     [](fmi2Component c, SpareArguments&) { return fmi2SetupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 1.0); }},
    {"fmi2EnterInitializationMode", [](fmi2Component c, SpareArguments&) { return fmi2EnterInitializationMode(c); }},
    {"fmi2ExitInitializationMode", [](fmi2Component c, SpareArguments&) { return fmi2ExitInitializationMode(c); }},
    {"fmi2Terminate", [](fmi2Component c, SpareArguments&) { return fmi2Terminate(c); }},
    {"fmi2Reset", [](fmi2Component c, SpareArguments&) { return fmi2Reset(c); }},
    {"fmi2GetReal", [](fmi2Component c, SpareArguments& a) { return fmi2GetReal(c, a.vr, 2, a.reals); }},
    {"fmi2SetReal", [](fmi2Component c, SpareArguments& a) { return fmi2SetReal(c, a.vr, 1, a.reals); }},
    {"fmi2GetString", [](fmi2Component c, SpareArguments& a) { return fmi2GetString(c, a.vr, 1, a.strings); }},
    {"fmi2SetBoolean", [](fmi2Component c, SpareArguments& a) { return fmi2SetBoolean(c, a.vr, 1, a.booleans); }},
    {"fmi2DoStep", [](fmi2Component c, SpareArguments&) { return fmi2DoStep(c, 0.0, 1e-5, fmi2True); }},
    {"fmi2GetFMUstate", [](fmi2Component c, SpareArguments& a) { return fmi2GetFMUstate(c, &a.state); }},
    {"fmi2SetFMUstate", [](fmi2Component c, SpareArguments& a) { return fmi2SetFMUstate(c, a.state); }},
    {"fmi2SerializedFMUstateSize",
     [](fmi2Component c, SpareArguments& a) { return fmi2SerializedFMUstateSize(c, a.state, &a.size); }},
    {"fmi2DeSerializeFMUstate",
     [](fmi2Component c, SpareArguments& a) { return fmi2DeSerializeFMUstate(c, a.bytes, sizeof a.bytes, &a.state); }},
    {"fmi2GetStatus", [](fmi2Component c, SpareArguments& a) { return fmi2GetStatus(c, fmi2DoStepStatus, &a.status); }},
    {"fmi2GetRealStatus",
     [](fmi2Component c, SpareArguments& a) { return fmi2GetRealStatus(c, fmi2LastSuccessfulTime, a.reals); }},
    {"fmi2CancelStep", [](fmi2Component c, SpareArguments&) { return fmi2CancelStep(c); }},
};

}  // namespace

void CallSequence::queryStatus() {
  const auto kind = static_cast<fmi2StatusKind>(rng_.below(4));
  const bool nullValue = rng_.chance(0.1);
  switch (rng_.below(3)) {
    case 0: {
      fmi2Status value = fmi2OK;
      const fmi2Status s = invoke("fmi2GetStatus", [&] { return fmi2GetStatus(instance_, kind, nullValue ? nullptr : &value); });
      const int level = static_cast<int>(value);
      if (s == fmi2OK && (level < fmi2OK || level > fmi2Pending)) violation("fmi2GetStatus gave no fmi2Status");
      return;
    }
    case 1: {
      fmi2Real value = 0.0;
      invoke("fmi2GetRealStatus", [&] { return fmi2GetRealStatus(instance_, kind, nullValue ? nullptr : &value); });
      return;
    }
    default: {
      fmi2Boolean value = fmi2False;
      invoke("fmi2GetBooleanStatus", [&] { return fmi2GetBooleanStatus(instance_, kind, nullValue ? nullptr : &value); });
      return;
    }
  }
}

void CallSequence::unsupportedCall() {
  const NamedCall& stub = rng_.pick(kUnsupportedCalls);
  SpareArguments arguments;
  const fmi2Status s = invoke(stub.name, [&] { return stub.call(instance_, arguments); });
  if (s != fmi2Error) violation(std::string(stub.name) + " is not supported and returned " + statusText(s));
}

void CallSequence::nullInstanceCall() {
  const NamedCall& call = rng_.pick(kNullInstanceCalls);
  SpareArguments arguments;
  const fmi2Status s = call.call(nullptr, arguments);
  ++stats_.calls;
  if (s == fmi2Error) ++stats_.statusCounts[fmi2Error];
  else violation(std::string(call.name) + " on a NULL instance returned " + statusText(s));
  if (arguments.state) violation(std::string(call.name) + " on a NULL instance made an FMU state");
}

void CallSequence::debugLogging() {
  constexpr const char* kCategories[] = {"logEvents", "logStatusWarning", "logStatusDiscard", "logStatusError",
                                         "logStatusFatal", "logAll", "noSuchCategory", "%s%n", nullptr};
  std::vector<fmi2String> categories(arrayLength());
  for (fmi2String& c : categories) c = rng_.pick(kCategories);
  const bool nullArray = !categories.empty() && rng_.chance(0.1);
  const fmi2Boolean on = rng_.chance(0.7) ? fmi2True : fmi2False;
  invoke("fmi2SetDebugLogging", [&] {
    return fmi2SetDebugLogging(instance_, on, categories.size(), nullArray ? nullptr : categories.data());
  });
}

}  // namespace chaindrive::fuzz::detail
