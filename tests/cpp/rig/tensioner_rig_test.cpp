// The hydraulic tensioner on the bench (src/rig): its physics integrated over time.
// - leak-down: the steady plunger speed is the annular gap's flow at the resulting pressure over
//   the plunger area (2 %);
// - static: at rest on the open supply the force is (p_supply - p_crack) A (1 %);
// - oil stiffness: a closed chamber's small-amplitude stiffness is K A^2 / V (2 %);
// - pumping: the check valve never lets oil back (large motions: cavitation and relief), the
//   chamber pumps up (small motions), and the oil's volume balance holds to the integrator's accuracy;
// - the loops' trends: the peak force rises as the clearance shrinks, falls with more air and
//   with a hotter oil.
// Each prints its measured figures (docs/hydraulic_tensioner.md quotes them).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "rig/tensioner_rig.h"

using namespace chaindrive;

namespace {

IntegratorSettings tight() {
  IntegratorSettings s;
  s.method = IntegratorMethod::ArkodeErk;
  s.adaptive.rtol = 1e-9;
  return s;
}

RigSetup loopOf(double frequency, double amplitude) {
  RigSetup r;
  r.test = RigTest::Loop;
  r.frequency = frequency;
  r.amplitude = amplitude;
  return r;
}

struct Period {
  double peakForce = -1e300, leastForce = 1e300, meanPressure = 0.0;
};

// The force's extremes and the mean pressure of period k (0: the first) of samples at a fixed output step.
Period period(const std::vector<RigSample>& samples, double frequency, int k) {
  Period p;
  int n = 0;
  for (const RigSample& s : samples) {
    const double phase = s.time * frequency;
    if (phase < k || phase >= k + 1) continue;
    p.peakForce = std::max(p.peakForce, s.device.force);
    p.leastForce = std::min(p.leastForce, s.device.force);
    p.meanPressure += s.pressure;
    ++n;
  }
  p.meanPressure /= n;
  return p;
}

// The last of `periods` periods of a loop, 400 samples a period.
Period settledLoop(const RigSetup& setup, int periods) {
  const auto samples = runRig(setup, tight(), periods / setup.frequency, 1.0 / (400.0 * setup.frequency));
  return period(samples, setup.frequency, periods - 1);
}

}  // namespace

// 300 N on the default plunger (26.5 bar) at 90 C: after the start's oscillation (its leak
// damping takes about 30 ms to halve it) the plunger sinks at the leak's speed. The window
// 0.2-0.3 s averages what is left of the oscillation over 250 of its periods.
TEST(TensionerRig, LeakDownSpeedIsTheGapFlowOverTheArea_2pc) {
  RigSetup setup;
  setup.test = RigTest::LeakDown;
  setup.force = 300.0;
  const auto samples = runRig(setup, tight(), 0.3, 1e-4);
  const TensionerRig rig(setup);
  const RigSample &a = samples[2000], &b = samples.back();
  double pMean = 0.0;
  for (std::size_t i = 2000; i < samples.size(); ++i) pMean += samples[i].pressure;
  pMean /= static_cast<double>(samples.size() - 2000);
  const double speed = (b.stroke - a.stroke) / (b.time - a.time);
  const HydraulicTensionerDesc& t = rig.tensioner();
  const double mu = oilViscosity(t.oil, t.oilTemperature);
  const double gap = 3.14159265358979323846 * t.plungerDiameter * std::pow(t.clearance, 3) /
                     (12.0 * mu * t.guideLength) * (1.0 + 1.5 * t.eccentricity * t.eccentricity);
  const double expected = -gap * pMean / plungerArea(t);
  std::printf("leak-down 300 N, 90 C: pressure %.5g bar (F/A %.5g bar), speed %.6g mm/s, gap flow / A %.6g mm/s, "
              "deviation %.3g %%\n",
              pMean * 1e-5, setup.force / plungerArea(t) * 1e-5, speed * 1e3, expected * 1e3,
              (speed / expected - 1.0) * 100.0);
  EXPECT_NEAR(speed / expected, 1.0, 0.02);
  EXPECT_NEAR(pMean * plungerArea(t) / setup.force, 1.0, 0.02);
  EXPECT_EQ(b.volumeCheck, 0.0);  // the supply closed
}

