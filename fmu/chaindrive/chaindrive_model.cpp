#include "chaindrive_model.h"

#include <cmath>

#include "description/drive_description.h"

namespace chaindrive::fmu {

namespace {

// What a Real output is read from: the solver outputs at the current state and the rotors' roles.
struct OutputView {
  const Outputs& out;
  const RotorRoles& roles;
};

// A rotor's quantity; 0 when the drive has no rotor of that role.
double rotor(int r, const std::vector<double>& a) { return r >= 0 ? a[r] : 0.0; }

struct RealOutput {
  unsigned vr;
  double (*read)(const OutputView& s);
};

// clang-format off
constexpr RealOutput kRealOutputs[] = {
  {kCrankshaftPhi,            [](const OutputView& s) { return rotor(s.roles.crank, s.out.rotorAngle); }},
  {kCrankshaftTau,            [](const OutputView& s) { return s.out.crankTorque; }},
  {kCamshaftIntakePhi,        [](const OutputView& s) { return rotor(s.roles.intake, s.out.rotorAngle); }},
  {kCamshaftIntakeW,          [](const OutputView& s) { return rotor(s.roles.intake, s.out.rotorRate); }},
  {kCamshaftExhaustPhi,       [](const OutputView& s) { return rotor(s.roles.exhaust, s.out.rotorAngle); }},
  {kCamshaftExhaustW,         [](const OutputView& s) { return rotor(s.roles.exhaust, s.out.rotorRate); }},
  {kTensionGuidePhi,          [](const OutputView& s) { return rotor(s.roles.tensionGuide, s.out.rotorAngle); }},
  {kTensionGuideW,            [](const OutputView& s) { return rotor(s.roles.tensionGuide, s.out.rotorRate); }},
  {kTensionerF,               [](const OutputView& s) { return s.out.tensionerForce; }},
  {kTensionerS,               [](const OutputView& s) { return s.out.tensionerStroke; }},
  {kTensionerV,               [](const OutputView& s) { return s.out.tensionerRate; }},
  {kChainFtight,              [](const OutputView& s) { return s.out.tightSpanForce; }},
  {kChainFslack,              [](const OutputView& s) { return s.out.slackSpanForce; }},
  {kLinkF,                    [](const OutputView& s) { return s.out.linkTension; }},
  {kLinkFn,                   [](const OutputView& s) { return s.out.linkNormalForce; }},
  {kLinkFnSprocket,           [](const OutputView& s) { return s.out.linkSprocketForce; }},
  {kLinkFnGuide,              [](const OutputView& s) { return s.out.linkGuideForce; }},
  {kLinkX,                    [](const OutputView& s) { return s.out.linkPosition.x; }},
  {kLinkY,                    [](const OutputView& s) { return s.out.linkPosition.y; }},
  {kEnergyKinetic,            [](const OutputView& s) { return s.out.energy.kinetic; }},
  {kEnergyElastic,            [](const OutputView& s) { return s.out.energy.elastic; }},
  {kEnergyDissipated,         [](const OutputView& s) { return s.out.energy.dissipated; }},
  {kEnergyInput,              [](const OutputView& s) { return s.out.energy.inputWork; }},
  {kChainMaxJointDeformation, [](const OutputView& s) { return s.out.maxJointDeformation; }},
  {kTensionerChamberPressure, [](const OutputView& s) { return s.out.chamberPressure; }},
  {kTensionerCheckValveFlow,  [](const OutputView& s) { return s.out.tensionerFlows.check; }},
  {kTensionerLeakFlow,        [](const OutputView& s) { return s.out.tensionerFlows.leak; }},
};
// clang-format on

const RealOutput* findRealOutput(unsigned vr) {
  for (const RealOutput& o : kRealOutputs)
    if (o.vr == vr) return &o;
  return nullptr;
}

}  // namespace

// ---- preparation ----

// The drive from the parameters (the file, the tensioner overrides) and the roles of its rotors.
bool ChainDriveModel::buildModel() {
  DriveDescription desc =
      describedBy(params_.driveFile, "default_drive.json", "drive", loadDriveDescription, defaultDriveDescription);
  if (!applyTensionerOverrides(desc)) return false;
  model_ = std::make_shared<const Model>(assemble(desc));
  return assignRoles(*model_) && choicesCombine(simulationOptions());
}

void ChainDriveModel::resetSettings() {
  params_ = Parameters{};
  choices_ = Choices{};
  in_ = kInputStarts;
}

// Every parameter problem is logged (all of them at once); false if there was one.
bool ChainDriveModel::parametersValid() {
  std::vector<std::string> problems;
  parseChoices(problems);
  checkRanges(problems);
  for (const auto& p : problems) host_.log(fmi2Error, "logStatusError", "%s", p.c_str());
  return problems.empty();
}

// The named choices (fidelity, integrator, contact method, joint model), parsed once; how they
// combine is checked with the drive (buildModel).
void ChainDriveModel::parseChoices(std::vector<std::string>& problems) {
  parseChoiceParameter("fidelity", params_.fidelity, choices_.fidelity, problems);
  parseChoiceParameter("solver.method", params_.method, choices_.method, problems, "the fidelity's own");
  parseChoiceParameter("contact.method", params_.contactMethod, choices_.contacts, problems);
  parseChoiceParameter("chain.jointModel", params_.jointModel, choices_.joints, problems);
}

// The numbers: solver tolerance and step, the tensioner overrides (negative: as in the drive).
void ChainDriveModel::checkRanges(std::vector<std::string>& problems) const {
  checkRange(problems, "solver.tolerance", params_.tolerance, 1e-12, 0.1);
  if (params_.step != 0.0 && !(params_.step >= 1e-9 && params_.step <= 1e-3))  // 0: the fidelity's own (run/defaults.h)
    problems.push_back(outsideRange("solver.step", params_.step, 1e-9, 1e-3, "s") + " (or 0: the fidelity's own step)");
  checkRange(problems, "solver.newmarkGamma", params_.newmarkGamma, 0.5, 1.0);
  auto checkOverride = [&](double v, const char* name, double hi, const char* unit) {
    if (!std::isfinite(v) || v > hi)
      problems.push_back(outsideRange(name, v, 0.0, hi, unit) + " (or negative: the drive description's)");
  };
  checkOverride(params_.tensionerPreload, "tensioner.preload", 1e5, "N");
  checkOverride(params_.tensionerStiffness, "tensioner.stiffness", 1e9, "N/m");
  checkOverride(params_.tensionerDamping, "tensioner.damping", 1e7, "N s/m");
  checkOverride(params_.tensionerDampingExtension, "tensioner.dampingExtension", 1e7, "N s/m");
}

// The crankshaft speed turns the drive in its running direction only: a negative speed (or one
// far beyond any engine's) is refused when set, before it can blow the run up.
bool ChainDriveModel::inputAcceptable(const Variable& v, double value) {
  if (v.vr == kTensionerSupplyPressure) {
    // gauge: no absolute pressure below zero; above, far beyond any engine's oil gallery
    if (value >= -kAtmosphere && value <= kMaxSupplyPressure) return true;
    host_.log(fmi2Error, "logStatusError", "fmi2SetReal: %s (gauge; the absolute pressure cannot be negative)",
              outsideRange(v.name, value, -kAtmosphere, kMaxSupplyPressure, "Pa").c_str());
    return false;
  }
  if (v.vr != kCrankshaftW || (value >= 0.0 && value <= kMaxCrankSpeed)) return true;
  host_.log(fmi2Error, "logStatusError", "fmi2SetReal: %s (the crankshaft turns in the running direction only)",
            outsideRange(v.name, value, 0.0, kMaxCrankSpeed, "rad/s").c_str());
  return false;
}

// The tensioner parameters (negative: as in the drive); false if the drive has no tensioner.
bool ChainDriveModel::applyTensionerOverrides(DriveDescription& desc) {
  const bool overrides = params_.tensionerPreload >= 0 || params_.tensionerStiffness >= 0 ||
                         params_.tensionerDamping >= 0 || params_.tensionerDampingExtension >= 0;
  if (overrides && !desc.tensioner.present) {
    host_.log(fmi2Error, "logStatusError", "tensioner.*: the drive has no tensioner to apply the parameters to");
    return false;
  }
  const bool damping = params_.tensionerDamping >= 0 || params_.tensionerDampingExtension >= 0;
  if (damping && desc.tensioner.kind == TensionerKind::Hydraulic) {
    host_.log(fmi2Error, "logStatusError", "tensioner.damping, tensioner.dampingExtension: apply to the "
              "spring-damper law only; the drive's tensioner is hydraulic (its oil damps: tensioner.oilTemperature "
              "and the drive description's tensioner.hydraulic)");
    return false;
  }
  if (params_.tensionerPreload >= 0) desc.tensioner.preload = params_.tensionerPreload;
  if (params_.tensionerStiffness >= 0) desc.tensioner.stiffness = params_.tensionerStiffness;
  if (params_.tensionerDamping >= 0) desc.tensioner.damping = params_.tensionerDamping;
  if (params_.tensionerDampingExtension >= 0) desc.tensioner.dampingExtension = params_.tensionerDampingExtension;
  return applyOilTemperature(desc);
}

// tensioner.oilTemperature sets a hydraulic tensioner's oil temperature, within its viscosity law's range.
bool ChainDriveModel::applyOilTemperature(DriveDescription& desc) {
  if (desc.tensioner.kind != TensionerKind::Hydraulic) return true;
  const OilDesc& oil = desc.tensioner.hydraulic.oil;
  const double temperature = params_.oilTemperature;
  if (!(temperature >= oil.temperatureMin && temperature <= oil.temperatureMax)) {
    host_.log(fmi2Error, "logStatusError", "%s (the range of the oil's viscosity law)",
              outsideRange("tensioner.oilTemperature", temperature, oil.temperatureMin, oil.temperatureMax, "K").c_str());
    return false;
  }
  desc.tensioner.hydraulic.oilTemperature = temperature;
  return true;
}

// The rotors the FMU's inputs and outputs refer to, and the monitored link's range.
bool ChainDriveModel::assignRoles(const Model& m) {
  if (params_.linkIndex < -1 || params_.linkIndex >= m.chain.links) {
    host_.log(fmi2Error, "logStatusError", "link.index = %d is outside 0..%d (or -1: as in the drive)",
              params_.linkIndex, m.chain.links - 1);
    return false;
  }
  roles_ = RotorRoles{};
  roles_.crank = m.drivenRotor;
  if (roles_.crank < 0) {
    host_.log(fmi2Error, "logStatusError", "the drive has no sprocket with motion 'prescribed' to follow crankshaft.w");
    return false;
  }
  roles_.intake = m.rotorIndex("camshaftIntake");
  roles_.exhaust = m.rotorIndex("camshaftExhaust");
  roles_.tensionGuide = m.tensioner.present ? m.tensioner.rotor : -1;
  if (roles_.intake < 0 || roles_.exhaust < 0)
    host_.log(fmi2Warning, "logStatusWarning",
              "the drive has no sprocket named camshaftIntake and/or camshaftExhaust: their inputs have no effect and "
              "their outputs are zero");
  return true;
}

// The solver parameters as the simulation takes them.
SimulationOptions ChainDriveModel::simulationOptions() const {
  SimulationOptions opt;
  opt.fidelity = choices_.fidelity;
  opt.contactMethod = choices_.contacts;
  // solver.method empty and solver.step 0: the fidelity's own (run/defaults.h: the row of runs
  // with joints with clearance or rigid contacts, or not), as the command-line tools and the
  // harness take them
  const SolverDefaults& own =
      model_ ? ownSolverDefaults(*model_, opt) : solverDefaults(Scene::TimingDrive, opt.fidelity);
  opt.integrator.method = choices_.method.value_or(own.method);
  opt.integrator.adaptive.rtol = params_.tolerance;
  opt.integrator.fixed.step = params_.step > 0.0 ? params_.step : defaultStep(own, opt.integrator.method);
  opt.integrator.newmark.gamma = params_.newmarkGamma;
  opt.integrator.adaptive.stopAtOutputs = true;
  opt.jointModel = choices_.joints;
  opt.preload.enabled = params_.preload;
  opt.monitoredLink = params_.linkIndex;
  return opt;
}

// The simulation of model_ with the solver parameters, at its start state on the time grid.
void ChainDriveModel::startSimulation() {
  makeSimulation(simulationOptions());
  sim_->start(host_.time());
  // what the start state solve found
  const PreloadReport& rep = sim_->preloadReport();
  host_.log(rep.converged ? fmi2OK : fmi2Warning, rep.converged ? "logEvents" : "logStatusWarning",
            "start state: %s (%.3f s CPU)", rep.message.c_str(), rep.cpuSeconds);
  runStarted();
}

void ChainDriveModel::applyInputs() {
  if (!held_) return;
  InputValues& v = held_->values;
  v.crankSpeed = in_[kInCrankSpeed];
  if (roles_.intake >= 0) v.loadTorque[roles_.intake] = in_[kInTauIntake];
  if (roles_.exhaust >= 0) v.loadTorque[roles_.exhaust] = in_[kInTauExhaust];
  v.supplyPressure = in_[kInSupplyPressure];
}

// ---- values by value reference ----

double* ChainDriveModel::realSetting(unsigned vr) {
  switch (vr) {
    case kCrankshaftW: return &in_[kInCrankSpeed];
    case kCamshaftIntakeTau: return &in_[kInTauIntake];
    case kCamshaftExhaustTau: return &in_[kInTauExhaust];
    case kTensionerSupplyPressure: return &in_[kInSupplyPressure];
    case kTensionerOilTemperature: return &params_.oilTemperature;
    case kSolverTolerance: return &params_.tolerance;
    case kSolverStep: return &params_.step;
    case kSolverNewmarkGamma: return &params_.newmarkGamma;
    case kTensionerPreload: return &params_.tensionerPreload;
    case kTensionerStiffness: return &params_.tensionerStiffness;
    case kTensionerDamping: return &params_.tensionerDamping;
    case kTensionerDampingExtension: return &params_.tensionerDampingExtension;
    default: return nullptr;
  }
}

std::string* ChainDriveModel::stringParameter(unsigned vr) {
  switch (vr) {
    case kDriveFile: return &params_.driveFile;
    case kSolverMethod: return &params_.method;
    case kContactMethod: return &params_.contactMethod;
    case kChainJointModel: return &params_.jointModel;
    case kFidelity: return &params_.fidelity;
    default: return nullptr;
  }
}

bool ChainDriveModel::readRealOutput(unsigned vr, double& value) const {
  const RealOutput* output = findRealOutput(vr);
  if (output) value = output->read(OutputView{out_, roles_});
  return output != nullptr;
}

bool ChainDriveModel::readIntegerOutput(unsigned vr, int& value) const {
  if (vr != kContacts) return false;
  value = out_.contacts;
  return true;
}

}  // namespace chaindrive::fmu
