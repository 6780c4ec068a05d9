// The model adapter of CVTChain.fmu: the chain CVT (src/cvt/) for transmission and vehicle
// simulation. Its parameters and their validation, the preparation of the CVT and its start
// state (the nominal state at the inputs: driving speed and ratio), the inputs and the outputs by
// value reference; the values' checks, the communication step and the FMU state's solver part are
// SimulationAdapter's (simulation_adapter.h), as for ChainDrive.fmu. Its public members below the
// constructor are the hooks of the ModelAdapter concept (adapter_contract.h). The ratio is an
// input the sheaves follow within the description's ratio range; the clamping force a parameter.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "cvt/cvt_description.h"
#include "cvt/cvt_outputs.h"
#include "run/defaults.h"
#include "simulation_adapter.h"
#include "cvt_variables.h"

namespace chaindrive::fmu {

/// The Real inputs, in the order of SimulationAdapter's input array.
enum CvtInput { kInDrivingSpeed = 0, kInLoadTorque = 1, kInRatio = 2, kCvtInputs = 3 };

class CvtChainModel : public SimulationAdapter<CvtChainModel, kCvtInputs> {
 public:
  explicit CvtChainModel(Host& host) : SimulationAdapter(host) { in_ = kInputStarts; }

  // ---- the hooks (adapter_contract.h) ----
  static constexpr unsigned kSolverTime = fmu::kSolverTime, kSolverSteps = fmu::kSolverSteps;
  const Variable* findVariable(unsigned vr) const { return fmu::findVariable(vr); }
  const char* modelIdentifier() const { return kModelIdentifier; }
  bool instantiated(const char* guid) { return guidMatches(guid, kGuid); }
  static constexpr const char* kModelWord = "CVT";  // (what a state must have been taken of)
  static constexpr char kStateMagic[8] = {'C', 'V', 'T', 'C', 'H', 'S', 'T', '2'};  // '2': the ratio input

  // the steps of prepare()
  bool parametersValid();
  bool buildModel();
  void startSimulation();
  void resetSettings();

  void applyInputs();
  void evaluateOutputs();
  double* realSetting(unsigned vr);
  std::string* stringParameter(unsigned vr);
  int* integerParameter(unsigned vr) { return vr == kLinkIndex ? &params_.linkIndex : nullptr; }
  bool* booleanParameter(unsigned) { return nullptr; }
  bool readRealOutput(unsigned vr, double& value) const;
  bool readIntegerOutput(unsigned vr, int& value) const;
  bool inputAcceptable(const Variable& v, double value);

 private:
  static constexpr std::array<double, kCvtInputs> kInputStarts = {209.43951023931953, 0.0, 1.0};

  struct Parameters {
    std::string cvtFile;
    int linkIndex = -1;
    // the CVT's defaults (run/defaults.h)
    std::string method = choiceName(solverDefaults(Scene::Cvt).method);
    double tolerance = solverDefaults(Scene::Cvt).tolerance;
    double step = solverDefaults(Scene::Cvt).step;
    double clampingForce = -1.0;  // < 0: the description's
  };

  SimulationOptions simulationOptions() const;

  Parameters params_;
  IntegratorMethod method_ = IntegratorMethod::FixedVerlet;  // solver.method parsed (parametersValid)
  Outputs out_;
  CvtOutputs cvt_;
};

}  // namespace chaindrive::fmu
