// The parameters of a hydraulic chain tensioner, as the drive description gives them (SI units,
// pressures gauge, relative to the atmosphere, unless named absolute): a plunger on an oil chamber
// fed from the engine's oil gallery through a check valve, leaking down through the plunger's
// annular clearance, with a relief valve and end stops. The device's equations:
// dynamics/hydraulic_tensioner.h; the schema and the sources of the defaults: docs/hydraulic_tensioner.md.
#pragma once

#include "choice.h"

namespace chaindrive {

/// The tensioner's force law: the spring-damper law (preload, rate, damping retracting and
/// extending) or the hydraulic device.
enum class TensionerKind { SpringDamper, Hydraulic };
template <>
struct ChoiceNames<TensionerKind> {
  static constexpr ChoiceName<TensionerKind> table[] = {{TensionerKind::SpringDamper, "spring-damper"},
                                                        {TensionerKind::Hydraulic, "hydraulic"}};
};

/// Engine oil: dynamic viscosity over temperature by Vogel's law mu(T) = a exp(b / (T - c)),
/// valid for T in [temperatureMin, temperatureMax]; the mixture with entrained air.
struct OilDesc {
  // The defaults: an SAE 5W-30 engine oil (Vogel's constants fitted to 40, 100 and 150 C, see
  // docs/hydraulic_tensioner.md for every default's source or "estimate").
  double vogelA = 4.6735e-6;         // [Pa s]
  double vogelB = 2340.37;           // [K]
  double vogelC = 61.113;            // [K]
  double temperatureMin = 293.15;    // [K] the law's range (20 C)
  double temperatureMax = 423.15;    // [K] (150 C)
  double density = 850.0;            // [kg/m3]
  double bulkModulus = 1.2e9;        // [Pa] of the pure oil (warm)
  double airFraction = 0.005;        // volume fraction of free air at atmospheric pressure
  double polytropicExponent = 1.4;   // of the entrained air's compression (1: isothermal)
  double atmosphericPressure = 1.01325e5;  // [Pa] absolute: the gauge pressures' zero (not a field)
  double vapourPressure = 2e3;       // [Pa] absolute: the chamber's floor (cavitation)
};

/// A spring-loaded valve as an orifice: closed below its cracking pressure difference, its area
/// growing linearly to maxArea at fullLiftPressure above cracking; laminar below
/// laminarPressure (the orifice law's infinite slope at zero pressure difference removed).
struct ValveDesc {
  bool present = true;
  double crackingPressure = 0.0;     // [Pa] pressure difference at which it opens
  double fullLiftPressure = 0.0;     // [Pa] above cracking, where its area reaches maxArea
  double maxArea = 0.0;              // [m2]
  double dischargeCoefficient = 0.7;
  double laminarPressure = 0.0;      // [Pa] pressure difference of the laminar-turbulent transition
};

/// The defaults of the two valves: a check ball on a light spring (inlet) and a relief valve
/// that caps the chamber pressure near 100 bar (estimates, docs/hydraulic_tensioner.md).
inline ValveDesc defaultCheckValve() { return ValveDesc{true, 1e4, 5e4, 1.5e-6, 0.7, 1e3}; }
inline ValveDesc defaultReliefValve() { return ValveDesc{true, 1e7, 2e6, 0.5e-6, 0.7, 1e3}; }

struct HydraulicTensionerDesc {
  // The defaults: a passenger-car tensioner (docs/hydraulic_tensioner.md: sources and estimates).
  double plungerDiameter = 12e-3;    // [m]
  double clearance = 20e-6;          // [m] radial, between plunger and bore
  double guideLength = 20e-3;        // [m] length of the leak gap
  double eccentricity = 0.5;         // relative, 0 (centred) to 1
  double chamberVolume = 2e-6;       // [m3] at the nominal (drawn) stroke
  double plungerMass = 0.03;         // [kg]
  double strokeMin = -4e-3;          // [m] end stops, stroke relative to the nominal (< 0)
  double strokeMax = 6e-3;           // [m] (> 0)
  double endStopStiffness = 5e7;     // [N/m]
  double oilTemperature = 363.15;    // [K] the default; the FMU parameter tensioner.oilTemperature overrides it
  double supplyPressure = 3e5;       // [Pa] gauge; the default of the FMU input tensioner.supplyPressure
  ValveDesc checkValve = defaultCheckValve(), reliefValve = defaultReliefValve();
  OilDesc oil;
};

}  // namespace chaindrive
