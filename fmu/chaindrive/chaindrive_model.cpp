#include "chaindrive_model.h"

#include <cmath>
#include <filesystem>
#include <optional>
#include <string>

#include "description/drive_description.h"
#include "interface/drive_interface.h"
#include "span/span_model.h"
#include "utf8_path.h"

namespace chaindrive::fmu {

namespace {

constexpr const char* kCalibrationFile = "span_calibration.json";  // in resources/

// The span model's calibration the FMU carries in resources/ (python -m harness export
// --span-calibration), "" when it carries none: then the span fidelity takes the cache's or
// calibrates, as an FMU without the file always did.
std::string carriedCalibration(const std::string& resourceDir) {
  if (resourceDir.empty()) return "";
  const std::string file = resourceDir + "/" + kCalibrationFile;
  std::error_code error;
  return std::filesystem::is_regular_file(utf8Path(file), error) ? file : "";
}

// Where the span model's laws came from (the carried file, the cache, identified now and at what
// cost); a carried file passed over (another key: the parameters changed the drive, or the file
// is of other code) as a warning, since the instance then paid for the calibration.
void logCalibration(Host& host, const span::SpanModel& sm) {
  for (const std::string& note : sm.notes) {
    if (note.rfind("calibration: the file ", 0) == 0) host.log(fmi2Warning, "logStatusWarning", "span %s", note.c_str());
    else if (note.rfind("calibration: key ", 0) == 0 || note.rfind("calibration: engagement laws ", 0) == 0 ||
             note.rfind("calibration: none", 0) == 0)
      host.log(fmi2OK, "logEvents", "span %s", note.c_str());
  }
}

}  // namespace

// ---- the interface ----

bool ChainDriveModel::instantiated(const char* guid) {
  const std::string problem = interface_.load(host_.resourceDir(), guid);
  if (problem.empty()) return true;
  host_.log(fmi2Error, "logStatusError", "fmi2Instantiate: %s", problem.c_str());
  return false;
}

const InterfaceVariable* ChainDriveModel::tableEntry(unsigned vr) const {
  const int i = interface_.at(vr);
  return i >= 0 ? &interface_.table().variables[i] : nullptr;
}

Binding ChainDriveModel::bindingOf(unsigned vr) const {
  const InterfaceVariable* v = tableEntry(vr);
  return v ? v->binding : Binding::SolverTime;
}

// ---- preparation ----

// The drive from the parameters (the file, the tensioner overrides) and its rotors by the
// interface's element names.
bool ChainDriveModel::buildModel() {
  DriveDescription desc = parameterDrive();
  if (!applyTensionerOverrides(desc)) return false;
  model_ = std::make_shared<const Model>(assemble(desc));
  return resolveElements(*model_) && choicesCombine(simulationOptions());
}

// The FMU's own drive, or the file of the parameter driveFile if its interface is this FMU's
// (a drive with the same elements and names: other masses, stiffnesses or geometry).
DriveDescription ChainDriveModel::parameterDrive() {
  if (params_.driveFile.empty()) {
    host_.log(fmi2OK, "logEvents", "drive: %s", interface_.drivePath().c_str());
    return interface_.drive();
  }
  DriveDescription desc = loadDriveDescription(params_.driveFile);
  const std::string mismatch = interfaceMismatch(interface_.table(), desc);
  if (!mismatch.empty())
    throw DescriptionError({"driveFile: '" + params_.driveFile + "' has another interface than this FMU's drive (" +
                            mismatch + "); export an FMU of that drive (python -m harness export --drive FILE)"});
  host_.log(fmi2OK, "logEvents", "drive: %s", params_.driveFile.c_str());
  return desc;
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
  if (params_.threads < 1 || params_.threads > StagePool::kMaxThreads)
    problems.push_back("solver.threads = " + std::to_string(params_.threads) + " is outside 1.." +
                       std::to_string(StagePool::kMaxThreads));
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
  const Binding binding = bindingOf(v.vr);
  if (binding == Binding::SupplyPressure) {
    // gauge: no absolute pressure below zero; above, far beyond any engine's oil gallery
    if (value >= -kAtmosphere && value <= kMaxSupplyPressure) return true;
    host_.log(fmi2Error, "logStatusError", "fmi2SetReal: %s (gauge; the absolute pressure cannot be negative)",
              outsideRange(v.name, value, -kAtmosphere, kMaxSupplyPressure, "Pa").c_str());
    return false;
  }
  if (binding != Binding::CrankSpeed || (value >= 0.0 && value <= kMaxCrankSpeed)) return true;
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

// The model's rotor of every element's variable, the load inputs' rotors, and the monitored
// link's range.
bool ChainDriveModel::resolveElements(const Model& m) {
  if (params_.linkIndex < -1 || params_.linkIndex >= m.chain.links) {
    host_.log(fmi2Error, "logStatusError", "link.index = %d is outside 0..%d (or -1: as in the drive)",
              params_.linkIndex, m.chain.links - 1);
    return false;
  }
  const std::vector<InterfaceVariable>& vars = interface_.table().variables;
  rotorOf_.assign(vars.size(), -1);
  loads_.clear();
  for (std::size_t i = 0; i < vars.size(); ++i) {
    if (vars[i].element.empty()) continue;
    rotorOf_[i] = m.rotorIndex(vars[i].element);
    if (rotorOf_[i] < 0) {  // (the interface was generated from this drive: not reached)
      host_.log(fmi2Error, "logStatusError", "%s: the drive has no rotor '%s'", vars[i].name.c_str(),
                vars[i].element.c_str());
      return false;
    }
    if (vars[i].binding == Binding::LoadTorque) loads_.emplace_back(kInLoads + vars[i].index, rotorOf_[i]);
  }
  return true;
}

// The solver parameters as the simulation takes them; the fixed step the table's for the method
// (startSimulation sets the drive's own, solverStep: the drive's may take probe runs).
SimulationOptions ChainDriveModel::simulationOptions() const {
  SimulationOptions opt;
  opt.fidelity = choices_.fidelity;
  opt.contactMethod = choices_.contacts;
  // solver.method empty and solver.step 0: the fidelity's own (run/defaults.h: the row of runs
  // with joints with clearance or rigid contacts, or not), the step the drive's own
  // (run/drive_defaults.h), as the command-line tools and the harness take them
  const SolverDefaults& own =
      model_ ? ownTableRow(*model_, opt) : solverDefaults(Scene::TimingDrive, opt.fidelity);
  opt.integrator.method = choices_.method.value_or(own.method);
  opt.integrator.adaptive.rtol = params_.tolerance;
  opt.integrator.fixed.step = params_.step > 0.0 ? params_.step : defaultStep(own, opt.integrator.method);
  opt.integrator.newmark.gamma = params_.newmarkGamma;
  opt.integrator.adaptive.stopAtOutputs = true;
  opt.jointModel = choices_.joints;
  opt.preload.enabled = params_.preload;
  opt.monitoredLink = params_.linkIndex;
  opt.threads = params_.threads;
  opt.spanCalibrationFile = carriedCalibration(host_.resourceDir());
  return opt;
}

// The simulation of model_ with the solver parameters, at its start state on the time grid.
void ChainDriveModel::startSimulation() {
  SimulationOptions opt = simulationOptions();
  // the step, once, and why (solver.step 0: the drive's own, run/drive_defaults.h)
  const StepChoice step = defaultStepChoice(*model_, opt, opt.integrator.method,
                                            params_.step > 0.0 ? std::optional<double>(params_.step) : std::nullopt);
  opt.integrator.fixed.step = step.step;
  makeSimulation(opt);
  if (const span::SpanModel* sm = sim_->spanModel()) logCalibration(host_, *sm);
  if (sim_->integratorFixedStep() > 0.0)
    host_.log(fmi2OK, "logEvents", "solver: %s, %s", choiceName(opt.integrator.method), step.reason.c_str());
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
  for (const auto& [slot, rotor] : loads_) v.loadTorque[rotor] = in_[slot];
  v.supplyPressure = in_[kInSupplyPressure];
}

// ---- values by value reference ----

double* ChainDriveModel::realSetting(unsigned vr) {
  const InterfaceVariable* v = tableEntry(vr);
  if (!v) return nullptr;
  switch (v->binding) {
    case Binding::CrankSpeed: return &in_[kInCrankSpeed];
    case Binding::SupplyPressure: return &in_[kInSupplyPressure];
    case Binding::LoadTorque: return &in_[kInLoads + v->index];
    case Binding::OilTemperature: return &params_.oilTemperature;
    case Binding::SolverTolerance: return &params_.tolerance;
    case Binding::SolverStep: return &params_.step;
    case Binding::NewmarkGamma: return &params_.newmarkGamma;
    case Binding::TensionerPreload: return &params_.tensionerPreload;
    case Binding::TensionerStiffness: return &params_.tensionerStiffness;
    case Binding::TensionerDamping: return &params_.tensionerDamping;
    case Binding::TensionerDampingExtension: return &params_.tensionerDampingExtension;
    default: return nullptr;
  }
}

std::string* ChainDriveModel::stringParameter(unsigned vr) {
  switch (bindingOf(vr)) {
    case Binding::DriveFile: return &params_.driveFile;
    case Binding::SolverMethod: return &params_.method;
    case Binding::ContactMethod: return &params_.contactMethod;
    case Binding::JointModel: return &params_.jointModel;
    case Binding::Fidelity: return &params_.fidelity;
    default: return nullptr;
  }
}

bool ChainDriveModel::readRealOutput(unsigned vr, double& value) const {
  const int i = interface_.at(vr);
  if (i < 0) return false;
  const InterfaceVariable& v = interface_.table().variables[i];
  const Outputs& o = out_;
  switch (v.binding) {
    case Binding::RotorAngle: value = o.rotorAngle[rotorOf_[i]]; break;
    case Binding::RotorRate: value = o.rotorRate[rotorOf_[i]]; break;
    case Binding::RotorChainTorque: value = o.rotorTorque[rotorOf_[i]]; break;
    case Binding::CrankTorque: value = o.crankTorque; break;
    case Binding::RotorChainTorqueStepMean: value = o.rotorTorqueStepMean[rotorOf_[i]]; break;
    case Binding::CrankTorqueStepMean: value = o.crankTorqueStepMean; break;
    case Binding::SpanForce: value = o.spanForce[v.index]; break;
    case Binding::TightSpanForce: value = o.tightSpanForce; break;
    case Binding::SlackSpanForce: value = o.slackSpanForce; break;
    case Binding::TensionerForce: value = o.tensionerForce; break;
    case Binding::TensionerStroke: value = o.tensionerStroke; break;
    case Binding::TensionerRate: value = o.tensionerRate; break;
    case Binding::ChamberPressure: value = o.chamberPressure; break;
    case Binding::CheckValveFlow: value = o.tensionerFlows.check; break;
    case Binding::LeakFlow: value = o.tensionerFlows.leak; break;
    case Binding::LinkTension: value = o.linkTension; break;
    case Binding::LinkNormalForce: value = o.linkNormalForce; break;
    case Binding::LinkSprocketForce: value = o.linkSprocketForce; break;
    case Binding::LinkGuideForce: value = o.linkGuideForce; break;
    case Binding::LinkX: value = o.linkPosition.x; break;
    case Binding::LinkY: value = o.linkPosition.y; break;
    case Binding::EnergyKinetic: value = o.energy.kinetic; break;
    case Binding::EnergyElastic: value = o.energy.elastic; break;
    case Binding::EnergyDissipated: value = o.energy.dissipated; break;
    case Binding::EnergyInput: value = o.energy.inputWork; break;
    case Binding::MaxJointDeformation: value = o.maxJointDeformation; break;
    default: return false;
  }
  return true;
}

bool ChainDriveModel::readIntegerOutput(unsigned vr, int& value) const {
  if (bindingOf(vr) != Binding::Contacts) return false;
  value = out_.contacts;
  return true;
}

}  // namespace chaindrive::fmu
