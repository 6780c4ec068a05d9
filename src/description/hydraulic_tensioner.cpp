// The reader of tensioner.hydraulic: every field with its range (the ranges span what passenger
// car and truck tensioners use, with room; outside them the device's equations lose their
// meaning: a zero clearance, a closed valve area, a viscosity law beyond its fitted range).
#include <cmath>
#include <string>

#include "description/fields.h"

namespace chaindrive {

namespace {

// Vogel's law and the oil with its air. The law's constants are checked together: c must lie
// below the range (the law has its pole at T = c).
void readOil(Fields f, OilDesc& oil) {
  if (!f.valid()) return;
  oil.vogelA = f.number("vogelA", 0.0, 1.0, oil.vogelA, "Pa s", true);
  oil.vogelB = f.number("vogelB", 0.0, 1e5, oil.vogelB, "K", true);
  oil.vogelC = f.number("vogelC", 0.0, 250.0, oil.vogelC, "K");
  oil.temperatureMin = f.number("temperatureMin", 200.0, 500.0, oil.temperatureMin, "K");
  oil.temperatureMax = f.number("temperatureMax", 200.0, 500.0, oil.temperatureMax, "K");
  if (oil.temperatureMax <= oil.temperatureMin)
    f.problem(f.at("temperatureMax"), formatNumber(oil.temperatureMax) + " K must exceed temperatureMin " +
                                          formatNumber(oil.temperatureMin) + " K");
  if (oil.vogelC >= oil.temperatureMin)
    f.problem(f.at("vogelC"), formatNumber(oil.vogelC) + " K must lie below temperatureMin " +
                                  formatNumber(oil.temperatureMin) + " K (Vogel's law has its pole at T = vogelC)");
  oil.density = f.number("density", 600.0, 1200.0, oil.density, "kg/m3");
  oil.bulkModulus = f.number("bulkModulus", 1e8, 1e10, oil.bulkModulus, "Pa");
  oil.airFraction = f.number("airFraction", 0.0, 0.5, oil.airFraction, "");
  oil.polytropicExponent = f.number("polytropicExponent", 1.0, 1.67, oil.polytropicExponent, "");
  oil.vapourPressure = f.number("vapourPressure", 0.0, 0.5e5, oil.vapourPressure, "Pa (absolute)", true);
  f.finish();
}

// A valve: absent (present false) or its opening law.
void readValve(Fields f, ValveDesc& v) {
  if (!f.valid()) return;
  v.present = f.boolean("present", v.present);
  v.crackingPressure = f.number("crackingPressure", 0.0, 1e8, v.crackingPressure, "Pa");
  v.fullLiftPressure = f.number("fullLiftPressure", 0.0, 1e8, v.fullLiftPressure, "Pa", true);
  v.maxArea = f.number("maxArea", 0.0, 1e-4, v.maxArea, "m2", true);
  v.dischargeCoefficient = f.number("dischargeCoefficient", 0.0, 1.0, v.dischargeCoefficient, "", true);
  v.laminarPressure = f.number("laminarPressure", 0.0, 1e5, v.laminarPressure, "Pa", true);
  f.finish();
}

}  // namespace

void readHydraulicTensioner(Fields f, HydraulicTensionerDesc& h) {
  if (!f.valid()) return;
  h.plungerDiameter = f.number("plungerDiameter", 3e-3, 50e-3, h.plungerDiameter, "m");
  h.clearance = f.number("clearance", 1e-6, 200e-6, h.clearance, "m");
  h.guideLength = f.number("guideLength", 1e-3, 0.1, h.guideLength, "m");
  h.eccentricity = f.number("eccentricity", 0.0, 1.0, h.eccentricity, "");
  h.chamberVolume = f.number("chamberVolume", 1e-8, 1e-4, h.chamberVolume, "m3");
  h.plungerMass = f.number("plungerMass", 1e-4, 1.0, h.plungerMass, "kg");
  h.strokeMin = f.number("strokeMin", -0.05, 0.0, h.strokeMin, "m");
  h.strokeMax = f.number("strokeMax", 0.0, 0.05, h.strokeMax, "m", true);
  h.endStopStiffness = f.number("endStopStiffness", 0.0, 1e10, h.endStopStiffness, "N/m");
  h.supplyPressure = f.number("supplyPressure", 0.0, 1e6, h.supplyPressure, "Pa");
  readValve(f.object("checkValve", false), h.checkValve);
  readValve(f.object("reliefValve", false), h.reliefValve);
  readOil(f.object("oil", false), h.oil);
  // after the oil: the temperature must lie in its viscosity law's range
  h.oilTemperature = f.number("oilTemperature", h.oil.temperatureMin, h.oil.temperatureMax, h.oilTemperature, "K");
  // (checked when the three fields are in range: otherwise their own problems say enough)
  const bool inRange = h.plungerDiameter >= 3e-3 && h.plungerDiameter <= 50e-3 && h.chamberVolume >= 1e-8 &&
                       h.chamberVolume <= 1e-4 && h.strokeMin >= -0.05 && h.strokeMin <= 0.0;
  const double minVolume = h.chamberVolume + 0.25 * kPi * h.plungerDiameter * h.plungerDiameter * h.strokeMin;
  if (inRange && minVolume <= 0.0)
    f.problem(f.at("strokeMin"), formatNumber(h.strokeMin) + " m empties the chamber of " +
                                     formatNumber(h.chamberVolume) + " m3; allowed > " +
                                     formatNumber(-h.chamberVolume / (0.25 * kPi * h.plungerDiameter * h.plungerDiameter)) + " m");
  f.finish();
}

}  // namespace chaindrive