// The plunger held at rest on a 3 bar supply: the chamber fills until the check valve closes at
// its cracking pressure, less the little difference that pushes the leak's flow through it.
TEST(TensionerRig, StaticForceIsSupplyLessCrackingTimesArea_1pc) {
  RigSetup setup = loopOf(50.0, 0.0);
  setup.initialPressure = 0.0;
  const auto samples = runRig(setup, tight(), 0.05, 1e-3);
  const RigSample& s = samples.back();
  const HydraulicTensionerDesc& t = setup.tensioner;
  const double expected = (t.supplyPressure - t.checkValve.crackingPressure) * plungerArea(t);
  std::printf("static: force %.6g N, (p_s - p_crack) A %.6g N, deviation %.3g %%; check flow %.3g mm3/s = leak %.3g mm3/s\n",
              s.device.force, expected, (s.device.force / expected - 1.0) * 100.0, s.device.flows.check * 1e9,
              s.device.flows.leak * 1e9);
  EXPECT_NEAR(s.device.force / expected, 1.0, 0.01);
  EXPECT_LE(s.device.force, expected);  // the check valve open a little: below cracking
  EXPECT_NEAR(s.device.flows.check / s.device.flows.leak, 1.0, 1e-6);  // steady
}

// A closed chamber (no valves, no gap) at 50 bar, the plunger on a 1 um sinusoid: the force's
// swing over the motion's swing is K A^2 / V, with and without air.
TEST(TensionerRig, ClosedChamberStiffnessIsKA2OverV_2pc) {
  for (double air : {0.0, 0.005}) {
    RigSetup setup = loopOf(100.0, 1e-6);
    HydraulicTensionerDesc& t = setup.tensioner;
    t.checkValve.present = t.reliefValve.present = false;
    t.clearance = 0.0;
    t.oil.airFraction = air;
    setup.initialPressure = 5e6;
    const auto samples = runRig(setup, tight(), 0.01, 1.0 / 40000.0);
    const Period p = period(samples, 100.0, 0);
    const double measured = (p.peakForce - p.leastForce) / (2.0 * setup.amplitude);
    const double A = plungerArea(t), expected = effectiveBulkModulus(t.oil, 5e6) * A * A / t.chamberVolume;
    std::printf("closed chamber, air %.3g: stiffness %.6g N/m, K A^2 / V %.6g N/m, deviation %.3g %%\n", air, measured,
                expected, (measured / expected - 1.0) * 100.0);
    EXPECT_NEAR(measured / expected, 1.0, 0.02);
  }
}

// The oil's volume balance over a run: the volumes that flowed in, less those out, plus the
// vapour's volume at the end, equal the chamber's growth A (s - s0) plus the oil's compression, the integral
// of V / K dp (trapezoids over samples 1 us apart: their error is below 1e-6 of the volumes).
// Tolerance: 1e-5 of the volume that came through the check valve, for the integrator's rtol
// 1e-9 accumulated over the run with the valves' kinks. Also the check flow at every sample,
// the least of which it returns (never negative: no oil back through the check valve).
double volumeBalance(const RigSetup& setup, const std::vector<RigSample>& samples, double& leastCheckFlow) {
  const HydraulicTensionerDesc& t = setup.tensioner;
  const double A = plungerArea(t), floor = t.oil.vapourPressure - t.oil.atmosphericPressure;
  const auto vk = [&](const RigSample& s) {
    return (t.chamberVolume + A * s.stroke) / effectiveBulkModulus(t.oil, std::max(s.pressure, floor));
  };
  double compression = 0.0;
  leastCheckFlow = 1e300;
  for (std::size_t i = 1; i < samples.size(); ++i) {
    const RigSample &a = samples[i - 1], &b = samples[i];
    compression += 0.5 * (vk(a) + vk(b)) * (std::max(b.pressure, floor) - std::max(a.pressure, floor));
    leastCheckFlow = std::min(leastCheckFlow, b.device.flows.check);
  }
  const RigSample &s0 = samples.front(), &e = samples.back();
  const double flowed = e.volumeCheck - e.volumeLeak - e.volumeRelief + e.volumeVapour;
  return flowed - (A * (e.stroke - s0.stroke) + compression);
}

