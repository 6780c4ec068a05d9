// ARKODE explicit Runge-Kutta (ERKStep): adaptive with an embedded pair, or at a fixed step.
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include <arkode/arkode_erkstep.h>

#include "integrators.h"
#include "sundials_common.h"

namespace chaindrive {

namespace {

class ArkodeErk : public Integrator {
 public:
  ArkodeErk(OdeSystem& sys, const IntegratorSettings& s, bool fixed)
      : sys_(sys), settings_(s), fixed_(fixed), y_(sys.size(), ctx_.ctx), atol_(sys.size(), ctx_.ctx) {
    cb_.sys = &sys;
  }
  ~ArkodeErk() override {
    if (mem_) ERKStepFree(&mem_);
  }
  std::string name() const override { return fixed_ ? "arkode-erk-fixed" : "arkode-erk"; }
  void setInitialStep(double h) override { initialStep_ = h; }

  void reset(double t0, const double* y0) override {
    std::memcpy(y_.data(), y0, sizeof(double) * sys_.size());
    t_ = t0;
    if (!mem_) {
      mem_ = ERKStepCreate(chaindriveRhs, t0, y_.v, ctx_.ctx);
      if (!mem_) throw std::runtime_error("ERKStepCreate failed");
      check(ERKStepSetUserData(mem_, &cb_), "ERKStepSetUserData");
      check(ERKStepSetErrHandlerFn(mem_, chaindriveErrHandler, &cb_), "ERKStepSetErrHandlerFn");
      if (ERKStepSetTableName(mem_, settings_.erkTable.c_str()) != 0)
        throw std::invalid_argument("unknown ARKODE ERK table '" + settings_.erkTable + "'");
      fillAbsoluteTolerances(sys_, settings_.rtol, atol_.v);
      check(ERKStepSVtolerances(mem_, settings_.rtol, atol_.v), "ERKStepSVtolerances");
      check(ERKStepSetMaxNumSteps(mem_, settings_.maxStepsPerOutput), "ERKStepSetMaxNumSteps");
      if (!fixed_ && settings_.minStep > 0.0) check(ERKStepSetMinStep(mem_, settings_.minStep), "ERKStepSetMinStep");
      if (settings_.maxStep > 0.0) check(ERKStepSetMaxStep(mem_, settings_.maxStep), "ERKStepSetMaxStep");
      if (fixed_) check(ERKStepSetFixedStep(mem_, settings_.fixedStep), "ERKStepSetFixedStep");
    } else {
      check(ERKStepReset(mem_, t0, y_.v), "ERKStepReset");
    }
    if (!fixed_) check(ERKStepSetInitStep(mem_, initialStep_), "ERKStepSetInitStep");
  }

  void advance(double tout, double* y) override {
    if (settings_.stopAtOutputs || fixed_) check(ERKStepSetStopTime(mem_, tout), "ERKStepSetStopTime");
    double t = t_;
    const int flag = ERKStepEvolve(mem_, tout, y_.v, &t, ARK_NORMAL);
    if (flag < 0) {
      double tcur = t;
      ERKStepGetCurrentTime(mem_, &tcur);
      char* fname = ERKStepGetReturnFlagName(flag);
      std::string reason = fname ? fname : "ARKODE error";
      std::free(fname);
      if (!sys_.lastError().empty()) reason += "; " + sys_.lastError();
      if (!cb_.lastSolverMessage.empty()) reason += "; " + cb_.lastSolverMessage;
      throw IntegrationError(tcur, reason);
    }
    t_ = tout;
    std::memcpy(y, y_.data(), sizeof(double) * sys_.size());
    std::string why;
    if (!sys_.healthy(tout, y, why)) throw IntegrationError(tout, why);
  }

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
  void check(int flag, const char* what) {
    if (flag < 0) throw std::runtime_error(std::string(what) + " failed (flag " + std::to_string(flag) + ")");
  }
  OdeSystem& sys_;
  IntegratorSettings settings_;
  bool fixed_;
  SundialsContext ctx_;
  SerialVector y_, atol_;
  CallbackState cb_;
  void* mem_ = nullptr;
  double t_ = 0.0;
  double initialStep_ = 0.0;
};

}  // namespace

std::unique_ptr<Integrator> makeArkodeErk(OdeSystem& sys, const IntegratorSettings& s, bool fixedStep) {
  return std::make_unique<ArkodeErk>(sys, s, fixedStep);
}

}  // namespace chaindrive
