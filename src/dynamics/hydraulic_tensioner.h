// A hydraulic chain tensioner: the chamber's pressure and flows and the force on the plunger.
// With s the plunger's extension from its nominal stroke, A the plunger area, V(s) = V0 + A s the
// chamber volume and p the chamber's gauge pressure:
//
//   dp/dt = K(p) / V(s) (Q_check - Q_leak - Q_relief - A ds/dt)
//   F     = p A + F_endstops   (the plunger spring is the tensioner's preload and rate)
//
// Q_leak: laminar flow through the annular clearance h of a plunger of diameter d and gap length
// L, pi d h^3 / (12 mu L) (1 + 1.5 e^2) p; Q_check from the supply (gauge p_s) through the check
// valve when p_s - p exceeds its cracking pressure, never backwards; Q_relief out when p exceeds
// the relief valve's cracking pressure; K(p) the bulk modulus of the oil with its entrained air;
// p never falls below the vapour pressure (cavitation). The functions are pure: the caller holds
// the state (s, ds/dt, p) and integrates it. Every transcendental function is the project's own
// (math/elementary.h), so that the platforms give the same bits.
#pragma once

#include "description/hydraulic_tensioner.h"

namespace chaindrive {

/// The flows of the chamber [m3/s], each >= 0: in through the check valve, out through the leak
/// gap (< 0 when the chamber is below the atmosphere) and the relief valve.
struct HydraulicFlows {
  double check = 0.0, leak = 0.0, relief = 0.0;
};

struct HydraulicResult {
  double force = 0.0;          // [N] on the plunger from the chamber and the end stops, >= 0
  double pressureRate = 0.0;   // [Pa/s] dp/dt of the state p
  double pressure = 0.0;       // [Pa] gauge, the chamber's: p, at least the floor (vapour pressure - p_atm)
  HydraulicFlows flows;
  double supplyPower = 0.0;    // [W] p_s Q_check: the power the oil supply gives
  double dissipatedPower = 0.0;  // [W] in the valves and the leak gap
};

/// The chamber's gauge pressure at rest [Pa]: the supply's less the check valve's cracking
/// pressure (the valve just closed; at least 0), the start state of a run.
double chamberRestPressure(const HydraulicTensionerDesc& t, double supplyPressure);
/// The plunger area pi d^2 / 4 [m2].
double plungerArea(const HydraulicTensionerDesc& t);
/// Vogel's law: the oil's dynamic viscosity [Pa s] at temperature [K] (within the law's range).
double oilViscosity(const OilDesc& oil, double temperature);
/// The effective bulk modulus [Pa] of the oil with its entrained air at gauge pressure p.
double effectiveBulkModulus(const OilDesc& oil, double pressure);
/// The chamber at extension stroke [m], its rate [m/s] and gauge pressure [Pa], with the supply's
/// gauge pressure [Pa] and the oil's viscosity [Pa s].
HydraulicResult hydraulicTensioner(const HydraulicTensionerDesc& t, double stroke, double rate, double pressure,
                                   double supplyPressure, double viscosity);

}  // namespace chaindrive
