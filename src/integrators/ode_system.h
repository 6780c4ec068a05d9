// The narrow interface through which every integrator sees a system: a first-order ODE
// y' = f(t, y) with optional sparse Jacobian, tolerance scales, a second-order structure for
// the fixed-step mechanical schemes, and a health check that detects blow-up.
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace chaindrive {

class OdeSystem {
 public:
  virtual ~OdeSystem() = default;
  virtual int size() const = 0;
  /// Returns 0 on success, > 0 for a recoverable failure (retry with a smaller step), < 0 fatal.
  virtual int rhs(double t, const double* y, double* ydot) noexcept = 0;
  /// Sparse Jacobian df/dy in compressed-sparse-column form; pattern fixed for the system's life.
  virtual bool hasJacobian() const { return false; }
  virtual int64_t jacobianNonzeros() const { return 0; }
  virtual const int64_t* jacobianColumnPointers() const { return nullptr; }
  virtual const int64_t* jacobianRowIndices() const { return nullptr; }
  virtual int jacobian(double /*t*/, const double* /*y*/, double* /*values*/) noexcept { return -1; }
  /// Half bandwidth of the dominant (banded) part of df/dy, for banded approximations.
  virtual int halfBandwidth() const { return size(); }
  /// Typical magnitude of the error that matters, per component: atol_i = rtol * scale_i.
  virtual void toleranceScales(double* scale) const = 0;
  /// For second-order schemes: index of the state holding the velocity of component i
  /// (y_i' = y_velocityOf(i)), or -1. Velocity components have isVelocity true.
  virtual int velocityOf(int i) const = 0;
  virtual bool isVelocity(int i) const = 0;
  /// Physical sanity of a state reached by a step; false with the reason when it has blown up.
  virtual bool healthy(double t, const double* y, std::string& why) noexcept = 0;
  /// The last exception message of a failed callback (callbacks never throw across C).
  virtual const std::string& lastError() const = 0;
};

struct IntegratorSettings {
  std::string method = "arkode-erk";  // see integratorNames()
  double rtol = 1e-5;                 // adaptive methods
  double fixedStep = 2e-6;            // fixed-step methods [s]
  double maxStep = 0.0;               // adaptive: 0 = unlimited
  std::string erkTable = "ARKODE_DORMAND_PRINCE_7_4_5";
  bool stopAtOutputs = false;         // never step past an output time (co-simulation)
  long maxStepsPerOutput = 5000000;
  // rigid-contact methods
  double reboundThreshold = 0.05;     // [m/s] event driven: slower rebounds close the contact
  double maxEventsPerSecond = 2e5;    // event driven: a higher rate is a runaway-event failure
  double gapTolerance = 1e-8;         // [m] rigid contacts: closed within this gap (time stepping:
                                      // active below it; event driven: open beyond it)
  std::string recordLcpDirectory;     // write the LCPs solved (Siconos format) into this directory
  int recordLcpCount = 0;             // ... the first this many
};

struct IntegratorStats {
  long long steps = 0, rhsEvaluations = 0, jacobianEvaluations = 0, nonlinearIterations = 0;
  long long errorTestFailures = 0, convergenceFailures = 0;
  double lastStep = 0.0;
};

/// Thrown by an integrator when it cannot continue: the time reached and the reason.
class IntegrationError : public std::exception {
 public:
  IntegrationError(double t, std::string reason)
      : time_(t), reason_(std::move(reason)), what_("integration failed at t = " + std::to_string(t) + " s: " + reason_) {}
  const char* what() const noexcept override { return what_.c_str(); }
  double time() const { return time_; }
  const std::string& reason() const { return reason_; }

 private:
  double time_;
  std::string reason_, what_;
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  /// (Re)starts from state y0 at t0 (after construction, an FMU state restore, or an impact).
  virtual void reset(double t0, const double* y0) = 0;
  /// Integrates to tout, writing the state at tout into y. Throws IntegrationError.
  virtual void advance(double tout, double* y) = 0;
  virtual IntegratorStats stats() const = 0;
  virtual std::string name() const = 0;
  /// First step to try after the next reset (adaptive methods); 0 lets the method choose.
  virtual void setInitialStep(double /*h*/) {}
};

std::vector<std::string> integratorNames();
/// Creates an integrator by name; throws std::invalid_argument listing the known names.
std::unique_ptr<Integrator> makeIntegrator(OdeSystem& sys, const IntegratorSettings& s);

}  // namespace chaindrive
