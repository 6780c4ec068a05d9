// Why a run stopped: the kind of failure, set where the failure is detected and carried by the
// exception, so that callers (the study's failure map, the FMU's log, the CLI summary) branch
// on the kind and never on the wording of a message.
#pragma once

#include <stdexcept>
#include <string>

namespace chaindrive {

enum class FailureKind {
  RunawayEvents,        // event driven: more events per second than the limit
  Tunnelling,           // a contact deeper than the tunnelling limit
  BlowUp,               // a joint stretched beyond the blow-up limit
  NonFinite,            // a state or derivative that is not finite
  LcpRayTermination,    // Lemke ended on a secondary ray
  LcpNumericalFailure,  // Lemke's pivots lost their accuracy
  LcpIterationLimit,    // Lemke reached its pivot cap
  NewtonFailure,        // the corrector or linear solver of an implicit method failed
  StepSizeCollapse,     // error-test failures or too many steps: the step size went to zero
  Other,
};

/// The keyword of a kind, as written to summaries and results files ("blow-up", ...).
inline const char* failureKeyword(FailureKind kind) {
  switch (kind) {
    case FailureKind::RunawayEvents: return "runaway-events";
    case FailureKind::Tunnelling: return "tunnelling";
    case FailureKind::BlowUp: return "blow-up";
    case FailureKind::NonFinite: return "non-finite";
    case FailureKind::LcpRayTermination: return "lcp-ray-termination";
    case FailureKind::LcpNumericalFailure: return "lcp-numerical-failure";
    case FailureKind::LcpIterationLimit: return "lcp-iteration-limit";
    case FailureKind::NewtonFailure: return "newton-failure";
    case FailureKind::StepSizeCollapse: return "step-size-collapse";
    case FailureKind::Other: break;
  }
  return "other";
}

/// A failure as found by a check: its kind and the sentence that explains it.
struct Failure {
  FailureKind kind = FailureKind::Other;
  std::string reason;
};

/// Thrown by an integrator when it cannot continue: the time reached, the kind and the reason.
class IntegrationError : public std::exception {
 public:
  IntegrationError(double t, Failure failure)
      : time_(t),
        failure_(std::move(failure)),
        what_("integration failed at t = " + std::to_string(t) + " s: " + failure_.reason) {}
  IntegrationError(double t, FailureKind kind, std::string reason) : IntegrationError(t, Failure{kind, std::move(reason)}) {}
  const char* what() const noexcept override { return what_.c_str(); }
  double time() const { return time_; }
  const std::string& reason() const { return failure_.reason; }
  FailureKind failureKind() const { return failure_.kind; }
  const char* kind() const { return failureKeyword(failure_.kind); }

 private:
  double time_;
  Failure failure_;
  std::string what_;
};

}  // namespace chaindrive
