// One FMU instance: the FMI 2.0 co-simulation protocol (setup, initialization, the communication
// step, reset, FMU state snapshots) around its model adapter, which holds the parameters, inputs
// and values by value reference. The protocol state is Host's, changed through its transitions;
// the model's is the adapter's. No global or static mutable state: everything lives here, one
// allocation per instance.
#pragma once

#include "adapter_contract.h"
#include "fmi2Functions.h"
#include "fmu_state.h"
#include "host.h"

namespace chaindrive::fmu {

template <CHAINDRIVE_MODEL_ADAPTER Model>
class Instance : public Host {
 public:
  Instance(const char* instanceName, const fmi2CallbackFunctions* callbacks, const char* resourceLocation,
           bool loggingOn)
      : Host(instanceName, callbacks, resourceLocation, loggingOn), model_(*this) {}

  /// The model adapter: parameters, inputs and outputs by value reference.
  Model& model() { return model_; }

  // (the protocol's functions that concern no model)
  using Host::enterErrorState;
  using Host::enterInitializationMode;
  using Host::getRealStatus;
  using Host::getStatus;
  using Host::terminate;

  fmi2Status setupExperiment(double startTime, bool stopTimeDefined, double stopTime) {
    // (fmi2SetupExperiment's tolerance is not used: the integrator's is the parameter solver.tolerance)
    if (!setExperiment(startTime, stopTimeDefined, stopTime)) return fmi2Error;
    model_.requirePreparation();
    return fmi2OK;
  }

  fmi2Status exitInitializationMode() {
    if (!model_.prepared()) {
      const fmi2Status s = model_.prepare();
      if (s > fmi2Warning) {
        enterErrorState();
        return s;
      }
    }
    startStepping();
    return fmi2OK;
  }

  /// The model's step, then the time it reached or the failed state (the model kept at its last
  /// success).
  fmi2Status doStep(double cp, double h) {
    double tEnd = 0.0;
    if (!stepAcceptable(cp, h, tEnd)) return fmi2Error;
    const fmi2Status st = model_.doStep(cp, tEnd);
    if (st == fmi2Discard) stepDiscarded();
    else if (st == fmi2OK) stepCompleted(tEnd);
    return st;
  }

  fmi2Status reset() {
    model_.reset();
    resetProtocol();
    return fmi2OK;
  }

  FmuState<Model> snapshot() const { return {protocolSnapshot(), model_.snapshot()}; }

  fmi2Status restore(const FmuState<Model>& s) {
    if (model_.restore(s.model) != fmi2OK) return fmi2Error;
    restoreProtocol(s.protocol);
    return fmi2OK;
  }

 private:
  Model model_;
};

}  // namespace chaindrive::fmu
