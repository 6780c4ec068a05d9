#include "dynamics/hydraulic_tensioner.h"

#include <algorithm>
#include <cmath>

#include "math/elementary.h"
#include "math/vec2.h"

namespace chaindrive {

namespace {

// The chamber never shrinks below this fraction of its nominal volume (the end stop holds the
// plunger long before; the guard keeps K / V finite if a caller drives it through the stop).
constexpr double kMinVolumeFraction = 1e-3;

// The gauge pressure of the cavitation floor.
double floorPressure(const OilDesc& oil) { return oil.vapourPressure - oil.atmosphericPressure; }

// The end stops' force on the plunger [N]: a one-sided spring beyond either stop, pushing back
// into the stroke range (positive: extending).
double endStopForce(const HydraulicTensionerDesc& t, double stroke) {
  if (stroke < t.strokeMin) return t.endStopStiffness * (t.strokeMin - stroke);
  if (stroke > t.strokeMax) return -t.endStopStiffness * (stroke - t.strokeMax);
  return 0.0;
}

}  // namespace

double plungerArea(const HydraulicTensionerDesc& t) { return 0.25 * kPi * t.plungerDiameter * t.plungerDiameter; }

double chamberVolume(const HydraulicTensionerDesc& t, double stroke) {
  return std::max(t.chamberVolume + plungerArea(t) * stroke, kMinVolumeFraction * t.chamberVolume);
}

double chamberRestPressure(const HydraulicTensionerDesc& t, double supplyPressure) {
  const double open = t.checkValve.present ? t.checkValve.crackingPressure : 0.0;
  return std::max(0.0, supplyPressure - open);
}

double oilViscosity(const OilDesc& oil, double temperature) {
  return oil.vogelA * math::exp(oil.vogelB / (temperature - oil.vogelC));
}

// The mixture of the oil and its free air (assembly/chamber_oil.h): K_eff = (1 + a) / (1 / K + a / (n p_abs)).
double effectiveBulkModulus(const OilDesc& oil, double pressure) {
  if (oil.airFraction <= 0.0) return oil.bulkModulus;
  const FreeAir a = freeAir(oil, pressure);
  return (1.0 + a.perOil) / (1.0 / oil.bulkModulus + a.perOil / (oil.polytropicExponent * a.absolutePressure));
}

// Laminar flow through the annular gap of an eccentric plunger: pi d h^3 / (12 mu L) (1 + 1.5 e^2).
double leakConductance(const HydraulicTensionerDesc& t, double viscosity) {
  const double h = t.clearance, e = t.eccentricity;
  return kPi * t.plungerDiameter * h * h * h / (12.0 * viscosity * t.guideLength) * (1.0 + 1.5 * e * e);
}

// Closed up to the cracking pressure, the area then linear in the excess up to maxArea; the
// orifice law Cd A sqrt(2 dp / rho), below laminarPressure its secant Cd A sqrt(2 p_l / rho) dp / p_l
// (equal at p_l, so the flow is continuous and Lipschitz down to dp = 0).
double valveFlow(const ValveDesc& v, double dp, double density) {
  if (!v.present || dp <= v.crackingPressure) return 0.0;
  const double excess = dp - v.crackingPressure;
  const double area = excess >= v.fullLiftPressure ? v.maxArea : v.maxArea * excess / v.fullLiftPressure;
  if (dp >= v.laminarPressure) return v.dischargeCoefficient * area * std::sqrt(2.0 * dp / density);
  return v.dischargeCoefficient * area * std::sqrt(2.0 * v.laminarPressure / density) * (dp / v.laminarPressure);
}

HydraulicResult hydraulicChamber(const HydraulicTensionerDesc& t, double stroke, double pressure,
                                 double supplyPressure, double viscosity) {
  const OilDesc& oil = t.oil;
  const double p = std::max(pressure, floorPressure(oil));  // a step may end a hair below the floor
  HydraulicResult r;
  r.flows.check = valveFlow(t.checkValve, supplyPressure - p, oil.density);
  r.flows.leak = leakConductance(t, viscosity) * p;
  r.flows.relief = valveFlow(t.reliefValve, p, oil.density);  // to the atmosphere
  r.pressure = p;
  r.force = std::max(0.0, p * plungerArea(t) + endStopForce(t, stroke));
  r.supplyPower = supplyPressure * r.flows.check;
  r.dissipatedPower = r.flows.check * (supplyPressure - p) + r.flows.leak * p + r.flows.relief * p;
  return r;
}

HydraulicResult hydraulicTensioner(const HydraulicTensionerDesc& t, double stroke, double rate, double pressure,
                                   double supplyPressure, double viscosity) {
  const OilDesc& oil = t.oil;
  const double area = plungerArea(t);
  const double volume = chamberVolume(t, stroke);
  const double floor = floorPressure(oil);
  HydraulicResult r = hydraulicChamber(t, stroke, pressure, supplyPressure, viscosity);
  const double p = r.pressure;
  const double net = r.flows.check - r.flows.leak - r.flows.relief - area * rate;
  if (pressure > floor) {
    r.pressureRate = effectiveBulkModulus(oil, p) / volume * net;
  } else {
    // Cavitating: the chamber's pressure stays at the floor and the volume the oil does not fill
    // is vapour; the state below the floor counts that volume, V_vap = (floor - state) V / K_f
    // (K_f the modulus at the floor), so that a cavity first collapses before the pressure rises
    // (no oil is made). dV_vap/dt = -net gives the state's rate, equal to the oil's at the floor
    // (an adaptive integrator's error control fails on a jump there).
    const double kFloor = effectiveBulkModulus(oil, floor);
    r.flows.vapour = -net;
    r.vapourVolume = (floor - pressure) * volume / kFloor;
    r.pressureRate = (kFloor * net + (floor - pressure) * area * rate) / volume;
  }
  return r;
}

}  // namespace chaindrive
