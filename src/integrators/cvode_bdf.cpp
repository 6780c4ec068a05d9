// CVODE BDF with a Newton solver on either a sparse direct solver (KLU, exact pattern and
// element Jacobian) or a banded solver (CVODE's difference-quotient band Jacobian, which drops
// the couplings outside the band: an approximate Newton matrix).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include <cvode/cvode.h>
#include <sunlinsol/sunlinsol_band.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_band.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "integrators/integrators.h"
#include "integrators/sundials_common.h"

namespace chaindrive {

namespace {

extern "C" int cvodeJacobian(double t, N_Vector y, N_Vector /*fy*/, SUNMatrix J, void* user, N_Vector, N_Vector,
                             N_Vector) noexcept {
  auto* cb = static_cast<CallbackState*>(user);
  OdeSystem& sys = *cb->sys;
  const int64_t nnz = sys.jacobianNonzeros();
  std::memcpy(SUNSparseMatrix_IndexPointers(J), sys.jacobianColumnPointers(), sizeof(sunindextype) * (sys.size() + 1));
  std::memcpy(SUNSparseMatrix_IndexValues(J), sys.jacobianRowIndices(), sizeof(sunindextype) * nnz);
  return sys.jacobian(t, N_VGetArrayPointer(y), SUNSparseMatrix_Data(J));
}

class CvodeBdf : public Integrator {
 public:
  CvodeBdf(OdeSystem& sys, const AdaptiveOptions& adaptive, const BdfOptions& bdf, bool klu)
      : sys_(sys), adaptive_(adaptive), bdf_(bdf), klu_(klu), y_(sys.size(), ctx_.ctx), atol_(sys.size(), ctx_.ctx) {
    cb_.sys = &sys;
    static_assert(sizeof(sunindextype) == sizeof(int64_t), "SUNDIALS index type must be 64 bit");
    mem_ = CVodeCreate(CV_BDF, ctx_.ctx);
    if (!mem_) throw std::runtime_error("CVodeCreate failed");
  }
  ~CvodeBdf() override {
    if (mem_) CVodeFree(&mem_);
    if (ls_) SUNLinSolFree(ls_);
    if (A_) SUNMatDestroy(A_);
  }

  std::string name() const override { return klu_ ? "cvode-bdf-klu" : "cvode-bdf-band"; }
  void setInitialStep(double h) override { initialStep_ = h; }

  void reset(double t0, const double* y0) override {
    std::memcpy(y_.data(), y0, sizeof(double) * sys_.size());
    t_ = t0;
    windowSteps_ = windowFails_ = 0;  // CVodeReInit restarts the counters
    if (!initialized_) {
      check(CVodeInit(mem_, chaindriveRhs, t0, y_.v), "CVodeInit");
      check(CVodeSetUserData(mem_, &cb_), "CVodeSetUserData");
      check(CVodeSetErrHandlerFn(mem_, chaindriveErrHandler, &cb_), "CVodeSetErrHandlerFn");
      fillAbsoluteTolerances(sys_, adaptive_.rtol, atol_.v);
      check(CVodeSVtolerances(mem_, adaptive_.rtol, atol_.v), "CVodeSVtolerances");
      if (klu_) {
        if (!sys_.hasJacobian()) throw std::invalid_argument("cvode-bdf-klu needs a system with a sparse Jacobian");
        A_ = SUNSparseMatrix(sys_.size(), sys_.size(), sys_.jacobianNonzeros(), CSC_MAT, ctx_.ctx);
        ls_ = SUNLinSol_KLU(y_.v, A_, ctx_.ctx);
        if (!A_ || !ls_) throw std::runtime_error("cannot create the KLU solver");
        check(CVodeSetLinearSolver(mem_, ls_, A_), "CVodeSetLinearSolver");
        check(CVodeSetJacFn(mem_, cvodeJacobian), "CVodeSetJacFn");
      } else {
        const int bw = sys_.halfBandwidth();
        if (bw < 0)
          throw std::invalid_argument("cvode-bdf-band needs a system whose Jacobian is banded; the link model's is not "
                                      "(its state is laid out component by component): use cvode-bdf-klu");
        A_ = SUNBandMatrix(sys_.size(), bw, bw, ctx_.ctx);
        ls_ = SUNLinSol_Band(y_.v, A_, ctx_.ctx);
        if (!A_ || !ls_) throw std::runtime_error("cannot create the band solver");
        check(CVodeSetLinearSolver(mem_, ls_, A_), "CVodeSetLinearSolver");
      }
      check(CVodeSetMaxNumSteps(mem_, adaptive_.maxStepsPerOutput), "CVodeSetMaxNumSteps");
      if (adaptive_.minStep > 0.0) check(CVodeSetMinStep(mem_, adaptive_.minStep), "CVodeSetMinStep");
      if (adaptive_.maxStep > 0.0) check(CVodeSetMaxStep(mem_, adaptive_.maxStep), "CVodeSetMaxStep");
      check(CVodeSetStabLimDet(mem_, SUNTRUE), "CVodeSetStabLimDet");
      initialized_ = true;
    } else {
      check(CVodeReInit(mem_, t0, y_.v), "CVodeReInit");
    }
    check(CVodeSetInitStep(mem_, initialStep_), "CVodeSetInitStep");
  }

