// One ChainDrive.fmu instance: the FMI 2.0 co-simulation state machine, parameters, inputs,
// logging and the FMU state, around a solver Simulation. No global or static mutable state:
// everything lives here, one allocation per instance.
#pragma once

#include <cstdarg>
#include <memory>
#include <string>
#include <vector>

#include "fmi2Functions.h"
#include "run/simulation.h"
#include "variables.h"

namespace chaindrive::fmu {

/// States of the FMI 2.0 co-simulation state machine (bit masks for the allowed-call tables).
enum State : unsigned {
  kInstantiated = 1u << 0,
  kInitializationMode = 1u << 1,
  kStepComplete = 1u << 2,
  kStepFailed = 1u << 3,
  kTerminated = 1u << 4,
  kError = 1u << 5,
};

/// A copy of everything a rollback needs.
struct Snapshot {
  unsigned state = kStepComplete;
  double time = 0.0;
  double lastSuccessfulTime = 0.0;
  double stepHint = 0.0;
  long long steps = 0;
  double gridStart = 0.0, gridUnit = 0.0;  // the time grid, to check that a restore is on it
  long long gridIndex = 0;                 // grid point of the state y
  double crankSpeed = 0.0, tauIntake = 0.0, tauExhaust = 0.0;
  std::vector<double> y;
};

class Instance {
 public:
  Instance(const char* instanceName, const fmi2CallbackFunctions* callbacks, const char* resourceLocation,
           bool loggingOn);

  unsigned state() const { return state_; }
  void setState(unsigned s) { state_ = s; }

  // logging (printf-style message; errors and warnings are always passed to the environment,
  // other categories when logging is on and the category is enabled)
  void log(fmi2Status status, const char* category, const char* fmt, ...);
  fmi2Status setDebugLogging(bool on, size_t n, const fmi2String categories[]);
  /// Returns fmi2Error after logging "<function>: not allowed in state <state>" if the current
  /// state is not in `allowed`.
  bool allowed(const char* function, unsigned allowedStates);

  fmi2Status setupExperiment(bool toleranceDefined, double tolerance, double startTime, bool stopTimeDefined,
                             double stopTime);
  fmi2Status enterInitializationMode();
  fmi2Status exitInitializationMode();
  fmi2Status doStep(double currentCommunicationPoint, double h);
  fmi2Status terminate();
  fmi2Status reset();

  fmi2Status getReal(const fmi2ValueReference vr[], size_t n, fmi2Real v[]);
  fmi2Status getInteger(const fmi2ValueReference vr[], size_t n, fmi2Integer v[]);
  fmi2Status getBoolean(const fmi2ValueReference vr[], size_t n, fmi2Boolean v[]);
  fmi2Status getString(const fmi2ValueReference vr[], size_t n, fmi2String v[]);
  fmi2Status setReal(const fmi2ValueReference vr[], size_t n, const fmi2Real v[]);
  fmi2Status setInteger(const fmi2ValueReference vr[], size_t n, const fmi2Integer v[]);
  fmi2Status setBoolean(const fmi2ValueReference vr[], size_t n, const fmi2Boolean v[]);
  fmi2Status setString(const fmi2ValueReference vr[], size_t n, const fmi2String v[]);

  fmi2Status getRealStatus(fmi2StatusKind kind, fmi2Real* value);
  fmi2Status getStatus(fmi2StatusKind kind, fmi2Status* value);

  Snapshot snapshot() const;
  fmi2Status restore(const Snapshot& s);
  static std::vector<char> serialize(const Snapshot& s);
  fmi2Status deserialize(const char* data, size_t size, Snapshot& out);

 private:
  struct Parameters {
    std::string driveFile;
    int linkIndex = -1;
    std::string method = "fixed-verlet";
    std::string contactMethod;  // "": the drive's
    std::string jointModel;     // "": the drive's
    double tolerance = 1e-5;
    double step = 2.5e-6;
    bool preload = true;
    double tensionerPreload = -1.0, tensionerStiffness = -1.0, tensionerDamping = -1.0,
           tensionerDampingExtension = -1.0;
  };
  struct Roles {
    int crank = -1, intake = -1, exhaust = -1, tensionGuide = -1;
  };

  fmi2Status prepare();            // assembles the model and the start state (initialization)
  // the steps of prepare()
  bool parametersValid();
  DriveDescription driveDescription();
  bool applyTensionerOverrides(DriveDescription& desc);
  bool assignRoles(const Model& m);
  void startSimulation();
  void dropSimulation();           // no model, no simulation: prepare() runs again
  bool outputsReady();             // evaluates the outputs if needed
  fmi2Status badVr(const char* function, fmi2ValueReference vr, const char* what);
  fmi2Status parameterChange(const Variable& v);  // only before initialization ends
  void applyInputs();

  std::string name_;
  fmi2CallbackFunctions callbacks_;
  std::string resourceDir_;
  bool loggingOn_ = false;
  std::vector<std::string> categories_;  // enabled categories; empty = all
  unsigned state_ = kInstantiated;

  Parameters params_;
  double inCrankSpeed_ = 314.1592653589793, inTauIntake_ = 0.0, inTauExhaust_ = 0.0;
  // time_: the master's communication point (cp + h of the last step, as the master formed it);
  // the solver state is at the grid point assigned to it (Simulation::time())
  double time_ = 0.0, startTime_ = 0.0, stopTime_ = 0.0, lastSuccessfulTime_ = 0.0, stepHint_ = 0.0;
  bool stopTimeDefined_ = false;
  long long steps_ = 0;

  std::shared_ptr<const Model> model_;
  std::unique_ptr<Simulation> sim_;
  HeldInputs* inputs_ = nullptr;  // owned by sim_
  Roles roles_;
  bool prepared_ = false;
  bool outputsValid_ = false;
  Outputs out_;
  std::string stringBuffer_;  // backing store for getString results
};

/// The resources directory from fmuResourceLocation (file:///dir, file:////dir, trailing '/',
/// percent-encoding, NULL); empty if none.
std::string resourceDirectory(const char* location);

}  // namespace chaindrive::fmu
