#include "cvt_model.h"

#include <cmath>

#include "cvt/cvt_assembly.h"

namespace chaindrive::fmu {

namespace {

// What a Real output is read from: the shared outputs and the CVT's at the current state.
struct OutputView {
  const Outputs& out;
  const CvtOutputs& cvt;
};

struct RealOutput {
  unsigned vr;
  double (*read)(const OutputView& s);
};

// clang-format off
constexpr RealOutput kRealOutputs[] = {
  {kDrivingPulleyPhi,            [](const OutputView& s) { return s.out.rotorAngle[kDrivingPulley]; }},
  {kDrivingPulleyTau,            [](const OutputView& s) { return s.cvt.drivingTorque; }},
  {kDrivenPulleyPhi,             [](const OutputView& s) { return s.out.rotorAngle[kDrivenPulley]; }},
  {kDrivenPulleyW,               [](const OutputView& s) { return s.cvt.drivenSpeed; }},
  {kDrivenPulleyTau,             [](const OutputView& s) { return s.cvt.drivenTorque; }},
  {kSlip,                        [](const OutputView& s) { return s.cvt.slip; }},
  {kChainFtight,                 [](const OutputView& s) { return s.cvt.tightStrandForce; }},
  {kChainFslack,                 [](const OutputView& s) { return s.cvt.slackStrandForce; }},
  {kDrivingPulleyFclamp,         [](const OutputView& s) { return s.cvt.clampingForce[kDrivingPulley]; }},
  {kDrivenPulleyFclamp,          [](const OutputView& s) { return s.cvt.clampingForce[kDrivenPulley]; }},
  {kPowerLoss,                   [](const OutputView& s) { return s.cvt.powerLoss; }},
  {kPinFn,                       [](const OutputView& s) { return s.cvt.pinNormalForce; }},
  {kPinFfrictionRadial,          [](const OutputView& s) { return s.cvt.pinRadialFriction; }},
  {kPinFfrictionCircumferential, [](const OutputView& s) { return s.cvt.pinCircumferentialFriction; }},
  {kLinkF,                       [](const OutputView& s) { return s.cvt.linkTension; }},
  {kEnergyKinetic,               [](const OutputView& s) { return s.out.energy.kinetic; }},
  {kEnergyElastic,               [](const OutputView& s) { return s.out.energy.elastic; }},
  {kEnergyDissipated,            [](const OutputView& s) { return s.out.energy.dissipated; }},
  {kEnergyInput,                 [](const OutputView& s) { return s.out.energy.inputWork; }},
};
// clang-format on

}  // namespace

// ---- preparation ----

// The CVT from the parameters, assembled at the ratio input of the start time (its sheaves ready
// for the ratio range).
bool CvtChainModel::buildModel() {
  CvtDescription desc = describedBy(params_.cvtFile, "default_cvt.json", "CVT", loadCvtDescription, defaultCvtDescription);
  if (params_.clampingForce >= 0.0) desc.clampingForce = params_.clampingForce;
  const double ratio = in_[kInRatio];
  if (!(ratio >= desc.ratioMin && ratio <= desc.ratioMax)) {
    host_.log(fmi2Error, "logStatusError", "ratio: the input %g is outside the CVT's ratio range [%g, %g] "
              "(pulleys.ratioRange of its description)", ratio, desc.ratioMin, desc.ratioMax);
    return false;
  }
  desc.ratio = ratio;
  model_ = std::make_shared<const Model>(assembleCvt(desc));
  if (params_.linkIndex < -1 || params_.linkIndex >= model_->chain.links) {
    host_.log(fmi2Error, "logStatusError", "link.index = %d is outside 0..%d (or -1: link 0)",
              params_.linkIndex, model_->chain.links - 1);
    return false;
  }
  return choicesCombine(simulationOptions());
}

void CvtChainModel::resetSettings() {
  params_ = Parameters{};
  in_ = kInputStarts;
}

// Every parameter problem is logged (all of them at once); false if there was one.
bool CvtChainModel::parametersValid() {
  std::vector<std::string> problems;
  parseChoiceParameter("solver.method", params_.method, method_, problems);
  checkRange(problems, "solver.tolerance", params_.tolerance, 1e-12, 0.1);
  checkRange(problems, "solver.step", params_.step, 1e-9, 1e-3, "s");
  if (params_.clampingForce > 1e6)
    problems.push_back(outsideRange("clampingForce", params_.clampingForce, 0.0, 1e6, "N") +
                       " (or negative: the CVT description's)");
  for (const auto& p : problems) host_.log(fmi2Error, "logStatusError", "%s", p.c_str());
  return problems.empty();
}

// The solver parameters as the simulation takes them.
SimulationOptions CvtChainModel::simulationOptions() const {
  SimulationOptions opt;
  opt.integrator.method = method_;
  opt.integrator.adaptive.rtol = params_.tolerance;
  opt.integrator.fixed.step = params_.step;
  opt.integrator.adaptive.stopAtOutputs = true;
  opt.monitoredLink = params_.linkIndex;
  return opt;
}

// The simulation from the nominal state at the driving speed input (the chain moving with the
// pulleys, pre-tensioned by the clamping force), on the time grid from the start time.
void CvtChainModel::startSimulation() {
  makeSimulation(simulationOptions());
  sim_->startFrom(host_.time(), cvtNominalState(*model_, in_[kInDrivingSpeed]));
  for (const std::string& note : model_->assembly.notes) host_.log(fmi2OK, "logEvents", "assembly: %s", note.c_str());
  runStarted();
}

void CvtChainModel::applyInputs() {
  if (!held_) return;
  held_->values.crankSpeed = in_[kInDrivingSpeed];
  held_->values.loadTorque[kDrivenPulley] = in_[kInLoadTorque];
  held_->values.ratio = in_[kInRatio];
}

void CvtChainModel::evaluateOutputs() {
  out_ = sim_->outputs();
  cvt_ = cvtOutputs(*model_, *sim_->outputData(), out_, params_.linkIndex);
}

// ---- values by value reference ----

double* CvtChainModel::realSetting(unsigned vr) {
  switch (vr) {
    case kDrivingPulleyW: return &in_[kInDrivingSpeed];
    case kDrivenPulleyTauLoad: return &in_[kInLoadTorque];
    case kSolverTolerance: return &params_.tolerance;
    case kSolverStep: return &params_.step;
    case kRatio: return &in_[kInRatio];
    case kClampingForce: return &params_.clampingForce;
    default: return nullptr;
  }
}

std::string* CvtChainModel::stringParameter(unsigned vr) {
  switch (vr) {
    case kCvtFile: return &params_.cvtFile;
    case kSolverMethod: return &params_.method;
    default: return nullptr;
  }
}

bool CvtChainModel::readRealOutput(unsigned vr, double& value) const {
  for (const RealOutput& o : kRealOutputs)
    if (o.vr == vr) {
      value = o.read(OutputView{out_, cvt_});
      return true;
    }
  return false;
}

// A ratio input outside the prepared CVT's range is an error (before the preparation, prepare()
// checks it against the description).
bool CvtChainModel::inputAcceptable(const Variable& v, double value) {
  if (v.vr != kRatio || !model_) return true;
  const RatioTable& t = model_->ratioTable;
  if (value >= t.lo && value <= t.hi()) return true;
  host_.log(fmi2Error, "logStatusError", "fmi2SetReal: ratio = %g is outside the CVT's ratio range [%g, %g] "
            "(pulleys.ratioRange of its description)", value, t.lo, t.hi());
  return false;
}

bool CvtChainModel::readIntegerOutput(unsigned vr, int& value) const {
  if (vr == kContacts) value = out_.contacts;
  else if (vr == kPinPulley) value = cvt_.pinPulley;
  else return false;
  return true;
}

}  // namespace chaindrive::fmu
