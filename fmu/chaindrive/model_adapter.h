// Which model this FMU's protocol serves (Reference-FMUs' config.h). The protocol code (host.h,
// instance.h, fmu_state.h, fmi2_functions.cpp) knows the model only as ModelAdapter, a class
// with these members:
//   ModelAdapter(Host&)                     logs and reads the state and time through the Host
//   bool prepared(); fmi2Status prepare();  the start state at Host::time(), then Host::runStarted()
//   void requirePreparation(); void reset();
//   fmi2Status get<Type>/set<Type>(vr[], n, values[])   for Real, Integer, Boolean, String
//   fmi2Status doStep(cp, tEnd)             fmi2OK, fmi2Error or fmi2Discard, each logged
//   struct Snapshot { ...; std::vector<double> y; }; Snapshot snapshot(); fmi2Status restore(s)
//   kStateMagic[8], kSnapshotFieldBytes, writeFields, readFields, invalidField   (serialization)
// and variables.h gives kGuid and kModelIdentifier. Another FMU compiles the protocol sources
// with its own model_adapter.h and variables.h.
#pragma once

#include "chaindrive_model.h"

namespace chaindrive::fmu {

using ModelAdapter = ChainDriveModel;

}  // namespace chaindrive::fmu
