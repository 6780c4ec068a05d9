// (provisional: replaced by the device's implementation)
#include "dynamics/hydraulic_tensioner.h"

#include <algorithm>
#include <cmath>

#include "math/elementary.h"

namespace chaindrive {

double chamberRestPressure(const HydraulicTensionerDesc& t, double supplyPressure) {
  return std::max(0.0, supplyPressure - t.checkValve.crackingPressure);
}

double plungerArea(const HydraulicTensionerDesc& t) { return 0.25 * 3.14159265358979323846 * t.plungerDiameter * t.plungerDiameter; }

double oilViscosity(const OilDesc& oil, double temperature) {
  return oil.vogelA * math::exp(oil.vogelB / (temperature - oil.vogelC));
}

double effectiveBulkModulus(const OilDesc& oil, double pressure) {
  const double pAbs = std::max(oil.vapourPressure, oil.atmosphericPressure + pressure);
  const double air = oil.airFraction * oil.atmosphericPressure / pAbs;  // isothermal
  return (1.0 + air) / (1.0 / oil.bulkModulus + air / pAbs);
}

namespace {
double valveFlow(const ValveDesc& v, double dp, double rho) {
  if (!v.present || dp <= v.crackingPressure) return 0.0;
  const double lift = std::min(1.0, (dp - v.crackingPressure) / v.fullLiftPressure);
  const double area = v.maxArea * lift;
  if (dp < v.laminarPressure) return v.dischargeCoefficient * area * std::sqrt(2.0 / rho / v.laminarPressure) * dp;
  return v.dischargeCoefficient * area * std::sqrt(2.0 * dp / rho);
}
}  // namespace

HydraulicResult hydraulicTensioner(const HydraulicTensionerDesc& t, double stroke, double rate, double pressure,
                                   double supplyPressure, double viscosity) {
  HydraulicResult r;
  const double area = plungerArea(t);
  const double h = t.clearance;
  r.flows.leak = 3.14159265358979323846 * t.plungerDiameter * h * h * h / (12.0 * viscosity * t.guideLength) *
                 (1.0 + 1.5 * t.eccentricity * t.eccentricity) * pressure;
  r.flows.check = valveFlow(t.checkValve, supplyPressure - pressure, t.oil.density);
  r.flows.relief = valveFlow(t.reliefValve, pressure, t.oil.density);
  const double volume = std::max(0.01 * t.chamberVolume, t.chamberVolume + area * stroke);
  r.pressureRate = effectiveBulkModulus(t.oil, pressure) / volume *
                   (r.flows.check - r.flows.leak - r.flows.relief - area * rate);
  const double floor = t.oil.vapourPressure - t.oil.atmosphericPressure;
  if (pressure <= floor && r.pressureRate < 0.0) r.pressureRate = 0.0;
  double stops = 0.0;
  if (stroke < t.strokeMin) stops = t.endStopStiffness * (t.strokeMin - stroke);
  if (stroke > t.strokeMax) stops = -t.endStopStiffness * (stroke - t.strokeMax);
  r.pressure = std::max(floor, pressure);
  r.force = std::max(0.0, r.pressure * area + stops);
  r.supplyPower = supplyPressure * r.flows.check;
  r.dissipatedPower = (supplyPressure - pressure) * r.flows.check + pressure * (r.flows.leak + r.flows.relief);
  return r;
}

}  // namespace chaindrive
