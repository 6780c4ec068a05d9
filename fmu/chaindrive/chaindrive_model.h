// The model adapter of ChainDrive.fmu (Reference-FMUs' model.c): the parameters and their
// validation, the preparation of the drive and its start state, the inputs and the outputs by
// value reference; the values' checks, the communication step and the FMU state's solver part
// are SimulationAdapter's (simulation_adapter.h). Its public members below the constructor are
// the hooks of the ModelAdapter concept (adapter_contract.h). Adding an output touches
// modelDescription.xml, chaindrive_variables.h and the output table in chaindrive_model.cpp only.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "run/defaults.h"
#include "simulation_adapter.h"
#include "chaindrive_variables.h"

namespace chaindrive::fmu {

/// The rotors the FMU's inputs and outputs refer to (-1: the drive has none of that role).
struct RotorRoles {
  int crank = -1, intake = -1, exhaust = -1, tensionGuide = -1;
};

/// The Real inputs, in the order of SimulationAdapter's input array.
enum ChainDriveInput { kInCrankSpeed = 0, kInTauIntake = 1, kInTauExhaust = 2, kInSupplyPressure = 3, kChainDriveInputs = 4 };

class ChainDriveModel : public SimulationAdapter<ChainDriveModel, kChainDriveInputs> {
 public:
  explicit ChainDriveModel(Host& host) : SimulationAdapter(host) { in_ = kInputStarts; }

  // ---- the hooks (adapter_contract.h) ----
  static constexpr ModelDescription kDescription = {kModelIdentifier, kGuid, findVariable, kSolverTime, kSolverSteps};
  static constexpr const char* kModelWord = "drive";  // (what a state must have been taken of)
  // '4': a hydraulic chamber's state is its oil content ('3': its pressure; the link states laid
  // out component by component since '3', src/assembly/model.h)
  static constexpr char kStateMagic[8] = {'C', 'H', 'D', 'R', 'V', 'S', 'T', '4'};

  // the steps of prepare(): the drive, the roles of its rotors and the start state at host.time()
  bool parametersValid();
  bool buildModel();
  void startSimulation();
  void resetSettings();

  void applyInputs();
  void evaluateOutputs() { out_ = sim_->outputs(); }
  double* realSetting(unsigned vr);  // a Real parameter or input; nullptr for others
  std::string* stringParameter(unsigned vr);
  int* integerParameter(unsigned vr) { return vr == kLinkIndex ? &params_.linkIndex : nullptr; }
  bool* booleanParameter(unsigned vr) { return vr == kSolverPreload ? &params_.preload : nullptr; }
  bool readRealOutput(unsigned vr, double& value) const;
  bool readIntegerOutput(unsigned vr, int& value) const;
  bool inputAcceptable(const Variable& v, double value);  // crankshaft.w in [0, kMaxCrankSpeed]; any finite torque

 private:
  static constexpr std::array<double, kChainDriveInputs> kInputStarts = {314.1592653589793, 0.0, 0.0, 3e5};
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
  bool applyTensionerOverrides(DriveDescription& desc);
  bool applyOilTemperature(DriveDescription& desc);
  bool assignRoles(const Model& m);

  SimulationOptions simulationOptions() const;

  Parameters params_;
  Choices choices_;
  RotorRoles roles_;
  Outputs out_;
};

}  // namespace chaindrive::fmu
