#include "rig/tensioner_rig.h"

#include <cmath>
#include <stdexcept>

#include "math/elementary.h"
#include "math/vec2.h"

namespace chaindrive {

namespace {

// The state after the pressure: the volumes that flowed (check, leak, relief). (The vapour's
// volume is a function of the state; its flow jumps where the chamber starts to cavitate, and
// integrated it would stall an adaptive method's error control there.)
constexpr int kVolumes = 3;

}  // namespace

TensionerRig::TensionerRig(const RigSetup& setup)
    : setup_(setup), device_(setup.tensioner), first_(setup.test == RigTest::LeakDown ? 2 : 0) {
  if (setup.test == RigTest::LeakDown) device_.checkValve.present = false;  // the supply closed
  const OilDesc& oil = device_.oil;
  const double temperature = device_.oilTemperature;
  if (!(temperature >= oil.temperatureMin && temperature <= oil.temperatureMax))
    throw std::invalid_argument("oil temperature " + std::to_string(temperature) + " K is outside the viscosity law's range [" +
                                std::to_string(oil.temperatureMin) + ", " + std::to_string(oil.temperatureMax) + "] K");
  if (setup.test == RigTest::Loop && !(setup.frequency > 0.0))
    throw std::invalid_argument("the loop's frequency must be positive");
  viscosity_ = oilViscosity(oil, temperature);
}

void TensionerRig::motion(double t, const double* y, double& stroke, double& rate) const {
  if (first_ == 2) {
    stroke = y[0];
    rate = y[1];
    return;
  }
  const double omega = 2.0 * kPi * setup_.frequency;
  stroke = setup_.mean + setup_.amplitude * math::sin(omega * t);
  rate = setup_.amplitude * omega * math::cos(omega * t);
}

int TensionerRig::rhs(double t, const double* y, double* ydot) noexcept {
  double stroke = 0.0, rate = 0.0;
  motion(t, y, stroke, rate);
  const double p = y[first_];
  const HydraulicResult r = hydraulicTensioner(device_, stroke, rate, p, device_.supplyPressure, viscosity_);
  if (first_ == 2) {
    ydot[0] = rate;
    ydot[1] = (r.force - setup_.force) / device_.plungerMass;
  }
  ydot[first_] = r.pressureRate;
  double* dv = ydot + first_ + 1;
  dv[0] = r.flows.check;
  dv[1] = r.flows.leak;
  dv[2] = r.flows.relief;
  for (int i = 0; i < size(); ++i)
    if (!std::isfinite(ydot[i])) {
      error_ = {FailureKind::NonFinite, "derivative " + std::to_string(i) + " is not finite at t = " + std::to_string(t)};
      return 1;
    }
  return 0;
}

// The error that matters: a micrometre of stroke, a millimetre per second, a kilopascal, and a
// thousandth of the volume the plunger sweeps over a millimetre.
void TensionerRig::toleranceScales(double* scale) const {
  if (first_ == 2) {
    scale[0] = 1e-6;
    scale[1] = 1e-3;
  }
  scale[first_] = 1e3;
  for (int i = 1; i <= kVolumes; ++i) scale[first_ + i] = 1e-3 * plungerArea(device_) * 1e-3;
}

bool TensionerRig::healthy(double t, const double* y, Failure& why) noexcept {
  for (int i = 0; i < size(); ++i)
    if (!std::isfinite(y[i])) {
      why = {FailureKind::NonFinite, "state " + std::to_string(i) + " is not finite at t = " + std::to_string(t)};
      return false;
    }
  return true;
}

std::vector<double> TensionerRig::initialState() const {
  std::vector<double> y(size(), 0.0);  // (leak-down: at rest at the nominal stroke)
  double p = setup_.initialPressure;
  if (std::isnan(p))
    p = first_ == 2 ? setup_.force / plungerArea(device_) : device_.supplyPressure - device_.checkValve.crackingPressure;
  y[first_] = p;
  return y;
}

RigSample TensionerRig::sample(double t, const double* y) const {
  RigSample s;
  s.time = t;
  motion(t, y, s.stroke, s.rate);
  s.device = hydraulicTensioner(device_, s.stroke, s.rate, y[first_], device_.supplyPressure, viscosity_);
  s.pressure = s.device.pressure;
  const double* v = y + first_ + 1;
  s.volumeCheck = v[0];
  s.volumeLeak = v[1];
  s.volumeRelief = v[2];
  s.volumeVapour = s.device.vapourVolume;  // (none at the start: the chamber starts filled)
  return s;
}

std::vector<RigSample> runRig(const RigSetup& setup, const IntegratorSettings& settings, double duration,
                              double outputStep) {
  if (!(outputStep > 0.0) || !(duration >= 0.0)) throw std::invalid_argument("the rig needs a positive output step");
  TensionerRig rig(setup);
  auto integrator = makeIntegrator(rig, settings);
  std::vector<double> y = rig.initialState();
  integrator->reset(0.0, y.data());
  const long long n = static_cast<long long>(std::floor(duration / outputStep + 0.5));
  std::vector<RigSample> samples;
  samples.reserve(static_cast<std::size_t>(n + 1));
  samples.push_back(rig.sample(0.0, y.data()));
  for (long long k = 1; k <= n; ++k) {
    const double t = static_cast<double>(k) * outputStep;
    integrator->advance(t, y.data());
    samples.push_back(rig.sample(t, y.data()));
  }
  return samples;
}

}  // namespace chaindrive
