// A hydraulic tensioner's chamber keeps its oil content as the state, not its pressure (in the
// link model and in the span model alike).
//
// The content c is the chamber's oil with its entrained air, measured as the volume it fills at
// gauge 0. At gauge p it fills c v(p), with v the mixture's volume ratio
//
//   v(p) = (1 + a(p)) / (1 + a(0)) exp(-p / K),   a(p) = alpha (p_atm / p_abs)^(1 / n),
//
// (K the oil's bulk modulus, a the free air per unit of oil, compressed polytropically: its
// modulus, -v / v', is that of dynamics/hydraulic_tensioner.h within a(p) <= alpha, 0.5 % by
// default). The chamber's pressure is the p at which the content fills the chamber's volume,
// v(p) = V(s) / c; where V(s) / c exceeds v at the vapour floor, the chamber cavitates at the
// floor. The content changes only by the valves' and the leak's flows, dc/dt = Q / v(p).
//
// Why: with the pressure as the state, dp/dt = K / V (Q - A ds/dt) holds the hydraulic spring
// (the plunger against the compressed oil, about 1 kHz with the tension guide) in a first-order
// state that the Verlet integrators advance by the trapezoidal rule, which lends that mode energy
// at every step (the span model's 20 us step pumped its chamber up by 13 % at 6000 rpm, and it
// emptied at 50 us; the link model's real-time method at 3.571 us raised the tensioner force's
// mean at 1000 rpm by 4 %). With the content as the state the pressure is a function of the
// plunger's position, the hydraulic spring a position force as every other spring, and the state
// itself only follows the valves' flows.
#pragma once

#include <algorithm>
#include <vector>

#include "description/hydraulic_tensioner.h"

namespace chaindrive {

/// The oil's entrained air at gauge pressure p: the absolute pressure [Pa] (at least the vapour
/// pressure) and the free air per unit volume of oil there, a = alpha (p_atm / p_abs)^(1/n).
struct FreeAir {
  double absolutePressure;
  double perOil;
};
FreeAir freeAir(const OilDesc& oil, double pressure);

/// The content [m3] a change of 1 bar moves in the chamber at rest, V0 1e5 Pa / K: the scale of
/// an adaptive integrator's tolerance on the content.
inline double chamberOilScale(const HydraulicTensionerDesc& t) { return t.chamberVolume * 1e5 / t.oil.bulkModulus; }

class ChamberOilLaw {
 public:
  ChamberOilLaw() = default;
  explicit ChamberOilLaw(const OilDesc& oil);
  bool empty() const { return pressure_.empty(); }
  /// v(p) of gauge pressure p [Pa] (at least the vapour floor's).
  double volumeRatio(double pressure) const;
  /// The gauge pressure [Pa] at which the content fills `ratio` times its own volume: the vapour
  /// floor's where the ratio exceeds the floor's (cavitation). Tabulated over ln v (cubic Hermite).
  double pressureAt(double ratio) const;
  /// v at the vapour floor: the largest ratio the oil fills.
  double floorRatio() const { return floorRatio_; }
  /// The content's rate [m3/s] of the net flow into the chamber [m3/s] at the volume ratio V / c:
  /// the flow over v (the floor's while the chamber cavitates: then the flows fill or empty the
  /// vapour's volume, not the oil's).
  double contentRate(double netFlow, double ratio) const { return netFlow / std::min(ratio, floorRatio_); }

 private:
  double dPressureDLogRatio(double pressure) const;  // -1 / (1/K + a / (n p_abs (1 + a)))
  OilDesc oil_;
  double floor_ = 0.0, floorRatio_ = 1.0;           // [Pa] gauge
  double logTop_ = 0.0, logStep_ = 0.0;             // the table's first node (the top pressure) and spacing
  std::vector<double> pressure_, slope_;            // (nodes) p and dp / d ln v
};

}  // namespace chaindrive