// 1 mm at 200 Hz: the plunger is drawn out faster than the check valve fills at 3 bar (the
// chamber cavitates) and pressed in to the relief valve. Pure oil: with air, the air's expansion
// at low pressure takes the volume and the floor is never reached.
TEST(TensionerRig, LargeMotionsCheckValveNeverReversesVolumeBalanceHolds) {
  RigSetup setup = loopOf(200.0, 1e-3);
  setup.tensioner.oil.airFraction = 0.0;
  const auto samples = runRig(setup, tight(), 0.05, 1e-6);
  double leastCheck = 0.0;
  const double balance = volumeBalance(setup, samples, leastCheck);
  const RigSample& e = samples.back();
  double largestCavity = 0.0;
  for (const RigSample& x : samples) largestCavity = std::max(largestCavity, x.volumeVapour);
  std::printf("large motions 1 mm, 200 Hz, 10 periods: in %.6g mm3, leak %.4g mm3, relief %.6g mm3, largest cavity %.6g mm3; "
              "balance %.3g mm3 (%.2g of the inflow); least check flow %.3g m3/s\n",
              e.volumeCheck * 1e9, e.volumeLeak * 1e9, e.volumeRelief * 1e9, largestCavity * 1e9, balance * 1e9,
              balance / e.volumeCheck, leastCheck);
  EXPECT_GE(leastCheck, 0.0);
  EXPECT_GT(largestCavity, 1e-9);  // the run did cavitate, by more than 1 mm3 (the balance covers that case)
  EXPECT_GT(e.volumeRelief, 0.0);  // and reach the relief valve
  EXPECT_NEAR(balance, 0.0, 1e-5 * e.volumeCheck);
}

// 0.05 mm at 100 Hz from the chamber filled at rest (2.9 bar): each stroke in raises the pressure
// above the supply, each stroke out draws in what leaked: the mean pressure of the first period
// is already more than 5 times the start's, and it still climbs to the thirtieth; the balance
// holds as above.
TEST(TensionerRig, SmallMotionsPumpUpVolumeBalanceHolds) {
  const RigSetup setup = loopOf(100.0, 0.05e-3);
  const auto samples = runRig(setup, tight(), 0.3, 1e-6);
  double leastCheck = 0.0;
  const double balance = volumeBalance(setup, samples, leastCheck);
  const Period first = period(samples, 100.0, 0), last = period(samples, 100.0, 29);
  const RigSample& e = samples.back();
  std::printf("pump-up 0.05 mm, 100 Hz: mean pressure period 1 %.4g bar, period 30 %.4g bar; in %.6g mm3, "
              "balance %.3g mm3 (%.2g of the inflow)\n",
              first.meanPressure * 1e-5, last.meanPressure * 1e-5, e.volumeCheck * 1e9, balance * 1e9,
              balance / e.volumeCheck);
  EXPECT_GE(leastCheck, 0.0);
  EXPECT_GT(first.meanPressure, 5.0 * samples.front().pressure);
  EXPECT_GT(last.meanPressure, first.meanPressure);
  EXPECT_NEAR(balance, 0.0, 1e-5 * e.volumeCheck);
}

