#include "run/simulation.h"

#include <algorithm>
#include <iterator>

#include <cmath>

#include "dynamics/contact_kinematics.h"
#include "dynamics/dynamics.h"
#include "dynamics/health.h"
#include "dynamics/iteration_matrix.h"
#include "dynamics/joint_forces.h"
#include "dynamics/link_loops.h"
#include "dynamics/threaded.h"
#include "run/span_damping.h"
#include "span/calibration_cache.h"
#include "span/span_outputs.h"

namespace chaindrive {

DriveSystem::DriveSystem(std::shared_ptr<const Model> m, const InputSignal& in, const HealthLimits& health)
    : model_(std::move(m)),
      in_(in),
      data_(*model_),
      jac_(*model_),
      iteration_(model_->chain.links),
      linkRhs_(3 * model_->chain.links),
      health_(health) {
  const Model& md = *model_;
  velocityOf_.assign(md.nStates, -1);
  isVelocity_.assign(md.nStates, 0);
  for (int i = 0; i < md.chain.links; ++i)
    for (int k = 0; k < 3; ++k) {
      velocityOf_[md.linkState(i, k)] = md.linkState(i, 3 + k);
      isVelocity_[md.linkState(i, 3 + k)] = 1;
    }
  for (const auto& r : md.rotors)
    if (!r.prescribed) {
      velocityOf_[r.stateAngle] = r.stateRate;
      isVelocity_[r.stateRate] = 1;
    }
}

int DriveSystem::rhs(double t, const double* y, double* ydot) noexcept {
  try {
    if (evaluatesOnThreads(*model_, data_)) forwardCompliantOnThreads(*model_, data_, in_, t, y, ydot);
    else forwardCompliant(*model_, data_, in_, t, y, ydot);
    if (!derivativesOnly_ && !allFinite(ydot, model_->nStates)) {  // (else healthy() checks the state)
      lastError_ = {FailureKind::NonFinite, "non-finite derivative"};
      return 1;  // recoverable: the integrator retries with a smaller step
    }
    return 0;
  } catch (const std::exception& e) {
    lastError_ = {FailureKind::Other, e.what()};
    return -1;
  } catch (...) {
    lastError_ = {FailureKind::Other, "unknown exception in the right-hand side"};
    return -1;
  }
}

int DriveSystem::jacobian(double t, const double* y, double* values) noexcept {
  try {
    jac_.assemble(*model_, data_, in_, t, y, values);
    return 0;
  } catch (const std::exception& e) {
    lastError_ = {FailureKind::Other, e.what()};
    return -1;
  } catch (...) {
    return -1;
  }
}

int DriveSystem::solveStiff(double a, double b, double* r) noexcept {
  const Model& m = *model_;
  linkIterationMatrix(m, data_, a, b, iteration_);
  if (!iteration_.factor()) {
    lastError_ = {FailureKind::NewtonFailure, "the links' iteration matrix is singular"};
    return 1;
  }
  // the ring's unknowns are per link (x, y, gamma); the state holds them component by component
  const double mass[3] = {m.chain.mass, m.chain.mass, m.chain.inertia};
  for (int i = 0; i < m.chain.links; ++i)
    for (int k = 0; k < 3; ++k) linkRhs_[3 * i + k] = mass[k] * r[m.linkState(i, 3 + k)];
  iteration_.solve(linkRhs_.data());
  for (int i = 0; i < m.chain.links; ++i)
    for (int k = 0; k < 3; ++k) r[m.linkState(i, 3 + k)] = linkRhs_[3 * i + k];
  return 0;
}

void DriveSystem::dampedKicks(double a, bool constantPart, double* kick) noexcept {
  const Model& m = *model_;
  for (const RotorModel& r : m.rotors)
    if (r.stateRate >= 0) kick[r.stateRate] = a;  // (rotors and guides: explicit)
  linkDampedKicks(m, data_, a, constantPart, kick);
}

bool DriveSystem::dampOffDiagonal(double a, double* ydot) noexcept {
  const Model& m = *model_;
  if (m.chain.jointClearance > 0.0 || !data_.jointForces) return false;  // (the joints' damping not constant)
  double* accel = ydot + m.linkState(0, Model::kVx);  // (the links' accelerations)
  if (evaluatesOnThreads(m, data_)) jointDampingOnThreads(m, data_, a, accel);
  else jointDampingOffDiagonalLoop(m, data_, a, accel);
  return true;
}

StagePool* DriveSystem::stagePool() { return evaluatesOnThreads(*model_, data_) ? data_.threads.pool : nullptr; }

int DriveSystem::ownerOf(int i) const {
  const int n = model_->chain.links;
  if (i >= 6 * n) return 0;  // (the rotors' and the others' components: the calling thread's)
  const std::vector<ThreadPart>& parts = data_.threads.parts;
  for (std::size_t t = 0; t < parts.size(); ++t)
    for (const LinkRange& r : parts[t].ranges)
      if (i % n >= r.first && i % n < r.last) return static_cast<int>(t);
  return 0;
}

void DriveSystem::toleranceScales(double* scale) const {
  const Model& m = *model_;
  const double linkScale[6] = {1e-3, 1e-3, 1e-1, 1.0, 1.0, 1e2};  // m, m, rad, m/s, m/s, rad/s
  for (int i = 0; i < m.chain.links; ++i)
    for (int k = 0; k < 6; ++k) scale[m.linkState(i, k)] = linkScale[k];
  for (const auto& r : m.rotors) {
    scale[r.stateAngle] = 1e-2;
    if (r.stateRate >= 0) scale[r.stateRate] = 10.0;
  }
  scale[m.stateInputWork] = 1.0;
  scale[m.stateDissipated] = 1.0;
  if (m.stateChamberOil >= 0) scale[m.stateChamberOil] = chamberOilScale(m.tensioner.hydraulic);
  impulseToleranceScales(m.chainImpulse, static_cast<int>(m.rotors.size()), scale);
}

bool DriveSystem::healthy(double t, const double* y, Failure& why) noexcept {
  // cheap enough for every fixed step: finiteness of the state, and the joint deformations and
  // deepest gap of the last right-hand-side evaluation (at or next to this state)
  const Model& m = *model_;
  if (!finiteState(y, m.nStates, why)) return false;
  if (m.stateChamberOil >= 0 && !chamberFilled(y[m.stateChamberOil], t, why)) return false;
  const bool jointsOk = jointsWithin(m, data_, health_.blowUpDeformation * m.chain.pitch);
  if (jointsOk && !(data_.deepestGap < -health_.tunnellingDepth * m.chain.depthScale)) return true;
  // beyond a limit: named from the contacts listed (evaluated again where they were not: the
  // same positions, so the same gaps) and the joints measured
  if (!data_.listContacts) {
    try {
      data_.listContacts = true;
      generalizedForces(m, data_, in_, t, y);
    } catch (...) {
    }
    data_.listContacts = false;
  }
  if (jointsOk)
    return !deepPenetration(data_.contacts.data(), data_.nContacts, health_.tunnellingDepth * m.chain.depthScale, t, why);
  measureJoints(m, data_);  // some joint is opened too far: which, and by how much
  return chainHealthy(m, health_, [&](int j) { return data_.joints.deformation[j]; }, data_.contacts.data(),
                      data_.nContacts, t, why);
}

namespace {

bool runsOnPulleys(IntegratorMethod m) {
  return std::find(std::begin(kPulleyIntegrators), std::end(kPulleyIntegrators), m) != std::end(kPulleyIntegrators);
}

std::string pulleyIntegratorNames() {
  std::vector<std::string> names;
  for (IntegratorMethod m : kPulleyIntegrators) names.emplace_back(choiceName(m));
  return listOfNames(names);
}

std::string quoted(const char* name) { return "'" + std::string(name) + "'"; }

// The span fidelity has spans, no contacts, and takes its span stiffness from journal bearings;
// its implicit part is not the links' joints and contacts.
void spanProblems(const RunChoices& c, std::vector<ChoiceProblem>& problems) {
  if (c.contacts != ContactMethod::Compliant)
    problems.push_back({RunChoice::ContactMethod, quoted(choiceName(c.contacts)) + " does not apply to fidelity "
                        "'span' (its chain has spans, not contacts); allowed with it: compliant"});
  if (c.joints != JointModel::JournalBearing)
    problems.push_back({RunChoice::JointModel, quoted(choiceName(c.joints)) + " does not apply to fidelity 'span' "
                        "(its spans take their stiffness from journal bearings); allowed with it: journal-bearing"});
  if (c.method == IntegratorMethod::FixedNewmark || c.method == IntegratorMethod::FixedVerletImplicitDamping ||
      c.method == IntegratorMethod::FixedVerletImplicitJointDamping)
    problems.push_back({RunChoice::Integrator, quoted(choiceName(c.method)) + " does not apply to fidelity 'span' "
                        "(its implicit part is the links' joints and contacts); allowed with it: the other methods"});
}

// A CVT's pin-sheave contacts (dynamics/pin_sheave.h) have a force law and, for time stepping, the
// friction as a constraint; no acceleration-level formulation (event driven), Jacobian or
// damping rates yet, so the methods that need one are refused.
void pulleyProblems(const RunChoices& c, std::vector<ChoiceProblem>& problems) {
  if (c.fidelity != Fidelity::Link)
    problems.push_back({RunChoice::Fidelity, "'span': a CVT has the link fidelity only"});
  if (c.contacts == ContactMethod::EventDriven)
    problems.push_back({RunChoice::ContactMethod, "'event-driven': a CVT's pins have a compliant normal (allowed: "
                        "compliant, time-stepping)"});
  if (c.contacts == ContactMethod::Compliant && !runsOnPulleys(c.method))
    problems.push_back({RunChoice::Integrator, quoted(choiceName(c.method)) + " needs the contacts' Jacobian or "
                        "damping rates, which a CVT's pin-sheave contacts do not give; allowed on a CVT: " +
                        pulleyIntegratorNames()});
}

}  // namespace

RunChoices runChoices(const Model& m, const SimulationOptions& opt) {
  return {opt.fidelity, opt.contactMethod.value_or(m.description.contact.method),
          opt.jointModel.value_or(m.description.chain.joint.model), opt.integrator.method,
          opt.integrator.rigid.rigidPins};
}

const SolverDefaults& ownTableRow(const Model& m, const SimulationOptions& opt) {
  const bool rigid = opt.contactMethod.value_or(m.description.contact.method) != ContactMethod::Compliant;
  return solverDefaults(Scene::TimingDrive, opt.fidelity, m.chain.jointClearance > 0.0 || rigid);
}

SolverDefaults ownSolverDefaults(const Model& m, const SimulationOptions& opt) {
  return driveRow(m, ownTableRow(m, opt)).row;
}

StepChoice defaultStepChoice(const Model& m, const SimulationOptions& opt, IntegratorMethod method,
                             std::optional<double> given) {
  return chooseStep(m, ownTableRow(m, opt), method, given);
}

std::vector<ChoiceProblem> combinationProblems(const Model& m, const RunChoices& c) {
  std::vector<ChoiceProblem> problems;
  if (c.fidelity == Fidelity::Span) spanProblems(c, problems);
  if (!m.pulleys.empty()) pulleyProblems(c, problems);
  if (c.fidelity == Fidelity::Link && c.contacts == ContactMethod::Compliant && c.joints == JointModel::Ideal)
    problems.push_back({RunChoice::JointModel, "'ideal' needs a rigid-contact method (event-driven or "
                        "time-stepping); with compliant contacts use journal-bearing joints"});
  if (c.contacts == ContactMethod::EventDriven && m.tensioner.hydraulicChamber())
    problems.push_back({RunChoice::ContactMethod, "'event-driven' does not integrate a hydraulic tensioner's chamber; "
                        "use time-stepping or compliant, or the drive's tensioner.model spring-damper"});
  if (c.rigidPins && m.pulleys.empty())
    problems.push_back({RunChoice::RigidPins, "are a chain CVT's option; this drive has no pulleys"});
  return problems;
}

Simulation::Simulation(std::shared_ptr<const Model> model, const SimulationOptions& opt,
                       std::unique_ptr<InputSignal> inputs)
    : model_(std::move(model)), options_(opt), inputs_(std::move(inputs)) {
  const RunChoices choices = runChoices(*model_, options_);
  contactMethod_ = choices.contacts;
  constexpr const char* kChoiceWords[] = {"fidelity", "contact method", "joint model", "integrator", "rigid pins"};
  std::string refused;
  for (const auto& p : combinationProblems(*model_, choices))
    refused += (refused.empty() ? "" : "; ") + std::string(kChoiceWords[static_cast<int>(p.choice)]) + " " + p.text;
  if (!refused.empty()) throw std::invalid_argument(refused);
  if (options_.threads != 1 && (options_.fidelity != Fidelity::Link || contactMethod_ != ContactMethod::Compliant))
    throw std::invalid_argument("solver.threads = " + std::to_string(options_.threads) +
                                ": several threads run the link model with compliant contacts only; allowed: 1");
  if (options_.fidelity == Fidelity::Link) buildLinkModel(choices.joints);
  else buildSpanModel();
  const double step = integrator_->fixedStep();
  grid_.unit = step > 0.0 ? step : kAdaptiveTimeQuantum;
}

// The link-by-link model with compliant or rigid contacts.
void Simulation::buildLinkModel(JointModel joints) {
  if (contactMethod_ == ContactMethod::Compliant) {
    system_ = std::make_unique<DriveSystem>(model_, *inputs_, options_.health);
    integrator_ = makeIntegrator(*system_, options_.integrator);
    startThreads();
  } else {
    rigid_ = std::make_shared<RigidContactDrive>(model_, *inputs_, joints == JointModel::Ideal, options_.health,
                                                 options_.integrator.rigid.rigidPins);
    auto ri = std::make_unique<RigidIntegrator>(rigid_, contactMethod_, options_.integrator);
    rigidIntegrator_ = ri.get();
    integrator_ = std::move(ri);
    outData_ = std::make_unique<Data>(*model_);
  }
  y_.assign(model_->nStates, 0.0);
}

// The pool of the options' threads, its stages the system's evaluations (a run they cannot split
// refused by name, not run on one thread unannounced).
void Simulation::startThreads() {
  const int n = options_.threads;
  if (n == 1) return;
  const std::string setting = "solver.threads = " + std::to_string(n);
  if (n < 1 || n > StagePool::kMaxThreads)
    throw std::invalid_argument(setting + ": allowed 1 to " + std::to_string(StagePool::kMaxThreads));
  if (!splitsEvaluations(*model_, system_->data()))
    throw std::invalid_argument(setting + ": several threads run the link model with compliant contacts, journal-bearing "
                                "joints and a method that reads only derivatives (fixed-verlet, "
                                "fixed-verlet-implicit-joint-damping), not " + std::string(integratorName()) +
                                (model_->pulleys.empty() ? "" : " on a drive with pulleys") + "; allowed: 1");
  pool_ = std::make_unique<StagePool>(n);
  system_->data().useThreads(*model_, pool_.get());
}

// The span model: no contacts (the chain is spans), its stiffness from the journal bearings, its
// spans' laws from the options' calibration file, the cache or the link model's statics.
void Simulation::buildSpanModel() {
  if (options_.spanModel) {
    spanModel_ = options_.spanModel;
  } else {
    auto sm = std::make_shared<span::SpanModel>(span::assembleSpanModel(*model_, false));
    span::calibrateSpanModel(*sm, options_.spanCalibrationFile);
    calibrateSpanDamping(model_, *sm);
    spanModel_ = sm;
  }
  spanSystem_ = std::make_unique<span::SpanSystem>(*spanModel_, *inputs_, options_.health);
  integrator_ = makeIntegrator(*spanSystem_, options_.integrator);
  outSpanData_ = std::make_unique<span::SpanData>(*spanModel_);
  y_.assign(spanModel_->nStates, 0.0);
}

long long Simulation::rhsEvaluations() const {
  if (spanSystem_) return spanSystem_->data().rhsEvaluations;
  return system_ ? system_->data().rhsEvaluations : rigidIntegrator_->contactStats().rhsEvaluations;
}

void Simulation::start(double t0) {
  InputValues v;
  v.loadTorque.assign(model_->rotors.size(), 0.0);
  inputs_->evaluate(t0, v);
  y_ = spanModel_ ? span::spanInitialState(*spanModel_, v, options_.preload, preload_)
                 : initialState(*model_, v, options_.preload, preload_);
  startFrom(t0, y_);
}

void Simulation::startFrom(double t0, const std::vector<double>& y) {
  grid_.start = t0;
  restoreAt(0, y);
}

void Simulation::restoreAt(long long k, const std::vector<double>& y) {
  y_ = y;
  k_ = k;
  integrator_->reset(time(), y_.data());
}

void Simulation::restart(double initialStep) {
  const ImpulseStates& impulse = spanModel_ ? spanModel_->chainImpulse : model_->chainImpulse;
  std::fill(y_.begin() + impulse.first, y_.begin() + impulse.time + 1, 0.0);  // the step means start over
  integrator_->setInitialStep(initialStep);
  integrator_->reset(time(), y_.data());
}

double Simulation::advanceTo(double t) {
  if (!grid_.reaches(t))
    throw std::invalid_argument("time " + std::to_string(t) + " s is beyond the range of the time grid");
  const long long target = grid_.indexOf(t);
  if (target > k_) {
    try {
      integrator_->advance(grid_.time(target), y_.data());
    } catch (const IntegrationError& e) {
      const FailureKind kind = e.failureKind();
      const double step = integrator_->fixedStep();
      if (!(step > 0.0) || !options_.blowUpAdvice ||
          (kind != FailureKind::BlowUp && kind != FailureKind::Tunnelling && kind != FailureKind::NonFinite))
        throw;
      throw IntegrationError(e.time(), kind, e.reason() + "; " + blowUpAdvice(step));
    }
    k_ = target;
  }
  return time();
}

// The drive's stable step for this run's method: a CVT's row for a drive with pulleys; on a timing
// drive rigid contacts take the row of rigid contacts whatever the integrator, compliant ones the
// row whose step the method takes.
std::string Simulation::blowUpAdvice(double step) const {
  const Model& m = *model_;
  const SolverDefaults& stable = !m.pulleys.empty() ? solverDefaults(Scene::Cvt)
                                 : contactMethod_ != ContactMethod::Compliant
                                     ? solverDefaults(Scene::TimingDrive, options_.fidelity, true)
                                     : defaultStepRow(ownTableRow(m, options_), options_.integrator.method);
  try {
    return stepAdvice(m, stable, step, options_.stepName);
  } catch (const DescriptionError& e) {  // (no estimate: the failure stands alone, in one line)
    std::string why;
    for (const std::string& p : e.problems()) why += (why.empty() ? "" : "; ") + p;
    return "no stable step estimated (" + why + ")";
  } catch (const std::exception& e) {
    return std::string("no stable step estimated (") + e.what() + ")";
  }
}

const Outputs& Simulation::outputs() {
  if (spanModel_) {
    span::computeSpanOutputs(*spanModel_, *outSpanData_, *inputs_, time(), y_.data(), options_.monitoredLink, out_);
  } else if (rigidIntegrator_) {
    rigidIntegrator_->contactPoints(rigidContacts_);
    RigidForces rf;
    rf.contacts = &rigidContacts_;
    if (rigid_->idealJoints()) rf.joints = &rigidIntegrator_->jointForces();
    computeOutputs(*model_, *outData_, *inputs_, time(), y_.data(), options_.monitoredLink, out_, &rf);
  } else {
    // in the system's own work area, whose search windows and hints fit this state (four times
    // cheaper than a cold one at every 0.1 ms); not counted among the integrator's evaluations
    Data& d = system_->data();
    const long long evaluations = d.rhsEvaluations;
    computeOutputs(*model_, d, *inputs_, time(), y_.data(), options_.monitoredLink, out_);
    d.rhsEvaluations = evaluations;
  }
  return out_;
}

}  // namespace chaindrive
