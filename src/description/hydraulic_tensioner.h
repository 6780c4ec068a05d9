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
  double vogelA = 0.0;               // [Pa s]
  double vogelB = 0.0;               // [K]
  double vogelC = 0.0;               // [K]
  double temperatureMin = 0.0;       // [K] the law's range
  double temperatureMax = 0.0;       // [K]
  double density = 0.0;              // [kg/m3]
  double bulkModulus = 0.0;          // [Pa] of the pure oil
  double airFraction = 0.0;          // volume fraction of free air at atmospheric pressure
  double polytropicExponent = 1.0;   // of the entrained air's compression
  double atmosphericPressure = 1.01325e5;  // [Pa] absolute: the gauge pressures' zero
  double vapourPressure = 0.0;       // [Pa] absolute: the chamber's floor (cavitation)
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

struct HydraulicTensionerDesc {
  double plungerDiameter = 0.0;      // [m]
  double clearance = 0.0;            // [m] radial, between plunger and bore
  double guideLength = 0.0;          // [m] length of the leak gap
  double eccentricity = 0.0;         // relative, 0 (centred) to 1
  double chamberVolume = 0.0;        // [m3] at the nominal (drawn) stroke
  double plungerMass = 0.0;          // [kg]
  double strokeMin = 0.0;            // [m] end stops, stroke relative to the nominal (< 0)
  double strokeMax = 0.0;            // [m] (> 0)
  double endStopStiffness = 0.0;     // [N/m]
  double oilTemperature = 363.15;    // [K] the default; the FMU parameter tensioner.oilTemperature overrides it
  double supplyPressure = 3e5;       // [Pa] gauge; the default of the FMU input tensioner.supplyPressure
  ValveDesc checkValve, reliefValve;
  OilDesc oil;
};

}  // namespace chaindrive
