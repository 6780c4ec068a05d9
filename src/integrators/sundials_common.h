// RAII ownership of the SUNDIALS objects of one integrator instance (one SUNContext each, as
// SUNDIALS is thread-safe only that way) and the C callbacks that forward to an OdeSystem.
#pragma once

#include <string>
#include <vector>

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>

#include "integrators/ode_system.h"

namespace chaindrive {

struct SundialsContext {
  SUNContext ctx = nullptr;
  SundialsContext();
  ~SundialsContext();
  SundialsContext(const SundialsContext&) = delete;
  SundialsContext& operator=(const SundialsContext&) = delete;
};

struct SerialVector {
  N_Vector v = nullptr;
  SerialVector(int n, SUNContext ctx);
  ~SerialVector();
  SerialVector(const SerialVector&) = delete;
  SerialVector& operator=(const SerialVector&) = delete;
  double* data() { return N_VGetArrayPointer(v); }
};

/// State shared by the SUNDIALS callbacks of one integrator.
struct CallbackState {
  OdeSystem* sys = nullptr;
  std::string lastSolverMessage;  // from the error handler (never printed)
};

extern "C" {
int chaindriveRhs(double t, N_Vector y, N_Vector ydot, void* user) noexcept;
void chaindriveErrHandler(int code, const char* module, const char* function, char* msg, void* user) noexcept;
}

/// Absolute tolerances rtol * scale_i into an N_Vector.
void fillAbsoluteTolerances(OdeSystem& sys, double rtol, N_Vector atol);

/// Throws std::runtime_error naming the setup call `what` when its flag reports an error.
void checkFlag(int flag, const char* what);

/// The kind of a failed CVODE or ARKODE step from its return flag (the two solvers share the
/// numbers of these flags).
FailureKind sundialsFailureKind(int flag);

/// The failure of a step that returned `flag` (named `flagName` by the solver, or `fallback`):
/// the system's own diagnosis (a non-finite derivative) before the flag's kind; the reason
/// names the flag, the system's last error and the solver's last message.
Failure sundialsFailure(int flag, char* flagName, const char* fallback, const OdeSystem& sys, const CallbackState& cb);

}  // namespace chaindrive
