// The narrow interface through which every integrator sees a system: a first-order ODE
// y' = f(t, y) with optional sparse Jacobian, tolerance scales, a second-order structure for
// the fixed-step mechanical schemes, and a health check that detects blow-up.
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "choice.h"
#include "failure.h"
#include "threads.h"

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
  /// For linearly implicit schemes: replaces r (state-sized; its velocity components are read
  /// and written) by (I - a dA/dv - b dA/dx)^-1 r, where A are the accelerations and the
  /// derivatives are those of the system's stiff part at its last rhs evaluation (identity
  /// outside that part). Returns as rhs does.
  virtual bool hasStiffSolve() const { return false; }
  virtual int solveStiff(double /*a*/, double /*b*/, double* /*r*/) noexcept { return -1; }
  /// For the fixed-step schemes that treat damping implicitly: the kick a / (1 + a r) of every
  /// velocity component, r its damping rate, -d(its acceleration)/d(itself) in the system's stiff
  /// part at its last rhs evaluation (>= 0 [1/s]; 0 outside that part: the kick a), into `kick`
  /// (state-sized; its velocity components are written). `constantPart`: of the damping only the
  /// part that is the same in every state (then the kicks need no evaluation).
  virtual bool hasDampedKicks() const { return false; }
  virtual void dampedKicks(double /*a*/, bool /*constantPart*/, double* /*kick*/) noexcept {}
  /// With the kicks of the constant part (dampedKicks, constantPart), the rest of that part made
  /// implicit too, by one Jacobi sweep: replaces the accelerations in ydot (an evaluation's
  /// derivative) by ydot - a A_off ydot, A_off the constant damping's matrix (over the masses)
  /// less its diagonal. The kick a / (1 + a r) of these is then exact for a motion the damping
  /// does not resist (a rigid one) and damps the motions it resists most (neighbours against each
  /// other) as the implicit kick does, to first order. False where there is no constant part.
  virtual bool dampOffDiagonal(double /*a*/, double* /*ydot*/) noexcept { return false; }
  /// Tells the system that its integrator reads nothing of an evaluation but the derivatives (no
  /// Jacobian, stiff solve or kicks damped at the evaluation's rates follow rhs) and checks every
  /// state it reaches (healthy): the system may skip what only those need, and its check of the
  /// derivatives.
  virtual void setDerivativesOnly(bool /*on*/) {}
  /// The threads the system's evaluations run on (null: the calling thread alone), and the one
  /// among them that reads and writes state component i there: a fixed-step scheme runs its loops
  /// over the components on the same threads, so that a component stays in its thread's cache.
  virtual StagePool* stagePool() { return nullptr; }
  virtual int ownerOf(int /*i*/) const { return 0; }
  /// Half bandwidth of the dominant (banded) part of df/dy, for banded approximations; -1 when
  /// df/dy has no such band (the band solver then refuses the system).
  virtual int halfBandwidth() const { return size(); }
  /// Typical magnitude of the error that matters, per component: atol_i = rtol * scale_i.
  virtual void toleranceScales(double* scale) const = 0;
  /// For second-order schemes: index of the state holding the velocity of component i
  /// (y_i' = y_velocityOf(i)), or -1. Velocity components have isVelocity true.
  virtual int velocityOf(int i) const = 0;
  virtual bool isVelocity(int i) const = 0;
  /// Physical sanity of a state reached by a step; false with the reason when it has blown up.
  virtual bool healthy(double t, const double* y, Failure& why) noexcept = 0;
  /// The failure of the last failed callback (callbacks never throw across C): its kind
  /// (non-finite for a derivative that is not finite) and message.
  virtual const Failure& lastError() const = 0;
};

/// Step-size control of the adaptive methods (arkode-erk, cvode-bdf-klu, cvode-bdf-band; rtol
/// and maxStep also of the event-driven method).
struct AdaptiveOptions {
  double rtol = 1e-5;
  double maxStep = 0.0;               // 0 = unlimited
  double minStep = 1e-10;             // a step size below this is a step-size collapse [s]
  long maxStepsPerOutput = 5000000;
  bool stopAtOutputs = false;         // never step past an output time (co-simulation)
};

/// The fixed-step methods (fixed-verlet, fixed-verlet-implicit-damping, fixed-newmark,
/// arkode-erk-fixed; time stepping too).
struct FixedStepOptions {
  double step = 2e-6;                 // the step, exactly [s]
};

