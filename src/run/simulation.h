// A simulation run: the model (shared, immutable), its work area, the inputs, the start state
// and an integrator. The command-line runner and the FMU both drive the solver through this.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "dynamics/data.h"
#include "dynamics/health.h"
#include "integrators/ode_system.h"
#include "linear/cyclic_block_tridiagonal.h"
#include "dynamics/jacobian.h"
#include "assembly/model.h"
#include "run/defaults.h"
#include "run/drive_defaults.h"
#include "outputs/outputs.h"
#include "statics/preload.h"
#include "nonsmooth/rigid_drive.h"
#include "integrators/time_grid.h"
#include "span/span_system.h"

namespace chaindrive {

struct SimulationOptions {
  Fidelity fidelity = Fidelity::Link;  // the link-by-link model or the span model (src/span/) of the
                                       // same drive
  IntegratorSettings integrator;      // compliant contacts: the integrator by name; rigid contacts:
                                      // fixed.step and rigid (time stepping), adaptive.rtol and
                                      // maxStep, rigid and eventDriven (event driven)
  std::optional<ContactMethod> contactMethod;  // none: the drive's
  std::optional<JointModel> jointModel;        // none: the drive's
  PreloadOptions preload;
  HealthLimits health;              // blow-up and tunnelling detection
  int monitoredLink = -1;           // -1: the model's
  std::string stepName = "solver.step";  // the fixed step's setting as a blow-up's advice names it
  bool blowUpAdvice = true;         // a blow-up's failure offers a stable step (false: the step
                                    // probe's own runs, run/step_probe.h, whose advice would probe)
  std::shared_ptr<const span::SpanModel> spanModel;  // span fidelity: this model (of the same link
                                                     // model) instead of one assembled and calibrated
  int threads = 1;                  // threads of the link model's evaluations (dynamics/threaded.h):
                                    // the same bits for every number; more than 1 only where they apply
  std::string spanCalibrationFile;  // span fidelity: a read-only calibration looked in before the
                                    // cache (an FMU's resources/span_calibration.json; taken when its
                                    // key is the drive's: span/calibration_cache.h); "": none
};

/// The compliant-contact chain drive as an ODE system for the integrators.
class DriveSystem : public OdeSystem {
 public:
  DriveSystem(std::shared_ptr<const Model> m, const InputSignal& in, const HealthLimits& health);
  int size() const override { return model_->nStates; }
  int rhs(double t, const double* y, double* ydot) noexcept override;
  bool hasJacobian() const override { return true; }
  int64_t jacobianNonzeros() const override { return jac_.nnz(); }
  const int64_t* jacobianColumnPointers() const override { return jac_.columnPointers().data(); }
  const int64_t* jacobianRowIndices() const override { return jac_.rowIndices().data(); }
  int jacobian(double t, const double* y, double* values) noexcept override;
  bool hasStiffSolve() const override { return true; }
  int solveStiff(double a, double b, double* r) noexcept override;  // joints and contacts on the links
  // the state is laid out component by component (model.h): a link's position and velocity lie
  // 3 links apart, so df/dy has no narrow band
  bool hasDampedKicks() const override { return true; }
  // the links' joints (their constant part, without clearance) and contacts
  void dampedKicks(double a, bool constantPart, double* kick) noexcept override;
  bool dampOffDiagonal(double a, double* ydot) noexcept override;
  int halfBandwidth() const override { return -1; }
  void toleranceScales(double* scale) const override;
  int velocityOf(int i) const override { return velocityOf_[i]; }
  bool isVelocity(int i) const override { return isVelocity_[i] != 0; }
  void setDerivativesOnly(bool on) override {
    derivativesOnly_ = on;
    data_.listContacts = !on;
  }
  StagePool* stagePool() override;
  int ownerOf(int i) const override;
  bool healthy(double t, const double* y, Failure& why) noexcept override;
  const Failure& lastError() const override { return lastError_; }
  Data& data() { return data_; }

 private:
  std::shared_ptr<const Model> model_;
  const InputSignal& in_;
  Data data_;
  JacobianAssembler jac_;
  CyclicBlockTridiagonal3 iteration_;      // linearly implicit schemes: the links' W
  std::vector<double> linkRhs_;            // (3 links) M r, then the solution
  std::vector<int> velocityOf_;
  std::vector<char> isVelocity_;
  HealthLimits health_;
  bool derivativesOnly_ = false;           // setDerivativesOnly
  Failure lastError_;
};

/// The integrators a drive with pulleys (a CVT) runs with: its pin-sheave contacts give no
/// Jacobian and no damping rates, which the others need.
constexpr IntegratorMethod kPulleyIntegrators[] = {
    IntegratorMethod::FixedVerlet, IntegratorMethod::FixedVerletImplicitJointDamping, IntegratorMethod::ArkodeErk,
    IntegratorMethod::ArkodeErkFixed};

/// A run's choices, the drive's where the options leave them open.
struct RunChoices {
  Fidelity fidelity;
  ContactMethod contacts;
  JointModel joints;
  IntegratorMethod method;
  bool rigidPins;
};
RunChoices runChoices(const Model& m, const SimulationOptions& opt);

/// The table's row (run/defaults.h) of a run of m with the options' fidelity: the row for joints
/// with clearance or rigid contacts (the options' or the drive's) where they apply.
const SolverDefaults& ownTableRow(const Model& m, const SimulationOptions& opt);

/// The timing drive's solver defaults for a run of m with the options' fidelity: ownTableRow with
/// the drive's own step (run/drive_defaults.h; the table's for the default drive).
SolverDefaults ownSolverDefaults(const Model& m, const SimulationOptions& opt);

/// The fixed step of a run of m with `method` and why: `given` as given, else the drive's step of
/// the row whose step the method takes (defaultStepRow on ownTableRow).
StepChoice defaultStepChoice(const Model& m, const SimulationOptions& opt, IntegratorMethod method,
                             std::optional<double> given = std::nullopt);

/// The choice a combination rule refuses (the one to change), and why: its text starts with the
/// refused value, so that each boundary puts its own name of the choice before it.
enum class RunChoice { Fidelity, ContactMethod, JointModel, Integrator, RigidPins };
struct ChoiceProblem {
  RunChoice choice;
  std::string text;
};

/// The rules that combine a run's choices on a drive, in one place (empty: the combination runs).
/// Simulation refuses a run that breaks one; the FMUs report them by parameter name.
std::vector<ChoiceProblem> combinationProblems(const Model& m, const RunChoices& choices);

class Simulation {
 public:
  Simulation(std::shared_ptr<const Model> model, const SimulationOptions& opt, std::unique_ptr<InputSignal> inputs);

