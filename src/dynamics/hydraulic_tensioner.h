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
// the pressure never falls below the vapour pressure (cavitation: the chamber's pressure stays at
// that floor while the volume the oil does not fill is vapour; the state p below the floor counts
// that volume, see hydraulicTensioner, so that a cavity collapses before the pressure rises
// again). The check valve is quasi-static (its area a function of the pressure difference; why
// that is a limitation at the top of the engine's frequencies: docs/hydraulic_tensioner.md). The
// functions are pure: the caller holds
// the state (s, ds/dt, p) and integrates it. Every transcendental function is the project's own
// (math/elementary.h), so that the platforms give the same bits.
#pragma once

#include "assembly/chamber_oil.h"
#include "description/hydraulic_tensioner.h"

namespace chaindrive {

/// The flows of the chamber [m3/s], each >= 0: in through the check valve, out through the leak
/// gap (< 0 when the chamber is below the atmosphere) and the relief valve; vapour: the rate at
/// which the vapour volume grows (< 0: collapses) while the chamber cavitates, so that
/// check - leak - relief + vapour = A ds/dt + V/K dp/dt holds at every state (dp/dt of the
/// chamber's pressure: 0 while it cavitates).
struct HydraulicFlows {
  double check = 0.0, leak = 0.0, relief = 0.0, vapour = 0.0;
};

struct HydraulicResult {
  double force = 0.0;          // [N] on the plunger from the chamber and the end stops, >= 0
  double pressureRate = 0.0;   // [Pa/s] dp/dt of the state p
  double pressure = 0.0;       // [Pa] gauge, the chamber's: p, at least the floor (vapour pressure - p_atm)
  double vapourVolume = 0.0;   // [m3] of the cavity while the chamber cavitates (p below the floor)
  HydraulicFlows flows;
  double supplyPower = 0.0;    // [W] p_s Q_check: the power the oil supply gives
  double dissipatedPower = 0.0;  // [W] in the valves and the leak gap
};

/// The chamber's gauge pressure at rest [Pa]: the supply's less the check valve's cracking
/// pressure (the valve just closed; at least 0), the start state of a run.
double chamberRestPressure(const HydraulicTensionerDesc& t, double supplyPressure);
/// The plunger area pi d^2 / 4 [m2].
double plungerArea(const HydraulicTensionerDesc& t);
/// The chamber's volume V0 + A s [m3] at the plunger's extension s [m] (at least a thousandth of V0).
double chamberVolume(const HydraulicTensionerDesc& t, double stroke);
/// Vogel's law: the oil's dynamic viscosity [Pa s] at temperature [K] (within the law's range).
double oilViscosity(const OilDesc& oil, double temperature);
/// The effective bulk modulus [Pa] of the oil with its entrained air at gauge pressure p.
double effectiveBulkModulus(const OilDesc& oil, double pressure);
/// The leak gap's conductance [m3/(s Pa)]: Q_leak = leakConductance * p.
double leakConductance(const HydraulicTensionerDesc& t, double viscosity);
/// The flow [m3/s] through a valve at the pressure difference dp [Pa] across it, in its opening
/// sense; 0 when it is closed or absent (never negative).
double valveFlow(const ValveDesc& v, double dp, double density);
/// The chamber at extension stroke [m], its rate [m/s] and gauge pressure [Pa], with the supply's
/// gauge pressure [Pa] and the oil's viscosity [Pa s]. The state `pressure` is the chamber's
/// gauge pressure down to the floor p_f = vapour pressure - p_atm; below it, it counts the vapour
/// volume (p_f - pressure) V(s) / K(p_f) of a cavitating chamber, whose pressure is p_f
/// (HydraulicResult::pressure). Integrate dp/dt = pressureRate in either case.
HydraulicResult hydraulicTensioner(const HydraulicTensionerDesc& t, double stroke, double rate, double pressure,
                                   double supplyPressure, double viscosity);
/// hydraulicTensioner without the state's rate (pressureRate, vapourVolume and flows.vapour 0):
/// the force, the valves' and the leak's flows and the powers at the chamber's pressure, for a
/// caller whose state is not the pressure (the drive models keep the oil content: assembly/chamber_oil.h).
HydraulicResult hydraulicChamber(const HydraulicTensionerDesc& t, double stroke, double pressure,
                                 double supplyPressure, double viscosity);

}  // namespace chaindrive
