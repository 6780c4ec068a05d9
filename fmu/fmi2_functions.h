// The FMI 2.0 C interface of an FMU: pure protocol, written once for every model adapter. Every
// entry checks the instance and the allowed states, catches every exception (none crosses the C
// boundary) and forwards to Instance and its model adapter. Unsupported functions exist
// (importers resolve all of them) and return fmi2Error.
//
// The C names cannot be templates: this header defines them for chaindrive::fmu::ExportedAdapter,
// the model adapter that the including file has named (fmu/<adapter>/<adapter>_adapter.h). One
// file of each FMU includes it (fmu/<adapter>/<adapter>_fmu.cpp), and only that one.
#pragma once

#include <cstring>
#include <memory>
#include <new>
#include <string>

#include "adapter_contract.h"
#include "fmi2Functions.h"
#include "fmu_state.h"
#include "instance.h"

namespace {

namespace fmu = chaindrive::fmu;
using fmu::ExportedAdapter;
using Instance = fmu::Instance<ExportedAdapter>;
using Snapshot = fmu::FmuState<ExportedAdapter>;

// allowed states per function (FMI 2.0 co-simulation state machine)
constexpr unsigned kAny = fmu::kAllStates;
constexpr unsigned kMaskSetDebugLogging = kAny;
constexpr unsigned kMaskSetupExperiment = fmu::kInstantiated;
constexpr unsigned kMaskEnterInit = fmu::kInstantiated;
constexpr unsigned kMaskExitInit = fmu::kInitializationMode;
constexpr unsigned kMaskTerminate = fmu::kStepComplete | fmu::kStepFailed;
constexpr unsigned kMaskReset = kAny;
constexpr unsigned kMaskGet = fmu::kInitializationMode | fmu::kStepComplete | fmu::kStepFailed | fmu::kTerminated |
                              fmu::kError;
constexpr unsigned kMaskSetReal = fmu::kInstantiated | fmu::kInitializationMode | fmu::kStepComplete;
constexpr unsigned kMaskSetOther = fmu::kInstantiated | fmu::kInitializationMode | fmu::kStepComplete;
constexpr unsigned kMaskState = kAny;
constexpr unsigned kMaskDoStep = fmu::kStepComplete;
constexpr unsigned kMaskStatus = fmu::kStepComplete | fmu::kStepFailed | fmu::kTerminated;

Instance* cast(fmi2Component c) { return static_cast<Instance*>(c); }

// Runs body() for a valid instance in an allowed state; converts exceptions to fmi2Error.
template <class F>
fmi2Status guarded(fmi2Component c, const char* fn, unsigned mask, F&& body) {
  Instance* in = cast(c);
  if (!in) return fmi2Error;
  try {
    if (!in->allowed(fn, mask)) return fmi2Error;
    return body(*in);
  } catch (const std::bad_alloc&) {
    in->log(fmi2Error, "logStatusError", "%s: out of memory", fn);
  } catch (const std::exception& e) {
    in->log(fmi2Error, "logStatusError", "%s: %s", fn, e.what());
  } catch (...) {
    in->log(fmi2Error, "logStatusError", "%s: unknown error", fn);
  }
  in->enterErrorState();
  return fmi2Error;
}

bool nullArg(Instance& in, const char* fn, const char* arg, const void* p, size_t n) {
  if (n > 0 && !p) {
    in.log(fmi2Error, "logStatusError", "%s: argument %s is NULL", fn, arg);
    return true;
  }
  return false;
}

fmi2Status unsupported(fmi2Component c, const char* fn) {
  Instance* in = cast(c);
  if (in)
    in->log(fmi2Error, "logStatusError", "%s is not supported by %s (co-simulation only)", fn,
            in->model().modelIdentifier());
  return fmi2Error;
}

}  // namespace

