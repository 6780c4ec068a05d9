// The model adapter of ChainDrive.fmu (Reference-FMUs' model.c): the parameters and their
// validation, the preparation of the drive and its start state, the inputs, the values by value
// reference, the communication step of the solver and the model's part of an FMU state. The
// protocol (host.h, instance.h, fmu_state.h, fmi2_functions.cpp) calls it through the members
// listed in model_adapter.h. Adding an output touches modelDescription.xml, variables.h and the
// output table in chaindrive_model.cpp only.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "fmi2Functions.h"
#include "host.h"
#include "run/simulation.h"
#include "state_bytes.h"
#include "variables.h"

namespace chaindrive::fmu {

/// The rotors the FMU's inputs and outputs refer to (-1: the drive has none of that role).
struct RotorRoles {
  int crank = -1, intake = -1, exhaust = -1, tensionGuide = -1;
};

class ChainDriveModel {
 public:
  /// The model's part of an FMU state (fmu_state.h): the inputs, the solver state on its time
  /// grid (y empty when the model was not prepared) and the integrator's step figures.
  struct Snapshot {
    double stepHint = 0.0;
    long long steps = 0;
    double gridStart = 0.0, gridUnit = 0.0;  // the time grid, to check that a restore is on it
    long long gridIndex = 0;                 // grid point of the state y
    double crankSpeed = 0.0, tauIntake = 0.0, tauExhaust = 0.0;
    std::vector<double> y;
  };
  /// The first bytes of a serialized state of this model.
  // '3': the link states laid out component by component (src/assembly/model.h)
  static constexpr char kStateMagic[8] = {'C', 'H', 'D', 'R', 'V', 'S', 'T', '3'};
  /// Bytes of the fixed fields of a serialized Snapshot (without y).
  static constexpr std::size_t kSnapshotFieldBytes = 6 * sizeof(double) + 2 * sizeof(long long);

  explicit ChainDriveModel(Host& host) : host_(host) {}

  // preparation: the drive, the roles of its rotors and the start state at host.time()
  bool prepared() const { return prepared_; }
  fmi2Status prepare();
  void requirePreparation() { prepared_ = false; }  // the start time changed
  void reset();                                      // parameters and inputs to their start values

  // values by value reference (the checks and messages of the fmi2Get*/fmi2Set* functions)
  fmi2Status getReal(const fmi2ValueReference vr[], std::size_t n, fmi2Real v[]);
  fmi2Status getInteger(const fmi2ValueReference vr[], std::size_t n, fmi2Integer v[]);
  fmi2Status getBoolean(const fmi2ValueReference vr[], std::size_t n, fmi2Boolean v[]);
  fmi2Status getString(const fmi2ValueReference vr[], std::size_t n, fmi2String v[]);
  fmi2Status setReal(const fmi2ValueReference vr[], std::size_t n, const fmi2Real v[]);
  fmi2Status setInteger(const fmi2ValueReference vr[], std::size_t n, const fmi2Integer v[]);
  fmi2Status setBoolean(const fmi2ValueReference vr[], std::size_t n, const fmi2Boolean v[]);
  fmi2Status setString(const fmi2ValueReference vr[], std::size_t n, const fmi2String v[]);

  /// The solver from the grid point of cp to the grid point of tEnd: fmi2OK, fmi2Error (logged:
  /// no simulation, beyond the grid) or fmi2Discard (logged: the integration failed; the state
  /// stays at the last successful step). A successful step of a fixed-step method allocates
  /// nothing, does no file I/O and logs nothing.
  fmi2Status doStep(double cp, double tEnd);

  Snapshot snapshot() const;
  /// fmi2Error (logged) if the snapshot's solver state does not fit this instance (another drive
  /// or fidelity: the state sizes differ).
  fmi2Status restore(const Snapshot& s);

  // the fixed fields of a serialized Snapshot, and the first field no instance can have written
  // (nullptr if none); `components` is the size of y
  static void writeFields(const Snapshot& s, std::vector<char>& out);
  static void readFields(ByteReader& in, Snapshot& s);
  static const char* invalidField(const Snapshot& s, std::uint64_t components);

 private:
  struct Parameters {
    std::string driveFile;
    int linkIndex = -1;
    std::string method = "fixed-verlet";
    std::string contactMethod;  // "": the drive's
    std::string jointModel;     // "": the drive's
    std::string fidelity = "link";  // "link" or "span" (SimulationOptions::fidelity)
    double tolerance = 1e-5;
    double step = 2.5e-6;
    double newmarkGamma = 0.5;
    bool preload = true;
    double tensionerPreload = -1.0, tensionerStiffness = -1.0, tensionerDamping = -1.0,
           tensionerDampingExtension = -1.0;
  };
  struct Inputs {
    double crankSpeed = 314.1592653589793, tauIntake = 0.0, tauExhaust = 0.0;
  };

  // the steps of prepare()
  bool parametersValid();
  void checkChoices(std::vector<std::string>& problems) const;
  void checkRanges(std::vector<std::string>& problems) const;
  DriveDescription driveDescription();
  bool applyTensionerOverrides(DriveDescription& desc);
  bool assignRoles(const Model& m);
  void startSimulation();
  void dropSimulation();  // no model, no simulation: prepare() runs again

  // values
  double* realSetting(unsigned vr);  // a Real parameter or input; nullptr for others
  std::string* stringParameter(unsigned vr);
  bool outputsReady();  // evaluates the outputs if needed (and prepares in initialization mode)
  fmi2Status badVr(const char* function, fmi2ValueReference vr, const char* what);
  fmi2Status notAvailable(const char* function, const Variable& v);
  fmi2Status parameterChange(const Variable& v);  // only before initialization ends
  void inputChange();
  void applyInputs();

  Host& host_;
  Parameters params_;
  Inputs in_;
  long long steps_ = 0;     // integrator steps since the start (output solver.steps)
  double stepHint_ = 0.0;   // the first step adaptive methods try in the next communication step

  std::shared_ptr<const Model> model_;
  std::unique_ptr<Simulation> sim_;
  HeldInputs* held_ = nullptr;  // owned by sim_
  RotorRoles roles_;
  bool prepared_ = false;
  bool outputsValid_ = false;
  Outputs out_;
};

}  // namespace chaindrive::fmu
