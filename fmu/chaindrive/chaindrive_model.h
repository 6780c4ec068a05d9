// The model adapter of a drive's FMU (Reference-FMUs' model.c): the variables of its drive's
// interface (chaindrive_interface.h, loaded from the FMU's resources at instantiation), the
// parameters and their validation, the preparation of the drive and its start state, the inputs
// and the outputs by their bindings; the values' checks, the communication step and the FMU
// state's solver part are SimulationAdapter's (simulation_adapter.h). Its public members below the
// constructor are the hooks of the ModelAdapter concept (adapter_contract.h). A new output is a
// binding (src/interface/drive_interface.h) and its line in readRealOutput.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "chaindrive_interface.h"
#include "run/defaults.h"
#include "simulation_adapter.h"

namespace chaindrive::fmu {

/// The Real inputs, in the order of SimulationAdapter's input array: the crankshaft speed, the
/// oil supply pressure, then a load torque per sprocket of the description (by its index).
enum ChainDriveInput { kInCrankSpeed = 0, kInSupplyPressure = 1, kInLoads = 2,
                       kChainDriveInputs = kInLoads + kMaxSprockets };

class ChainDriveModel : public SimulationAdapter<ChainDriveModel, kChainDriveInputs> {
 public:
  explicit ChainDriveModel(Host& host) : SimulationAdapter(host) { in_ = kInputStarts; }

  // ---- the hooks (adapter_contract.h) ----
  static constexpr unsigned kSolverTime = chaindrive::kVrSolverTime, kSolverSteps = chaindrive::kVrSolverSteps;
  static constexpr const char* kModelWord = "drive";  // (what a state must have been taken of)
  // '5': the inputs of every sprocket ('4': a hydraulic chamber's state is its oil content; the
  // link states laid out component by component since '3', src/assembly/model.h)
  static constexpr char kStateMagic[8] = {'C', 'H', 'D', 'R', 'V', 'S', 'T', '5'};
  const Variable* findVariable(unsigned vr) const { return interface_.find(vr); }
  const char* modelIdentifier() const { return interface_.modelIdentifier().c_str(); }
  bool instantiated(const char* guid);  // the interface from the resources folder

  // the steps of prepare(): the drive, its rotors by the interface's names and the start state
  bool parametersValid();
  bool buildModel();
  void startSimulation();
  void resetSettings();

  void applyInputs();
  void evaluateOutputs() { out_ = sim_->outputs(); }
  double* realSetting(unsigned vr);  // a Real parameter or input; nullptr for others
  std::string* stringParameter(unsigned vr);
  int* integerParameter(unsigned vr) {
    const Binding b = bindingOf(vr);
    return b == Binding::LinkIndex ? &params_.linkIndex : b == Binding::SolverThreads ? &params_.threads : nullptr;
  }
  bool* booleanParameter(unsigned vr) { return bindingOf(vr) == Binding::SolverPreload ? &params_.preload : nullptr; }
  bool readRealOutput(unsigned vr, double& value) const;
  bool readIntegerOutput(unsigned vr, int& value) const;
  bool inputAcceptable(const Variable& v, double value);  // the crankshaft speed in [0, kMaxCrankSpeed]; any finite torque

 private:
  static constexpr std::array<double, kChainDriveInputs> kInputStarts = {314.1592653589793, 3e5};  // (loads 0)
  // [rad/s] the largest crankshaft speed accepted (about 28600 rpm): above chaindrive-run's
  // 20000 rpm with its rotational vibration, far below a speed no engine turns at
  static constexpr double kMaxCrankSpeed = 3000.0;
  static constexpr double kAtmosphere = 1.01325e5;     // [Pa] the gauge pressures' zero
  static constexpr double kMaxSupplyPressure = 2e7;    // [Pa] gauge: 200 bar

  struct Parameters {
    std::string driveFile;
    int linkIndex = -1;
    // the defaults (run/defaults.h): the method and the step are the fidelity's own when empty and 0
    std::string method;
    std::string contactMethod;  // "": the drive's
    std::string jointModel;     // "": the drive's
    std::string fidelity = "link";  // "link" or "span" (SimulationOptions::fidelity)
    double tolerance = solverDefaults(Scene::TimingDrive).tolerance;
    double step = 0.0;
    double newmarkGamma = 0.5;
    int threads = 1;
    bool preload = true;
    double tensionerPreload = -1.0, tensionerStiffness = -1.0, tensionerDamping = -1.0,
           tensionerDampingExtension = -1.0;
    double oilTemperature = 363.15;  // [K] a hydraulic tensioner's oil
  };

  /// The choice parameters parsed (parametersValid), as SimulationOptions takes them.
  struct Choices {
    std::optional<IntegratorMethod> method;  // none: the fidelity's own
    std::optional<ContactMethod> contacts;  // none: the drive's
    std::optional<JointModel> joints;       // none: the drive's
    Fidelity fidelity = Fidelity::Link;
  };

  // the parts of parametersValid(), buildModel() and startSimulation()
  void parseChoices(std::vector<std::string>& problems);
  void checkRanges(std::vector<std::string>& problems) const;
  DriveDescription parameterDrive();
  bool applyTensionerOverrides(DriveDescription& desc);
  bool applyOilTemperature(DriveDescription& desc);
  bool resolveElements(const Model& m);

  SimulationOptions simulationOptions() const;
  /// The binding of a value reference's variable (SolverTime, a protocol output, for none).
  Binding bindingOf(unsigned vr) const;
  const InterfaceVariable* tableEntry(unsigned vr) const;

  FmuInterface interface_;
  Parameters params_;
  Choices choices_;
  std::vector<int> rotorOf_;  // (the interface's variables) the model's rotor of an element's variable, -1 none
  std::vector<std::pair<int, int>> loads_;  // (input slot, rotor) of every load-torque input
  Outputs out_;
};

}  // namespace chaindrive::fmu