/// fixed-newmark: gamma = 1/2 keeps every mode's amplitude, more damps the unresolved ones.
struct NewmarkOptions {
  double gamma = 0.5;
};

/// arkode-erk and arkode-erk-fixed.
struct ErkOptions {
  std::string table = "ARKODE_DORMAND_PRINCE_7_4_5";
};

/// cvode-bdf-klu and cvode-bdf-band.
struct BdfOptions {
  double maxConvergenceFailureRatio = 0.5;  // more Newton convergence failures per step (over any
                                            // 200 steps) is a Newton failure
};

/// The rigid-contact methods on a drive (time stepping and event driven).
struct RigidContactOptions {
  double gapTolerance = 1e-8;         // [m] closed within this gap (time stepping: active below
                                      // it; event driven: open beyond it)
  std::string recordLcpDirectory;     // write the LCPs solved (Siconos format) into this directory
  int recordLcpCount = 0;             // ... the first this many
  int frictionFacets = 8;             // time stepping on a CVT: facets of the polygon that
                                      // linearizes a pin's friction disc (>= 3)
  bool rigidPins = false;             // time stepping on a CVT: the pins axially rigid (rigid_drive.h)
};

/// The event-driven method on a drive.
struct EventDrivenOptions {
  double reboundThreshold = 0.05;     // [m/s] slower rebounds close the contact
  double maxEventsPerSecond = 2e5;    // a higher rate is a runaway-event failure
};

/// The integrator methods of the smooth systems (compliant contacts).
enum class IntegratorMethod {
  CvodeBdfKlu,
  CvodeBdfBand,
  ArkodeErk,
  ArkodeErkFixed,
  FixedVerlet,
  FixedVerletImplicitDamping,
  FixedVerletImplicitJointDamping,
  FixedNewmark
};
template <>
struct ChoiceNames<IntegratorMethod> {
  static constexpr ChoiceName<IntegratorMethod> table[] = {
      {IntegratorMethod::CvodeBdfKlu, "cvode-bdf-klu"},
      {IntegratorMethod::CvodeBdfBand, "cvode-bdf-band"},
      {IntegratorMethod::ArkodeErk, "arkode-erk"},
      {IntegratorMethod::ArkodeErkFixed, "arkode-erk-fixed"},
      {IntegratorMethod::FixedVerlet, "fixed-verlet"},
      {IntegratorMethod::FixedVerletImplicitDamping, "fixed-verlet-implicit-damping"},
      {IntegratorMethod::FixedVerletImplicitJointDamping, "fixed-verlet-implicit-joint-damping"},
      {IntegratorMethod::FixedNewmark, "fixed-newmark"}};
};

/// The method and the options of every method; each method is built from its own
/// groups only (makeIntegrator, RigidIntegrator).
struct IntegratorSettings {
  IntegratorMethod method = IntegratorMethod::ArkodeErk;
  AdaptiveOptions adaptive;
  FixedStepOptions fixed;
  NewmarkOptions newmark;
  ErkOptions erk;
  BdfOptions bdf;
  RigidContactOptions rigid;
  EventDrivenOptions eventDriven;
};

struct IntegratorStats {
  long long steps = 0, rhsEvaluations = 0, jacobianEvaluations = 0, nonlinearIterations = 0;
  long long errorTestFailures = 0, convergenceFailures = 0;
  double lastStep = 0.0;
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  /// (Re)starts from state y0 at t0 (after construction, an FMU state restore, or an impact).
  /// Fixed-step methods step on the grid t0 + k fixedStep() from here (time_grid.h).
  virtual void reset(double t0, const double* y0) = 0;
  /// Integrates to tout, writing the state at tout into y. Throws IntegrationError. Fixed-step
  /// methods integrate to the point of their grid that time_grid.h's rule assigns to tout (a
  /// caller on the same grid asks for grid points only).
  virtual void advance(double tout, double* y) = 0;
  /// The step of a fixed-step method; 0 for adaptive methods.
  virtual double fixedStep() const { return 0.0; }
  virtual IntegratorStats stats() const = 0;
  virtual std::string name() const = 0;
  /// First step to try after the next reset (adaptive methods); 0 lets the method choose.
  virtual void setInitialStep(double /*h*/) {}
};

/// Creates the integrator of s.method from its option groups.
std::unique_ptr<Integrator> makeIntegrator(OdeSystem& sys, const IntegratorSettings& s);

}  // namespace chaindrive