extern "C" {

FMI2_Export const char* fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
FMI2_Export const char* fmi2GetVersion(void) { return fmi2Version; }

FMI2_Export fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t n,
                                           const fmi2String categories[]) {
  return guarded(c, "fmi2SetDebugLogging", kMaskSetDebugLogging, [&](Instance& in) {
    if (nullArg(in, "fmi2SetDebugLogging", "categories", categories, n)) return fmi2Error;
    return in.setDebugLogging(loggingOn != fmi2False, n, categories);
  });
}

FMI2_Export fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                                          fmi2String fmuResourceLocation, const fmi2CallbackFunctions* functions,
                                          fmi2Boolean /*visible*/, fmi2Boolean loggingOn) {
  if (!functions || !functions->logger) return nullptr;  // nowhere to report anything
  auto fail = [&](const char* msg) -> fmi2Component {
    functions->logger(functions->componentEnvironment, instanceName ? instanceName : "", fmi2Error,
                      "logStatusError", "fmi2Instantiate: %s", msg);
    return nullptr;
  };
  try {
    if (!instanceName || !*instanceName) return fail("instanceName must be a non-empty string");
    if (fmuType != fmi2CoSimulation) return fail("this FMU supports co-simulation only (fmuType must be fmi2CoSimulation)");
    // the model adapter checks the GUID against its model description (ChainDrive: the interface
    // in its resources, checked against the drive there) and logs what does not fit
    auto instance = std::make_unique<Instance>(instanceName, functions, fmuResourceLocation, loggingOn != fmi2False);
    if (!instance->model().instantiated(fmuGUID)) return nullptr;
    return instance.release();
  } catch (const std::exception& e) {
    return fail(e.what());
  } catch (...) {
    return fail("unknown error");
  }
}

FMI2_Export void fmi2FreeInstance(fmi2Component c) {
  try {
    delete cast(c);
  } catch (...) {
  }
}

FMI2_Export fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean /*toleranceDefined*/, fmi2Real /*tolerance*/,
                                           fmi2Real startTime, fmi2Boolean stopTimeDefined, fmi2Real stopTime) {
  return guarded(c, "fmi2SetupExperiment", kMaskSetupExperiment, [&](Instance& in) {
    return in.setupExperiment(startTime, stopTimeDefined != fmi2False, stopTime);
  });
}

FMI2_Export fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
  return guarded(c, "fmi2EnterInitializationMode", kMaskEnterInit, [](Instance& in) { return in.enterInitializationMode(); });
}

FMI2_Export fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
  return guarded(c, "fmi2ExitInitializationMode", kMaskExitInit, [](Instance& in) { return in.exitInitializationMode(); });
}

FMI2_Export fmi2Status fmi2Terminate(fmi2Component c) {
  return guarded(c, "fmi2Terminate", kMaskTerminate, [](Instance& in) { return in.terminate(); });
}

FMI2_Export fmi2Status fmi2Reset(fmi2Component c) {
  return guarded(c, "fmi2Reset", kMaskReset, [](Instance& in) { return in.reset(); });
}

