#include "integrators/sundials_common.h"

#include <stdexcept>

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

}  // namespace chaindrive
