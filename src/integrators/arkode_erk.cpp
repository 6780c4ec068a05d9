// ARKODE explicit Runge-Kutta (ERKStep): adaptive with an embedded pair, or at a fixed step.
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include <arkode/arkode_erkstep.h>

#include "integrators/integrators.h"
#include "integrators/sundials_common.h"
#include "integrators/time_grid.h"

namespace chaindrive {

namespace {

class ArkodeErk : public Integrator {
 public:
  ArkodeErk(OdeSystem& sys, const AdaptiveOptions& adaptive, const ErkOptions& erk, const FixedStepOptions* fixed)
      : sys_(sys),
        adaptive_(adaptive),
        erk_(erk),
        step_(fixed ? fixed->step : 0.0),
        y_(sys.size(), ctx_.ctx),
        atol_(sys.size(), ctx_.ctx) {
    cb_.sys = &sys;
    if (fixed && !(step_ > 0.0)) throw std::invalid_argument("arkode-erk-fixed needs a positive fixed step");
  }
  ~ArkodeErk() override {
    if (mem_) ERKStepFree(&mem_);
  }
  std::string name() const override { return fixed() ? "arkode-erk-fixed" : "arkode-erk"; }
  void setInitialStep(double h) override { initialStep_ = h; }

  void reset(double t0, const double* y0) override {
    std::memcpy(y_.data(), y0, sizeof(double) * sys_.size());
    grid_ = TimeGrid{t0, step_};
    k_ = 0;
    if (!mem_) {
      mem_ = ERKStepCreate(chaindriveRhs, t0, y_.v, ctx_.ctx);
      if (!mem_) throw std::runtime_error("ERKStepCreate failed");
      check(ERKStepSetUserData(mem_, &cb_), "ERKStepSetUserData");
      check(ERKStepSetErrHandlerFn(mem_, chaindriveErrHandler, &cb_), "ERKStepSetErrHandlerFn");
      if (ERKStepSetTableName(mem_, erk_.table.c_str()) != 0)
        throw std::invalid_argument("unknown ARKODE ERK table '" + erk_.table + "'");
      fillAbsoluteTolerances(sys_, adaptive_.rtol, atol_.v);
      check(ERKStepSVtolerances(mem_, adaptive_.rtol, atol_.v), "ERKStepSVtolerances");
      check(ERKStepSetMaxNumSteps(mem_, adaptive_.maxStepsPerOutput), "ERKStepSetMaxNumSteps");
      if (!fixed() && adaptive_.minStep > 0.0) check(ERKStepSetMinStep(mem_, adaptive_.minStep), "ERKStepSetMinStep");
      if (adaptive_.maxStep > 0.0) check(ERKStepSetMaxStep(mem_, adaptive_.maxStep), "ERKStepSetMaxStep");
      if (fixed()) check(ERKStepSetFixedStep(mem_, step_), "ERKStepSetFixedStep");
    } else {
      check(ERKStepReset(mem_, t0, y_.v), "ERKStepReset");
    }
    if (!fixed()) check(ERKStepSetInitStep(mem_, initialStep_), "ERKStepSetInitStep");
  }

  void advance(double tout, double* y) override {
    if (fixed()) {
      advanceOnGrid(tout);
    } else {
      if (adaptive_.stopAtOutputs) check(ERKStepSetStopTime(mem_, tout), "ERKStepSetStopTime");
      evolve(tout, ARK_NORMAL);
    }
    std::memcpy(y, y_.data(), sizeof(double) * sys_.size());
    Failure why;
    if (!sys_.healthy(tout, y, why)) throw IntegrationError(tout, why);
  }

  double fixedStep() const override { return step_; }

  IntegratorStats stats() const override {
    IntegratorStats s;
    long v = 0, fe = 0;
    if (ERKStepGetNumSteps(mem_, &v) == 0) s.steps = v;
    if (ERKStepGetNumRhsEvals(mem_, &fe) == 0) s.rhsEvaluations = fe;
    if (ERKStepGetNumErrTestFails(mem_, &v) == 0) s.errorTestFailures = v;
    double h = 0;
    if (ERKStepGetLastStep(mem_, &h) == 0) s.lastStep = h;
    return s;
  }

 private:
  // Fixed step: one ARKODE step of exactly h per grid point (one-step mode, no stop time, which
  // would shorten the last step to a rounding-dependent length).
  void advanceOnGrid(double tout) {
    const long long target = grid_.indexOf(tout);
    for (; k_ < target; ++k_) evolve(grid_.time(k_ + 1), ARK_ONE_STEP);
  }

  void evolve(double tout, int mode) {
    double t = 0.0;
    const int flag = ERKStepEvolve(mem_, tout, y_.v, &t, mode);
    if (flag >= 0) return;
    double tcur = t;
    ERKStepGetCurrentTime(mem_, &tcur);
    throw IntegrationError(tcur, sundialsFailure(flag, ERKStepGetReturnFlagName(flag), "ARKODE error", sys_, cb_));
  }

  static void check(int flag, const char* what) { checkFlag(flag, what); }
  bool fixed() const { return step_ > 0.0; }

  OdeSystem& sys_;
  AdaptiveOptions adaptive_;
  ErkOptions erk_;
  double step_;       // fixed step: the step (positive); 0 for the adaptive method
  SundialsContext ctx_;
  SerialVector y_, atol_;
  CallbackState cb_;
  void* mem_ = nullptr;
  TimeGrid grid_;     // fixed step: t0 (the last reset) + k h
  long long k_ = 0;   // fixed step: grid index of the state
  double initialStep_ = 0.0;
};

}  // namespace

std::unique_ptr<Integrator> makeArkodeErk(OdeSystem& sys, const AdaptiveOptions& adaptive, const ErkOptions& erk,
                                          const FixedStepOptions* fixed) {
  return std::make_unique<ArkodeErk>(sys, adaptive, erk, fixed);
}

}  // namespace chaindrive