  /// Pre-loads the start state for the inputs at t0 and starts the integrator there; the run's
  /// time grid (time_grid.h) starts at t0.
  void start(double t0);
  /// Starts from a given state at t0 (a saved state); the time grid starts at t0.
  void startFrom(double t0, const std::vector<double>& y);
  /// Starts from a given state at point k of the current time grid (an FMU state restore).
  void restoreAt(long long k, const std::vector<double>& y);
  /// Integrates to the grid point of t (time_grid.h: t itself when it is on the grid, otherwise
  /// the point before it) and returns that point's time; throws IntegrationError (time and
  /// reason) when the method fails, std::invalid_argument when t is beyond the grid's range. The
  /// state stays at its last successful value. A fixed-step method's blow-up (a joint or span
  /// stretched, a contact tunnelled, a state not finite) names the step it ran with and the
  /// drive's estimated stable step to try (stepAdvice, under the options' stepName).
  double advanceTo(double t);
  /// Restarts the integrator from the current state and grid point (a communication step that
  /// must not depend on the integrator's history: exact rollback, bit-identical instances), the
  /// step means' accumulators zeroed (model.h: ImpulseStates; the outputs' step means then average
  /// over the time advanced since). `initialStep` is the first step adaptive methods try (0:
  /// their own estimate).
  void restart(double initialStep);

  /// The run's time grid: unit = the fixed step of fixed-step methods, kAdaptiveTimeQuantum for
  /// adaptive ones; the state is at grid point gridIndex().
  const TimeGrid& grid() const { return grid_; }
  long long gridIndex() const { return k_; }
  double time() const { return grid_.time(k_); }
  const std::vector<double>& state() const { return y_; }
  const Model& model() const { return *model_; }
  InputSignal& inputs() { return *inputs_; }
  const PreloadReport& preloadReport() const { return preload_; }
  IntegratorStats integratorStats() const { return integrator_->stats(); }
  long long rhsEvaluations() const;
  /// Barriers the threads crossed (solver.threads > 1; 0 on one thread).
  long long threadBarriers() const { return pool_ ? pool_->barriers() : 0; }
  const char* integratorName() const { return choiceName(options_.integrator.method); }
  /// The step of a fixed-step method (compliant or time stepping); 0 for adaptive methods.
  double integratorFixedStep() const { return integrator_->fixedStep(); }
  ContactMethod contactMethod() const { return contactMethod_; }
  Fidelity fidelity() const { return options_.fidelity; }
  /// The span model (nullptr in link fidelity).
  const span::SpanModel* spanModel() const { return spanModel_.get(); }
  /// Counters of the rigid-contact methods (nullptr for compliant contacts).
  const ns::NsStats* contactStats() const { return rigidIntegrator_ ? &rigidIntegrator_->contactStats() : nullptr; }
  /// Outputs at the current state (evaluates the dynamics once more; no allocation after the first call).
  const Outputs& outputs();
  /// The work area outputs() evaluated in (the link model; nullptr for the span model): the
  /// contacts behind the outputs, for a scene's own (cvt/cvt_outputs.h).
  const Data* outputData() const { return system_ ? &system_->data() : outData_.get(); }

 private:
  std::shared_ptr<const Model> model_;
  SimulationOptions options_;
  std::unique_ptr<InputSignal> inputs_;
  ContactMethod contactMethod_;  // the options' or the drive's
  std::unique_ptr<DriveSystem> system_;              // compliant contacts
  std::shared_ptr<RigidContactDrive> rigid_;         // rigid contacts
  RigidIntegrator* rigidIntegrator_ = nullptr;       // owned by integrator_
  std::shared_ptr<const span::SpanModel> spanModel_;  // span fidelity
  std::unique_ptr<span::SpanSystem> spanSystem_;
  std::unique_ptr<span::SpanData> outSpanData_;
  std::unique_ptr<Integrator> integrator_;
  std::vector<ContactPoint> rigidContacts_;
  std::unique_ptr<Data> outData_;             // rigid contacts: the outputs' work area
  std::unique_ptr<StagePool> pool_;           // options' threads > 1
  std::vector<double> y_;
  TimeGrid grid_;
  long long k_ = 0;  // grid index of the state y_
  PreloadReport preload_;
  Outputs out_;

  void buildLinkModel(JointModel joints);
  void buildSpanModel();
  void startThreads();
  std::string blowUpAdvice(double step) const;  // stepAdvice for this run's failure at `step`
};

}  // namespace chaindrive