// The peak force of the settled loop (0.05 mm, 20 and 100 Hz, below the relief valve): rises as
// the clearance shrinks, falls with more air, falls with a hotter (thinner) oil.
TEST(TensionerRig, LoopTrendsClearanceAirTemperature) {
  for (double f : {20.0, 100.0}) {
    const int periods = f < 50.0 ? 10 : 30;
    RigSetup base = loopOf(f, 0.05e-3);
    const double reference = settledLoop(base, periods).peakForce;
    RigSetup tight15 = base, loose30 = base, airy = base, hot = base, cool = base;
    tight15.tensioner.clearance = 15e-6;
    loose30.tensioner.clearance = 30e-6;
    airy.tensioner.oil.airFraction = 0.05;
    hot.tensioner.oilTemperature = 383.15;
    cool.tensioner.oilTemperature = 333.15;
    const double fTight = settledLoop(tight15, periods).peakForce, fLoose = settledLoop(loose30, periods).peakForce;
    const double fAir = settledLoop(airy, periods).peakForce;
    const double fHot = settledLoop(hot, periods).peakForce, fCool = settledLoop(cool, periods).peakForce;
    std::printf("loop %g Hz 0.05 mm peak force: default %.4g N; clearance 15 um %.4g N, 30 um %.4g N; air 5 %% %.4g N; "
                "60 C %.4g N, 110 C %.4g N\n",
                f, reference, fTight, fLoose, fAir, fCool, fHot);
    EXPECT_GT(fTight, reference);
    EXPECT_GT(reference, fLoose);
    EXPECT_LT(fAir, reference);
    EXPECT_GT(fCool, reference);
    EXPECT_LT(fHot, reference);
  }
}

// The stable step, for the drive's integration: fixed-verlet integrates the pressure as a
// component without a velocity (trapezoidal, from the derivatives at the half-step velocities
// before and after the step), so the pressure lags the plunger by half a step, h/2: the plunger
// on its oil (stiffness k = K A^2 / V, mass m) sees a negative damping -k h/2, its oscillation
// grows at omega^2 h / 4. A closed chamber of pure oil at 50 bar, the default plunger (30 g):
// omega = 1.60e4 rad/s, growth 160 /s at 2.5 us. Measured from the pressure swing's peaks in the
// first and the last 2 ms of 20 ms: within 10 % (the peaks sample the swing at the step). The
// fixed-step Dormand-Prince (arkode-erk-fixed) at the same step keeps the amplitude (|rate| below
// 0.01 /s).
TEST(TensionerRig, FixedVerletGrowsThePlungerOscillationAtOmegaSquaredHOver4_10pc) {
  RigSetup setup;
  setup.test = RigTest::LeakDown;
  HydraulicTensionerDesc& t = setup.tensioner;
  t.clearance = 0.0;
  t.reliefValve.present = false;
  t.oil.airFraction = 0.0;
  setup.force = 5e6 * plungerArea(t);
  setup.initialPressure = 5.05e6;
  const double A = plungerArea(t), omega2 = t.oil.bulkModulus * A * A / (t.chamberVolume * t.plungerMass);
  const auto growth = [&](IntegratorMethod method, double h) {
    IntegratorSettings s;
    s.method = method;
    s.fixed.step = h;
    double first = 0.0, last = 0.0;
    for (const RigSample& x : runRig(setup, s, 0.02, h)) {
      if (x.time < 0.002) first = std::max(first, std::fabs(x.pressure - 5e6));
      if (x.time > 0.018) last = std::max(last, std::fabs(x.pressure - 5e6));
    }
    return std::log(last / first) / 0.017;
  };
  for (double h : {1e-6, 2.5e-6, 5e-6}) {
    const double verlet = growth(IntegratorMethod::FixedVerlet, h), erk = growth(IntegratorMethod::ArkodeErkFixed, h);
    std::printf("plunger on pure oil at 50 bar, h %.3g us: fixed-verlet growth %.4g /s (omega^2 h / 4 = %.4g /s), "
                "arkode-erk-fixed %.3g /s\n",
                h * 1e6, verlet, omega2 * h / 4.0, erk);
    EXPECT_NEAR(verlet / (omega2 * h / 4.0), 1.0, 0.1);
    EXPECT_LT(std::fabs(erk), 0.01);
  }
}
