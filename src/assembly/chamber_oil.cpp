#include "assembly/chamber_oil.h"

#include <algorithm>
#include <cmath>

#include "math/elementary.h"

namespace chaindrive {

namespace {

constexpr double kTopPressure = 2e8;  // [Pa] the table's top (2000 bar); above it, extrapolated linearly
constexpr int kIntervals = 4096;

}  // namespace

// The isothermal-polytropic mixture of Simscape's hydraulic fluid: per unit volume of oil, free
// air of volume a(p) = alpha (p_atm / p_abs)^(1/n), compressed polytropically (its modulus n p_abs)
// in parallel with the oil (modulus K). The oil's own volume change is left out of the mixture's
// volume (it is below 1 % up to 100 bar).
FreeAir freeAir(const OilDesc& oil, double pressure) {
  const double pAbs = std::max(pressure + oil.atmosphericPressure, oil.vapourPressure);
  return {pAbs, oil.airFraction * math::pow(oil.atmosphericPressure / pAbs, 1.0 / oil.polytropicExponent)};
}

double ChamberOilLaw::volumeRatio(double pressure) const {
  const double air = freeAir(oil_, pressure).perOil;
  return (1.0 + air) / (1.0 + oil_.airFraction) * math::exp(-pressure / oil_.bulkModulus);
}

double ChamberOilLaw::dPressureDLogRatio(double pressure) const {
  const FreeAir a = freeAir(oil_, pressure);
  return -1.0 / (1.0 / oil_.bulkModulus + a.perOil / (oil_.polytropicExponent * a.absolutePressure * (1.0 + a.perOil)));
}

// The nodes equally spaced in ln v from the top pressure to the floor; each node's pressure by
// Newton's method from the last node's, inside the bracket of the two (ln v falls with p).
ChamberOilLaw::ChamberOilLaw(const OilDesc& oil) : oil_(oil) {
  floor_ = oil.vapourPressure - oil.atmosphericPressure;
  floorRatio_ = volumeRatio(floor_);
  logTop_ = math::log(volumeRatio(kTopPressure));
  logStep_ = (math::log(floorRatio_) - logTop_) / kIntervals;
  pressure_.assign(kIntervals + 1, 0.0);
  slope_.assign(kIntervals + 1, 0.0);
  double p = kTopPressure;
  for (int i = 0; i <= kIntervals; ++i) {
    const double target = logTop_ + i * logStep_;
    double hi = p, lo = floor_;
    for (int it = 0; it < 100; ++it) {
      const double g = math::log(volumeRatio(p)) - target;  // > 0: p too low
      (g > 0.0 ? lo : hi) = p;
      double next = p - g * dPressureDLogRatio(p);
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      const bool converged = std::fabs(next - p) <= 1e-12 * std::max(1e5, std::fabs(p));
      p = next;
      if (converged) break;
    }
    pressure_[i] = i == kIntervals ? floor_ : p;
    slope_[i] = dPressureDLogRatio(pressure_[i]);
  }
}

double ChamberOilLaw::pressureAt(double ratio) const {
  const double u = (math::log(ratio) - logTop_) / logStep_;
  if (std::isnan(u)) return u;  // (a content no longer positive, or a non-finite state: the health check names it)
  if (u >= kIntervals) return floor_;
  if (u <= 0.0) return pressure_[0] + u * logStep_ * slope_[0];
  const int i = std::min(static_cast<int>(u), kIntervals - 1);
  const double f = u - i, h = logStep_;
  const double h00 = (1.0 + 2.0 * f) * (1.0 - f) * (1.0 - f), h10 = f * (1.0 - f) * (1.0 - f);
  const double h01 = f * f * (3.0 - 2.0 * f), h11 = f * f * (f - 1.0);
  return h00 * pressure_[i] + h10 * h * slope_[i] + h01 * pressure_[i + 1] + h11 * h * slope_[i + 1];
}

}  // namespace chaindrive
