#include "instance.h"

#include <algorithm>
#include <cmath>

namespace chaindrive::fmu {

Instance::Instance(const char* instanceName, const fmi2CallbackFunctions* callbacks, const char* resourceLocation,
                   bool loggingOn)
    : Host(instanceName, callbacks, resourceLocation, loggingOn), model_(*this) {}

fmi2Status Instance::setupExperiment(bool /*toleranceDefined*/, double /*tolerance*/, double startTime,
                                     bool stopTimeDefined, double stopTime) {
  if (!std::isfinite(startTime)) {
    log(fmi2Error, "logStatusError", "fmi2SetupExperiment: startTime %g is not finite", startTime);
    return fmi2Error;
  }
  if (stopTimeDefined && !(stopTime >= startTime)) {
    log(fmi2Error, "logStatusError", "fmi2SetupExperiment: stopTime %g is before startTime %g", stopTime, startTime);
    return fmi2Error;
  }
  // the tolerance argument is not used: the integrator's tolerance is the parameter solver.tolerance
  startTime_ = time_ = lastSuccessfulTime_ = startTime;
  stopTimeDefined_ = stopTimeDefined;
  stopTime_ = stopTime;
  model_.requirePreparation();
  return fmi2OK;
}

fmi2Status Instance::enterInitializationMode() {
  state_ = kInitializationMode;
  return fmi2OK;
}

fmi2Status Instance::exitInitializationMode() {
  if (!model_.prepared()) {
    const fmi2Status s = model_.prepare();
    if (s > fmi2Warning) {
      state_ = kError;
      return s;
    }
  }
  state_ = kStepComplete;
  return fmi2OK;
}

fmi2Status Instance::doStep(double cp, double h) {
  // the step: positive, from the FMU's time (within a relative drift), not past the stop time
  if (!std::isfinite(h) || h <= 0.0) {
    log(fmi2Error, "logStatusError", "fmi2DoStep: communicationStepSize %g must be positive and finite", h);
    return fmi2Error;
  }
  const double tol = 1e-9 * std::max(1.0, std::fabs(time_));
  if (!std::isfinite(cp) || std::fabs(cp - time_) > tol) {
    log(fmi2Error, "logStatusError", "fmi2DoStep: currentCommunicationPoint %.17g does not match the FMU time %.17g", cp,
        time_);
    return fmi2Error;
  }
  const double tEnd = cp + h;
  if (stopTimeDefined_ && tEnd > stopTime_ * (1.0 + 1e-12) + 1e-12) {
    log(fmi2Error, "logStatusError", "fmi2DoStep: the step ends at %.17g, after the stop time %.17g", tEnd, stopTime_);
    return fmi2Error;
  }
  // the model's step, then the time it reached or the failed state (kept at the last success)
  const fmi2Status st = model_.doStep(cp, tEnd);
  if (st == fmi2Discard) {
    lastSuccessfulTime_ = time_;
    state_ = kStepFailed;
  } else if (st == fmi2OK) {
    time_ = tEnd;
    lastSuccessfulTime_ = tEnd;
  }
  return st;
}

fmi2Status Instance::terminate() {
  state_ = kTerminated;
  return fmi2OK;
}

fmi2Status Instance::reset() {
  model_.reset();
  time_ = startTime_ = stopTime_ = lastSuccessfulTime_ = 0.0;
  stopTimeDefined_ = false;
  state_ = kInstantiated;
  return fmi2OK;
}

fmi2Status Instance::getRealStatus(fmi2StatusKind kind, fmi2Real* value) {
  if (kind == fmi2LastSuccessfulTime) {
    *value = lastSuccessfulTime_;
    return fmi2OK;
  }
  log(fmi2Error, "logStatusError", "fmi2GetRealStatus: status kind %d is not provided", static_cast<int>(kind));
  return fmi2Discard;
}

fmi2Status Instance::getStatus(fmi2StatusKind kind, fmi2Status* value) {
  if (kind == fmi2DoStepStatus) {
    *value = state_ == kStepFailed ? fmi2Discard : fmi2OK;
    return fmi2OK;
  }
  log(fmi2Error, "logStatusError", "fmi2GetStatus: status kind %d is not provided", static_cast<int>(kind));
  return fmi2Discard;
}

Snapshot Instance::snapshot() const {
  Snapshot s;
  s.state = state_;
  s.time = time_;
  s.lastSuccessfulTime = lastSuccessfulTime_;
  s.model = model_.snapshot();
  return s;
}

fmi2Status Instance::restore(const Snapshot& s) {
  if (model_.restore(s.model) != fmi2OK) return fmi2Error;
  // a state taken after a failed step or in the error state is restored ready for the next step
  state_ = s.state == kStepFailed || s.state == kError ? kStepComplete : s.state;
  time_ = s.time;
  lastSuccessfulTime_ = s.lastSuccessfulTime;
  log(fmi2OK, "logEvents", "state restored at t = %.9g s", time_);
  return fmi2OK;
}

}  // namespace chaindrive::fmu
