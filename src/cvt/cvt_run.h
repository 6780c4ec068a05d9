// A stationary CVT run: the driving pulley at a constant speed, a constant load torque on the
// driven one, from the nominal state; the CVT's outputs sampled at every output step, and their
// means over the run's second part with the checks of a stationary state (speed ratio, torque
// balance, energy balance). The command-line tool and the tests run the CVT through this.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "assembly/model.h"
#include "cvt/cvt_outputs.h"
#include "dynamics/dynamics.h"
#include "integrators/ode_system.h"
#include "nonsmooth/system.h"
#include "run/defaults.h"
#include "run/state_file.h"

namespace chaindrive {

struct CvtRunOptions {
  double drivingSpeed = 2000.0 * 3.14159265358979323846 / 30.0;  // [rad/s] in the running direction
  double loadTorque = 0.0;        // [N m] on the driven pulley, against its running direction
  double duration = 0.2;          // [s]
  double outputStep = 5e-5;       // [s]
  double statisticsFrom = 0.5;    // the means start at this fraction of the duration
  ContactMethod contactMethod = ContactMethod::Compliant;  // or time stepping: the pins' friction as
                                                          // complementarity
  IntegratorSettings integrator;  // method, step and tolerance (default: the CVT's row of run/defaults.h)
  int monitoredLink = -1;         // the pin of the Figure 9 outputs (-1: the model's)
  std::optional<StateSnapshot> start;  // a saved state to start from (else the nominal state at 0);
                                       // the run lasts `duration` from its time
  CvtRunOptions() { applySolverDefaults(solverDefaults(Scene::Cvt), integrator); }
};

/// A CVT run's method by one name: an integrator of the compliant pins, or time stepping (the
/// pins' friction as complementarity) with compliant or axially rigid pins.
enum class CvtMethod {
  FixedVerlet,
  FixedVerletImplicitJointDamping,
  ArkodeErk,
  ArkodeErkFixed,
  TimeStepping,
  TimeSteppingRigidPins
};
template <>
struct ChoiceNames<CvtMethod> {
  static constexpr ChoiceName<CvtMethod> table[] = {
      {CvtMethod::FixedVerlet, "fixed-verlet"},
      {CvtMethod::FixedVerletImplicitJointDamping, "fixed-verlet-implicit-joint-damping"},
      {CvtMethod::ArkodeErk, "arkode-erk"},
      {CvtMethod::ArkodeErkFixed, "arkode-erk-fixed"},
      {CvtMethod::TimeStepping, "time-stepping"},
      {CvtMethod::TimeSteppingRigidPins, "time-stepping-rigid-pins"}};
};

/// Sets the contact method, the integrator and the pins' rigidity of `method`.
void setCvtMethod(CvtMethod method, CvtRunOptions& run);
/// The method `run` is set to.
CvtMethod cvtMethodOf(const CvtRunOptions& run);

struct CvtSample {
  double time = 0.0;
  CvtOutputs cvt;
  EnergyTerms energy;
};

/// Means over the statistics window, and the checks of a stationary run.
struct CvtSummary {
  double from = 0.0, to = 0.0;    // [s] the window
  double drivingSpeed = 0.0, drivenSpeed = 0.0;  // [rad/s]
  double slip = 0.0;              // mean slip
  double speedRatio = 0.0;        // mean driving over mean driven speed
  double geometricRatio = 0.0;    // r2 / r1 of the assembly
  double tightStrandForce = 0.0, slackStrandForce = 0.0;  // [N]
  double clampingForce[2] = {0.0, 0.0};                   // [N]
  double drivingTorque = 0.0, drivenTorque = 0.0;         // [N m]
  double powerLoss = 0.0;         // [W] mean dissipated power (the dissipated energy's growth over the window)
  double netInputPower = 0.0;     // [W] mean driving minus output power (the input work's growth)
  // checks
  double speedRatioError = 0.0;   // speedRatio / geometricRatio - 1
  double torqueBalanceDriven = 0.0;  // (F_tight - F_slack) r2 [N m], to compare with drivenTorque
  double torqueBalanceDriving = 0.0; // (F_tight - F_slack) r1 [N m], to compare with drivingTorque
  double energyBalanceError = 0.0;   // change of (energy + dissipated - input work) over the
                                     // window, over the energy dissipated in it
  double pinsInContact[2] = {0.0, 0.0};  // mean number of pins pressed by each pulley's sheaves
};

struct CvtRunResult {
  std::vector<CvtSample> samples;
  CvtSummary summary;
  double cpuSeconds = 0.0;        // of the integration (outputs included)
  long long steps = 0;
  std::optional<ns::NsStats> contactStats;  // time stepping: its LCPs
  StateSnapshot end;              // the last state
};

/// Runs the model (a CVT: assembleCvt) with the options; throws IntegrationError when the method
/// fails, std::invalid_argument for options the CVT does not support.
CvtRunResult runCvt(std::shared_ptr<const Model> m, const CvtRunOptions& opt);

/// The means and checks of samples whose time lies in [from, to].
CvtSummary summarizeCvt(const Model& m, const std::vector<CvtSample>& samples, double from, double to);

}  // namespace chaindrive
