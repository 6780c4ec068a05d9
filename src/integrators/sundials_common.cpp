#include "integrators/sundials_common.h"

#include <cstdlib>
#include <stdexcept>

#include <arkode/arkode.h>
#include <cvode/cvode.h>

namespace chaindrive {

SundialsContext::SundialsContext() {
  if (SUNContext_Create(nullptr, &ctx) != 0 || !ctx) throw std::runtime_error("SUNContext_Create failed");
}
SundialsContext::~SundialsContext() {
  if (ctx) SUNContext_Free(&ctx);
}

SerialVector::SerialVector(int n, SUNContext ctx) {
  v = N_VNew_Serial(n, ctx);
  if (!v) throw std::runtime_error("N_VNew_Serial failed");
}
SerialVector::~SerialVector() {
  if (v) N_VDestroy(v);
}

extern "C" int chaindriveRhs(double t, N_Vector y, N_Vector ydot, void* user) noexcept {
  auto* cb = static_cast<CallbackState*>(user);
  return cb->sys->rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
}

extern "C" void chaindriveErrHandler(int code, const char* module, const char* function, char* msg, void* user) noexcept {
  auto* cb = static_cast<CallbackState*>(user);
  try {
    cb->lastSolverMessage = std::string(module ? module : "") + "/" + (function ? function : "") + " (" +
                            std::to_string(code) + "): " + (msg ? msg : "");
  } catch (...) {
  }
}

void fillAbsoluteTolerances(OdeSystem& sys, double rtol, N_Vector atol) {
  double* a = N_VGetArrayPointer(atol);
  sys.toleranceScales(a);
  const int n = sys.size();
  for (int i = 0; i < n; ++i) a[i] *= rtol;
}

void checkFlag(int flag, const char* what) {
  if (flag < 0) throw std::runtime_error(std::string(what) + " failed (flag " + std::to_string(flag) + ")");
}

static_assert(CV_TOO_MUCH_WORK == ARK_TOO_MUCH_WORK && CV_ERR_FAILURE == ARK_ERR_FAILURE &&
                  CV_TOO_CLOSE == ARK_TOO_CLOSE && CV_CONV_FAILURE == ARK_CONV_FAILURE &&
                  CV_LSETUP_FAIL == ARK_LSETUP_FAIL && CV_LSOLVE_FAIL == ARK_LSOLVE_FAIL &&
                  CV_RHSFUNC_FAIL == ARK_RHSFUNC_FAIL && CV_FIRST_RHSFUNC_ERR == ARK_FIRST_RHSFUNC_ERR &&
                  CV_REPTD_RHSFUNC_ERR == ARK_REPTD_RHSFUNC_ERR && CV_UNREC_RHSFUNC_ERR == ARK_UNREC_RHSFUNC_ERR,
              "CVODE and ARKODE number their failure flags alike");

FailureKind sundialsFailureKind(int flag) {
  switch (flag) {
    case CV_RHSFUNC_FAIL:
    case CV_FIRST_RHSFUNC_ERR:
    case CV_REPTD_RHSFUNC_ERR:
    case CV_UNREC_RHSFUNC_ERR: return FailureKind::NonFinite;
    case CV_CONV_FAILURE:
    case CV_LSETUP_FAIL:
    case CV_LSOLVE_FAIL: return FailureKind::NewtonFailure;
    case CV_TOO_MUCH_WORK:
    case CV_ERR_FAILURE:
    case CV_TOO_CLOSE: return FailureKind::StepSizeCollapse;
    default: return FailureKind::Other;
  }
}

Failure sundialsFailure(int flag, char* flagName, const char* fallback, const OdeSystem& sys, const CallbackState& cb) {
  Failure f;
  f.kind = sys.lastError().kind == FailureKind::NonFinite ? FailureKind::NonFinite : sundialsFailureKind(flag);
  f.reason = flagName ? flagName : fallback;
  std::free(flagName);
  if (!sys.lastError().reason.empty()) f.reason += "; " + sys.lastError().reason;
  if (!cb.lastSolverMessage.empty()) f.reason += "; " + cb.lastSolverMessage;
  return f;
}

}  // namespace chaindrive
