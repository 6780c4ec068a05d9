// The hydraulic tensioner's equations one by one: Vogel's law at its defining points, the oil's
// bulk modulus with and without air, the leak gap, the valve law (closed, continuous, never
// backwards), the chamber's volume balance, cavitation, end stops and powers. The rig tests
// (tests/cpp/rig) check the device integrated over time.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "dynamics/hydraulic_tensioner.h"

using namespace chaindrive;

namespace {

constexpr double kPiT = 3.14159265358979323846;

}  // namespace

// The defaults' Vogel constants were fitted to an SAE 5W-30 at 40 C (60 mm2/s at 840 kg/m3),
// 100 C (10.5 mm2/s at 805 kg/m3) and 150 C (3.0 mPa s, the grade's least high-shear viscosity);
// the constants are rounded to 5-6 digits, so the law meets the points within 0.01 %.
TEST(HydraulicTensioner, ViscosityMeetsItsDefiningPoints) {
  const OilDesc oil;
  const double points[][2] = {{313.15, 60e-6 * 840.0}, {373.15, 10.5e-6 * 805.0}, {423.15, 3.0e-3}};
  for (const auto& pt : points) EXPECT_NEAR(oilViscosity(oil, pt[0]) / pt[1], 1.0, 1e-4) << pt[0];
  // monotonic falling, and the kinematic viscosity at the constant density (for the docs)
  double last = 1e9;
  for (double c = 20.0; c <= 150.0; c += 10.0) {
    const double mu = oilViscosity(oil, 273.15 + c);
    EXPECT_LT(mu, last);
    last = mu;
  }
  std::printf("kinematic viscosity at 850 kg/m3: 60 C %.2f mm2/s, 90 C %.2f mm2/s, 100 C %.2f mm2/s\n",
              oilViscosity(oil, 333.15) / oil.density * 1e6, oilViscosity(oil, 363.15) / oil.density * 1e6,
              oilViscosity(oil, 373.15) / oil.density * 1e6);
}

// Without air the pure oil's modulus; with the default 0.5 % air the closed form of the mixture,
// within 5 % of the pure oil at 200 bar and more than 20 times softer at 0 bar gauge.
TEST(HydraulicTensioner, BulkModulusPureAtHighPressureSoftWithAirNearZero) {
  OilDesc oil;
  const double K = oil.bulkModulus, n = oil.polytropicExponent, pa = oil.atmosphericPressure;
  oil.airFraction = 0.0;
  EXPECT_EQ(effectiveBulkModulus(oil, 0.0), K);
  EXPECT_EQ(effectiveBulkModulus(oil, 2e7), K);
  oil.airFraction = 0.005;
  const auto closedForm = [&](double p) {
    const double abs = p + pa, a = 0.005 * std::pow(pa / abs, 1.0 / n);
    return (1.0 + a) / (1.0 / K + a / (n * abs));
  };
  for (double p : {0.0, 1e5, 3e5, 1e6, 1e7, 2e7}) EXPECT_NEAR(effectiveBulkModulus(oil, p) / closedForm(p), 1.0, 1e-13);
  EXPECT_NEAR(effectiveBulkModulus(oil, 2e7) / K, 1.0, 0.05);
  EXPECT_LT(effectiveBulkModulus(oil, 0.0), K / 20.0);
  double last = 0.0;  // stiffening with pressure
  for (double p = -0.9e5; p <= 3e7; p += 1e5) {
    const double k = effectiveBulkModulus(oil, p);
    EXPECT_GT(k, last) << p;
    last = k;
  }
  // below the vapour pressure: the modulus at the vapour pressure (finite, positive)
  EXPECT_EQ(effectiveBulkModulus(oil, -pa), effectiveBulkModulus(oil, oil.vapourPressure - pa));
  EXPECT_GT(effectiveBulkModulus(oil, -pa), 0.0);
  std::printf("bulk modulus with 0.5 %% air: 0 bar %.4g Pa, 3 bar %.4g Pa, 100 bar %.4g Pa, 200 bar %.4g Pa\n",
              effectiveBulkModulus(oil, 0.0), effectiveBulkModulus(oil, 3e5), effectiveBulkModulus(oil, 1e7),
              effectiveBulkModulus(oil, 2e7));
}

