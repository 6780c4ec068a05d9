// One FMU instance: the FMI 2.0 co-simulation protocol (setup, initialization, the checks and
// state transitions of a communication step, termination, reset, status queries, FMU state
// snapshots) around its model adapter (model_adapter.h), which holds the parameters, inputs and
// values by value reference. No global or static mutable state: everything lives here, one
// allocation per instance.
#pragma once

#include "fmi2Functions.h"
#include "fmu_state.h"
#include "host.h"
#include "model_adapter.h"

namespace chaindrive::fmu {

class Instance : public Host {
 public:
  Instance(const char* instanceName, const fmi2CallbackFunctions* callbacks, const char* resourceLocation,
           bool loggingOn);

  /// The model adapter: parameters, inputs and outputs by value reference.
  ModelAdapter& model() { return model_; }

  fmi2Status setupExperiment(bool toleranceDefined, double tolerance, double startTime, bool stopTimeDefined,
                             double stopTime);
  fmi2Status enterInitializationMode();
  fmi2Status exitInitializationMode();
  fmi2Status doStep(double currentCommunicationPoint, double h);
  fmi2Status terminate();
  fmi2Status reset();

  fmi2Status getRealStatus(fmi2StatusKind kind, fmi2Real* value);
  fmi2Status getStatus(fmi2StatusKind kind, fmi2Status* value);

  Snapshot snapshot() const;
  fmi2Status restore(const Snapshot& s);

 private:
  ModelAdapter model_;
};

}  // namespace chaindrive::fmu