#define CHAINDRIVE_GETTER(Fn, T, method)                                                          \
  FMI2_Export fmi2Status Fn(fmi2Component c, const fmi2ValueReference vr[], size_t n, T value[]) { \
    return guarded(c, #Fn, kMaskGet, [&](Instance& in) {                                           \
      if (nullArg(in, #Fn, "vr", vr, n) || nullArg(in, #Fn, "value", value, n)) return fmi2Error;  \
      return in.model().method(vr, n, value);                                                      \
    });                                                                                            \
  }
#define CHAINDRIVE_SETTER(Fn, T, method, mask)                                                           \
  FMI2_Export fmi2Status Fn(fmi2Component c, const fmi2ValueReference vr[], size_t n, const T value[]) { \
    return guarded(c, #Fn, mask, [&](Instance& in) {                                                     \
      if (nullArg(in, #Fn, "vr", vr, n) || nullArg(in, #Fn, "value", value, n)) return fmi2Error;        \
      return in.model().method(vr, n, value);                                                            \
    });                                                                                                  \
  }

CHAINDRIVE_GETTER(fmi2GetReal, fmi2Real, getReal)
CHAINDRIVE_GETTER(fmi2GetInteger, fmi2Integer, getInteger)
CHAINDRIVE_GETTER(fmi2GetBoolean, fmi2Boolean, getBoolean)
CHAINDRIVE_GETTER(fmi2GetString, fmi2String, getString)
CHAINDRIVE_SETTER(fmi2SetReal, fmi2Real, setReal, kMaskSetReal)
CHAINDRIVE_SETTER(fmi2SetInteger, fmi2Integer, setInteger, kMaskSetOther)
CHAINDRIVE_SETTER(fmi2SetBoolean, fmi2Boolean, setBoolean, kMaskSetOther)
CHAINDRIVE_SETTER(fmi2SetString, fmi2String, setString, kMaskSetOther)

// ---- FMU state ----
FMI2_Export fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate* state) {
  return guarded(c, "fmi2GetFMUstate", kMaskState, [&](Instance& in) {
    if (nullArg(in, "fmi2GetFMUstate", "FMUstate", state, 1)) return fmi2Error;
    if (*state) *static_cast<Snapshot*>(*state) = in.snapshot();
    else *state = new Snapshot(in.snapshot());
    return fmi2OK;
  });
}

FMI2_Export fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate state) {
  return guarded(c, "fmi2SetFMUstate", kMaskState, [&](Instance& in) {
    if (nullArg(in, "fmi2SetFMUstate", "FMUstate", state, 1)) return fmi2Error;
    return in.restore(*static_cast<const Snapshot*>(state));
  });
}

FMI2_Export fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate* state) {
  return guarded(c, "fmi2FreeFMUstate", kMaskState, [&](Instance&) {
    if (state && *state) {
      delete static_cast<Snapshot*>(*state);
      *state = nullptr;
    }
    return fmi2OK;
  });
}

FMI2_Export fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate state, size_t* size) {
  return guarded(c, "fmi2SerializedFMUstateSize", kMaskState, [&](Instance& in) {
    if (nullArg(in, "fmi2SerializedFMUstateSize", "FMUstate", state, 1) ||
        nullArg(in, "fmi2SerializedFMUstateSize", "size", size, 1))
      return fmi2Error;
    *size = fmu::serialize(*static_cast<const Snapshot*>(state)).size();
    return fmi2OK;
  });
}

FMI2_Export fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate state, fmi2Byte bytes[], size_t size) {
  return guarded(c, "fmi2SerializeFMUstate", kMaskState, [&](Instance& in) {
    if (nullArg(in, "fmi2SerializeFMUstate", "FMUstate", state, 1) || nullArg(in, "fmi2SerializeFMUstate", "bytes", bytes, 1))
      return fmi2Error;
    const std::vector<char> b = fmu::serialize(*static_cast<const Snapshot*>(state));
    if (b.size() != size) {
      in.log(fmi2Error, "logStatusError", "fmi2SerializeFMUstate: buffer of %zu bytes, the state needs %zu", size, b.size());
      return fmi2Error;
    }
    std::memcpy(bytes, b.data(), size);
    return fmi2OK;
  });
}

FMI2_Export fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte bytes[], size_t size,
                                               fmi2FMUstate* state) {
  return guarded(c, "fmi2DeSerializeFMUstate", kMaskState, [&](Instance& in) {
    if (nullArg(in, "fmi2DeSerializeFMUstate", "FMUstate", state, 1)) return fmi2Error;
    Snapshot s;
    const fmi2Status st = fmu::deserialize(in, bytes, size, s);
    if (st != fmi2OK) return st;
    if (*state) *static_cast<Snapshot*>(*state) = std::move(s);
    else *state = new Snapshot(std::move(s));
    return fmi2OK;
  });
}

FMI2_Export fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference[], size_t,
                                                    const fmi2ValueReference[], size_t, const fmi2Real[], fmi2Real[]) {
  return unsupported(c, "fmi2GetDirectionalDerivative");
}

// ---- co-simulation ----
FMI2_Export fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference[], size_t,
                                                   const fmi2Integer[], const fmi2Real[]) {
  return unsupported(c, "fmi2SetRealInputDerivatives");
}