  void advance(double tout, double* y) override {
    if (adaptive_.stopAtOutputs) check(CVodeSetStopTime(mem_, tout), "CVodeSetStopTime");
    double t = t_;
    const int flag = CVode(mem_, tout, y_.v, &t, CV_NORMAL);
    if (flag < 0) {
      double tcur = t;
      CVodeGetCurrentTime(mem_, &tcur);
      throw IntegrationError(tcur, sundialsFailure(flag, CVodeGetReturnFlagName(flag), "CVODE error", sys_, cb_));
    }
    t_ = tout;
    std::memcpy(y, y_.data(), sizeof(double) * sys_.size());
    Failure why;
    if (!sys_.healthy(tout, y, why)) throw IntegrationError(tout, why);
    checkNewtonFailures(tout);
  }

  IntegratorStats stats() const override {
    IntegratorStats s;
    long v = 0;
    if (CVodeGetNumSteps(mem_, &v) == 0) s.steps = v;
    if (CVodeGetNumRhsEvals(mem_, &v) == 0) s.rhsEvaluations = v;
    if (CVodeGetNumJacEvals(mem_, &v) == 0) s.jacobianEvaluations = v;
    long fdRhs = 0;
    if (CVodeGetNumLinRhsEvals(mem_, &fdRhs) == 0) s.rhsEvaluations += fdRhs;
    if (CVodeGetNumNonlinSolvIters(mem_, &v) == 0) s.nonlinearIterations = v;
    if (CVodeGetNumErrTestFails(mem_, &v) == 0) s.errorTestFailures = v;
    if (CVodeGetNumNonlinSolvConvFails(mem_, &v) == 0) s.convergenceFailures = v;
    double h = 0;
    if (CVodeGetLastStep(mem_, &h) == 0) s.lastStep = h;
    return s;
  }

 private:
  // Newton iterations that keep failing (a poor Newton matrix, as the band solver's) make CVODE
  // cut the step again and again without an error: detected as the ratio of convergence failures
  // to steps over windows of at least 200 steps.
  void checkNewtonFailures(double t) {
    long steps = 0, fails = 0;
    if (CVodeGetNumSteps(mem_, &steps) != 0 || CVodeGetNumNonlinSolvConvFails(mem_, &fails) != 0) return;
    const long ds = steps - windowSteps_, df = fails - windowFails_;
    if (ds < 200) return;
    if (static_cast<double>(df) > bdf_.maxConvergenceFailureRatio * static_cast<double>(ds)) {
      double h = 0.0;
      CVodeGetLastStep(mem_, &h);
      char buf[200];
      std::snprintf(buf, sizeof buf,
                    "Newton failure (CV_CONV_FAILURE repeatedly): %ld convergence failures in %ld steps, step size "
                    "%.3g s",
                    df, ds, h);
      throw IntegrationError(t, FailureKind::NewtonFailure, buf);
    }
    windowSteps_ = steps;
    windowFails_ = fails;
  }
  static void check(int flag, const char* what) { checkFlag(flag, what); }
  OdeSystem& sys_;
  AdaptiveOptions adaptive_;
  BdfOptions bdf_;
  bool klu_;
  SundialsContext ctx_;
  SerialVector y_, atol_;
  CallbackState cb_;
  void* mem_ = nullptr;
  SUNMatrix A_ = nullptr;
  SUNLinearSolver ls_ = nullptr;
  bool initialized_ = false;
  double t_ = 0.0;
  double initialStep_ = 0.0;
  long windowSteps_ = 0, windowFails_ = 0;
};

}  // namespace

std::unique_ptr<Integrator> makeCvodeBdf(OdeSystem& sys, const AdaptiveOptions& adaptive, const BdfOptions& bdf,
                                         bool klu) {
  return std::make_unique<CvodeBdf>(sys, adaptive, bdf, klu);
}

}  // namespace chaindrive