// The textbook annular gap: a fully eccentric plunger leaks 2.5 times a centred one.
TEST(HydraulicTensioner, LeakIsTheAnnularGapFlow) {
  HydraulicTensionerDesc t;
  t.eccentricity = 0.0;
  const double mu = 0.01, g0 = leakConductance(t, mu);
  EXPECT_NEAR(g0, kPiT * t.plungerDiameter * std::pow(t.clearance, 3) / (12.0 * mu * t.guideLength), 1e-15 * g0 * 1e3);
  t.eccentricity = 1.0;
  EXPECT_NEAR(leakConductance(t, mu) / g0, 2.5, 1e-14);
  const HydraulicResult r = hydraulicTensioner(t, 0.0, 0.0, 2e6, 0.0, mu);
  EXPECT_DOUBLE_EQ(r.flows.leak, leakConductance(t, mu) * 2e6);
}

// Closed up to cracking, never backwards, the area linear up to full lift, the orifice law
// beyond, the laminar branch joining it continuously, and Lipschitz at dp = 0.
TEST(HydraulicTensioner, ValveLaw) {
  ValveDesc v{true, 1e4, 5e4, 1.5e-6, 0.7, 1e3};
  const double rho = 850.0;
  for (double dp : {-1e6, -1.0, 0.0, 5e3, 1e4}) EXPECT_EQ(valveFlow(v, dp, rho), 0.0) << dp;
  EXPECT_NEAR(valveFlow(v, 2e5, rho), 0.7 * 1.5e-6 * std::sqrt(2.0 * 2e5 / rho), 1e-18);
  EXPECT_NEAR(valveFlow(v, 3.5e4, rho), 0.7 * 1.5e-6 * 0.5 * std::sqrt(2.0 * 3.5e4 / rho), 1e-18);
  v.present = false;
  EXPECT_EQ(valveFlow(v, 2e5, rho), 0.0);
  // no cracking pressure: the laminar branch below 1 kPa
  v = ValveDesc{true, 0.0, 5e4, 1.5e-6, 0.7, 1e3};
  const double below = valveFlow(v, 1e3 * (1.0 - 1e-12), rho), at = valveFlow(v, 1e3, rho);
  EXPECT_NEAR(below, at, 1e-11 * at);
  double slope = 0.0;  // the largest secant slope near 0: bounded (Lipschitz)
  for (double dp = 1e-6; dp < 2e3; dp *= 1.5) slope = std::max(slope, valveFlow(v, dp, rho) / dp);
  const double lipschitz = 0.7 * 1.5e-6 / 5e4 * std::sqrt(2.0 * 1e3 / rho) * 2.0 + 0.7 * 1.5e-6 * std::sqrt(2.0 / (rho * 1e3));
  EXPECT_LE(slope, lipschitz);
}

// Every state: check - leak - relief + vapour = A ds/dt + V / K dp/dt (to rounding; dp/dt of the
// chamber's pressure, 0 while it cavitates), the check
// flow never negative, the force never negative, the dissipation never negative.
TEST(HydraulicTensioner, ChamberVolumeBalanceAtEveryState) {
  const HydraulicTensionerDesc t;
  const double A = plungerArea(t), mu = 0.011;
  for (double s : {-3e-3, 0.0, 2e-3})
    for (double v : {-0.5, -0.01, 0.0, 0.01, 0.5})
      for (double p : {-1.1e5, -0.99e5, -0.5e5, 0.0, 2.8e5, 3e5, 5e6, 1.05e7, 2e7}) {
        const HydraulicResult r = hydraulicTensioner(t, s, v, p, 3e5, mu);
        const double floor = t.oil.vapourPressure - t.oil.atmosphericPressure, pe = std::max(p, floor);
        const double V = t.chamberVolume + A * s, K = effectiveBulkModulus(t.oil, pe);
        const double in = r.flows.check - r.flows.leak - r.flows.relief + r.flows.vapour;
        const double out = A * v + (p > floor ? V / K * r.pressureRate : 0.0);  // (cavitating: the pressure holds)
        EXPECT_NEAR(in, out, 1e-12 * (std::fabs(A * v) + std::fabs(r.flows.check) + std::fabs(r.flows.relief) + 1e-9))
            << s << " " << v << " " << p;
        EXPECT_GE(r.flows.check, 0.0);
        EXPECT_GE(r.flows.relief, 0.0);
        if (p > floor) {
          EXPECT_EQ(r.flows.vapour, 0.0);
        }
        EXPECT_GE(r.force, 0.0);
        EXPECT_GE(r.dissipatedPower, 0.0);
        EXPECT_EQ(r.supplyPower, 3e5 * r.flows.check);
      }
}