FMI2_Export fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference[], size_t,
                                                    const fmi2Integer[], fmi2Real[]) {
  return unsupported(c, "fmi2GetRealOutputDerivatives");
}

FMI2_Export fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint, fmi2Real communicationStepSize,
                                  fmi2Boolean /*noSetFMUStatePriorToCurrentPoint*/) {
  return guarded(c, "fmi2DoStep", kMaskDoStep,
                 [&](Instance& in) { return in.doStep(currentCommunicationPoint, communicationStepSize); });
}

FMI2_Export fmi2Status fmi2CancelStep(fmi2Component c) { return unsupported(c, "fmi2CancelStep"); }

FMI2_Export fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status* value) {
  return guarded(c, "fmi2GetStatus", kMaskStatus, [&](Instance& in) {
    if (nullArg(in, "fmi2GetStatus", "value", value, 1)) return fmi2Error;
    return in.getStatus(s, value);
  });
}

FMI2_Export fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real* value) {
  return guarded(c, "fmi2GetRealStatus", kMaskStatus, [&](Instance& in) {
    if (nullArg(in, "fmi2GetRealStatus", "value", value, 1)) return fmi2Error;
    return in.getRealStatus(s, value);
  });
}

FMI2_Export fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind, fmi2Integer*) {
  return unsupported(c, "fmi2GetIntegerStatus");
}

FMI2_Export fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean* value) {
  return guarded(c, "fmi2GetBooleanStatus", kMaskStatus, [&](Instance& in) {
    if (nullArg(in, "fmi2GetBooleanStatus", "value", value, 1)) return fmi2Error;
    if (s == fmi2Terminated) {
      *value = fmi2False;  // the slave never asks to terminate
      return fmi2OK;
    }
    in.log(fmi2Error, "logStatusError", "fmi2GetBooleanStatus: status kind %d is not provided", static_cast<int>(s));
    return fmi2Discard;
  });
}

FMI2_Export fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind, fmi2String*) {
  return unsupported(c, "fmi2GetStringStatus");
}

// ---- model exchange: not supported, but importers resolve these names ----
FMI2_Export fmi2Status fmi2EnterEventMode(fmi2Component c) { return unsupported(c, "fmi2EnterEventMode"); }
FMI2_Export fmi2Status fmi2NewDiscreteStates(fmi2Component c, fmi2EventInfo*) {
  return unsupported(c, "fmi2NewDiscreteStates");
}
FMI2_Export fmi2Status fmi2EnterContinuousTimeMode(fmi2Component c) {
  return unsupported(c, "fmi2EnterContinuousTimeMode");
}
FMI2_Export fmi2Status fmi2CompletedIntegratorStep(fmi2Component c, fmi2Boolean, fmi2Boolean*, fmi2Boolean*) {
  return unsupported(c, "fmi2CompletedIntegratorStep");
}
FMI2_Export fmi2Status fmi2SetTime(fmi2Component c, fmi2Real) { return unsupported(c, "fmi2SetTime"); }
FMI2_Export fmi2Status fmi2SetContinuousStates(fmi2Component c, const fmi2Real[], size_t) {
  return unsupported(c, "fmi2SetContinuousStates");
}
FMI2_Export fmi2Status fmi2GetDerivatives(fmi2Component c, fmi2Real[], size_t) {
  return unsupported(c, "fmi2GetDerivatives");
}
FMI2_Export fmi2Status fmi2GetEventIndicators(fmi2Component c, fmi2Real[], size_t) {
  return unsupported(c, "fmi2GetEventIndicators");
}
FMI2_Export fmi2Status fmi2GetContinuousStates(fmi2Component c, fmi2Real[], size_t) {
  return unsupported(c, "fmi2GetContinuousStates");
}
FMI2_Export fmi2Status fmi2GetNominalsOfContinuousStates(fmi2Component c, fmi2Real[], size_t) {
  return unsupported(c, "fmi2GetNominalsOfContinuousStates");
}

}  // extern "C"
