#include "cvt/cvt_run.h"

#include <time.h>

#include <algorithm>
#include <cmath>

#include "cvt/cvt_assembly.h"
#include "run/simulation.h"

namespace chaindrive {

namespace {

double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// The running mean of a quantity over the window's samples.
struct Mean {
  double sum = 0.0;
  int n = 0;
  void add(double v) { sum += v, ++n; }
  double value() const { return n > 0 ? sum / n : std::nan(""); }
};

}  // namespace

// The compliant pins' integrators, in both directions.
constexpr std::pair<CvtMethod, IntegratorMethod> kCvtIntegrators[] = {
    {CvtMethod::FixedVerlet, IntegratorMethod::FixedVerlet},
    {CvtMethod::FixedVerletImplicitJointDamping, IntegratorMethod::FixedVerletImplicitJointDamping},
    {CvtMethod::ArkodeErk, IntegratorMethod::ArkodeErk},
    {CvtMethod::ArkodeErkFixed, IntegratorMethod::ArkodeErkFixed}};

void setCvtMethod(CvtMethod method, CvtRunOptions& run) {
  const bool stepping = method == CvtMethod::TimeStepping || method == CvtMethod::TimeSteppingRigidPins;
  run.contactMethod = stepping ? ContactMethod::TimeStepping : ContactMethod::Compliant;
  run.integrator.rigid.rigidPins = method == CvtMethod::TimeSteppingRigidPins;
  for (const auto& [cvt, integrator] : kCvtIntegrators)
    if (cvt == method) run.integrator.method = integrator;
}

CvtMethod cvtMethodOf(const CvtRunOptions& run) {
  if (run.contactMethod == ContactMethod::TimeStepping)
    return run.integrator.rigid.rigidPins ? CvtMethod::TimeSteppingRigidPins : CvtMethod::TimeStepping;
  for (const auto& [cvt, integrator] : kCvtIntegrators)
    if (integrator == run.integrator.method) return cvt;
  throw std::invalid_argument(std::string("integrator '") + choiceName(run.integrator.method) + "' is not a CVT method");
}

CvtRunResult runCvt(std::shared_ptr<const Model> m, const CvtRunOptions& opt) {
  SimulationOptions so;
  so.integrator = opt.integrator;
  so.contactMethod = opt.contactMethod;
  so.monitoredLink = opt.monitoredLink;
  auto inputs = std::make_unique<HeldInputs>(*m);
  HeldInputs& held = *inputs;
  held.values.crankSpeed = opt.drivingSpeed;
  held.values.loadTorque[kDrivenPulley] = opt.loadTorque;
  Simulation sim(m, so, std::move(inputs));
  const double t0 = opt.start ? opt.start->time : 0.0;
  sim.startFrom(t0, opt.start ? opt.start->y : cvtNominalState(*m, opt.drivingSpeed));
  CvtRunResult r;
  const long long outputs = std::llround(opt.duration / opt.outputStep);
  r.samples.reserve(static_cast<std::size_t>(outputs + 1));
  const double cpu0 = threadCpuSeconds();
  for (long long k = 0; k <= outputs; ++k) {
    if (k > 0) sim.advanceTo(t0 + static_cast<double>(k) * opt.outputStep);
    const Outputs& out = sim.outputs();
    CvtSample s;
    s.time = sim.time();
    s.cvt = cvtOutputs(*m, *sim.outputData(), out, opt.monitoredLink);
    s.energy = out.energy;
    r.samples.push_back(s);
  }
  r.cpuSeconds = threadCpuSeconds() - cpu0;
  r.steps = sim.integratorStats().steps;
  if (const ns::NsStats* cs = sim.contactStats()) r.contactStats = *cs;
  r.end = {sim.time(), sim.state()};
  r.summary = summarizeCvt(*m, r.samples, t0 + opt.statisticsFrom * opt.duration, t0 + opt.duration);
  return r;
}

CvtSummary summarizeCvt(const Model& m, const std::vector<CvtSample>& samples, double from, double to) {
  CvtSummary s;
  s.from = from;
  s.to = to;
  Mean w1, w2, slip, tight, slack, clamp0, clamp1, t1, t2, pins0, pins1;
  const CvtSample* first = nullptr;
  const CvtSample* last = nullptr;
  for (const CvtSample& x : samples) {
    if (x.time < from || x.time > to) continue;
    if (!first) first = &x;
    last = &x;
    const CvtOutputs& c = x.cvt;
    w1.add(c.drivingSpeed), w2.add(c.drivenSpeed), slip.add(c.slip);
    tight.add(c.tightStrandForce), slack.add(c.slackStrandForce);
    clamp0.add(c.clampingForce[0]), clamp1.add(c.clampingForce[1]);
    t1.add(c.drivingTorque), t2.add(c.drivenTorque);
    pins0.add(c.pinsInContact[0]), pins1.add(c.pinsInContact[1]);
  }
  s.drivingSpeed = w1.value(), s.drivenSpeed = w2.value(), s.slip = slip.value();
  s.tightStrandForce = tight.value(), s.slackStrandForce = slack.value();
  s.clampingForce[0] = clamp0.value(), s.clampingForce[1] = clamp1.value();
  s.drivingTorque = t1.value(), s.drivenTorque = t2.value();
  s.pinsInContact[0] = pins0.value(), s.pinsInContact[1] = pins1.value();
  const double r1 = m.pulleys[kDrivingPulley].runningRadius, r2 = m.pulleys[kDrivenPulley].runningRadius;
  s.geometricRatio = r2 / r1;
  s.speedRatio = s.drivingSpeed / s.drivenSpeed;
  s.speedRatioError = s.speedRatio / s.geometricRatio - 1.0;
  s.torqueBalanceDriven = (s.tightStrandForce - s.slackStrandForce) * r2;
  s.torqueBalanceDriving = (s.tightStrandForce - s.slackStrandForce) * r1;
  if (first && last && last != first) {
    // the mean powers from the works over the window (exact, where sampled powers alias the pins' impacts)
    const double span = last->time - first->time, dissipated = last->energy.dissipated - first->energy.dissipated;
    s.powerLoss = dissipated / span;
    s.netInputPower = (last->energy.inputWork - first->energy.inputWork) / span;
    s.energyBalanceError = (last->energy.balance() - first->energy.balance()) / dissipated;
  }
  return s;
}

}  // namespace chaindrive