// At the floor, a plunger drawn out faster than the valve fills: the chamber's pressure holds,
// the missing oil is vapour, and the state falls below the floor counting the vapour volume;
// pushed back in, the cavity collapses (the state rises) before the pressure does. The state's
// rate is continuous through the floor.
TEST(HydraulicTensioner, CavitationHoldsTheFloorAndCountsTheVapour) {
  const HydraulicTensionerDesc t;
  const double floor = t.oil.vapourPressure - t.oil.atmosphericPressure, mu = 0.011;
  const double s = 1e-3, V = t.chamberVolume + plungerArea(t) * s, kFloor = effectiveBulkModulus(t.oil, floor);
  HydraulicResult r = hydraulicTensioner(t, s, 1.0, floor, 3e5, mu);
  EXPECT_EQ(r.pressure, floor);
  EXPECT_GT(r.flows.vapour, 0.0);
  EXPECT_NEAR(r.flows.vapour, plungerArea(t) * 1.0 - r.flows.check + r.flows.leak, 1e-15);
  EXPECT_NEAR(r.pressureRate, -r.flows.vapour * kFloor / V, 1e-12 * std::fabs(r.pressureRate));
  const HydraulicResult above = hydraulicTensioner(t, s, 1.0, floor * (1.0 - 1e-12), 3e5, mu);
  EXPECT_EQ(above.flows.vapour, 0.0);
  EXPECT_NEAR(above.pressureRate / r.pressureRate, 1.0, 1e-9);  // continuous through the floor
  r = hydraulicTensioner(t, s, -1.0, floor - 1e3, 3e5, mu);  // a cavity of 1e3 Pa V / K_f (2.8 % of V), pushed in
  EXPECT_EQ(r.pressure, floor);
  EXPECT_NEAR(r.vapourVolume, 1e3 * V / kFloor, 1e-12 * r.vapourVolume);
  // d/dt of the vapour volume (its state's rate, the chamber's growth) is the vapour flow
  const double dVdt = -r.pressureRate * V / kFloor + 1e3 * plungerArea(t) * -1.0 / kFloor;
  EXPECT_NEAR(dVdt, r.flows.vapour, 1e-12 * std::fabs(r.flows.vapour));
  EXPECT_GT(r.pressureRate, 0.0);
  EXPECT_LT(r.flows.vapour, 0.0);  // collapsing
  EXPECT_EQ(r.force, 0.0);
}

// The force: p A within the stroke; beyond the stops a spring pushing back into range.
TEST(HydraulicTensioner, ForceAndEndStops) {
  const HydraulicTensionerDesc t;
  const double A = plungerArea(t);
  EXPECT_DOUBLE_EQ(hydraulicTensioner(t, 0.0, 0.0, 2e6, 3e5, 0.011).force, 2e6 * A);
  // (the stroke's rounding beside the stop: 1e-12 of the force)
  EXPECT_NEAR(hydraulicTensioner(t, t.strokeMin - 1e-5, 0.0, 2e6, 3e5, 0.011).force,
              2e6 * A + t.endStopStiffness * 1e-5, 1e-12 * 726.0);
  EXPECT_NEAR(hydraulicTensioner(t, t.strokeMax + 1e-6, 0.0, 2e6, 3e5, 0.011).force,
              2e6 * A - t.endStopStiffness * 1e-6, 1e-12 * 176.0);
  EXPECT_EQ(hydraulicTensioner(t, t.strokeMax + 1e-3, 0.0, 2e6, 3e5, 0.011).force, 0.0);  // never pulls
  EXPECT_EQ(hydraulicTensioner(t, 0.0, 0.0, -0.5e5, 3e5, 0.011).force, 0.0);
}
