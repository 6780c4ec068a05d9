// System tests of the compliant link-by-link model against analytical references: energy
// conservation, the static tension split, polygonal action.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "dynamics/dynamics.h"
#include "statics/preload.h"
#include "test_util.h"

using namespace chaindrive;
using namespace chaindrive::test;
using nlohmann::json;

namespace {

// The default drive made conservative: no damping or friction anywhere, the crankshaft
// sprocket free (with inertia) instead of driven, no load torques.
DriveDescription conservativeDrive() {
  return modifiedDefault([](json& j) {
    auto& crank = sprocketJson(j, "crankshaft");
    crank["motion"] = "free";
    crank["inertia"] = 0.01;
    j["chain"]["joint"]["damping"] = 0.0;
    for (const char* c : {"rollerSprocket", "plateGuide"}) {
      j["contact"][c]["dampingFactor"] = 0.0;
      j["contact"][c]["friction"] = 0.0;
    }
    test::useSpringDamperTensioner(j);  // (the hydraulic chamber's leak and valves dissipate)
    j["tensioner"]["damping"] = 0.0;
    j["tensioner"]["dampingExtension"] = 0.0;
  });
}

// Largest drift of the total mechanical energy over a run, relative to the kinetic energy.
double energyDrift(const std::shared_ptr<const Model>& m, const IntegratorSettings& is, double tEnd, double& e0out) {
  SimulationOptions opt;
  opt.integrator = is;
  opt.preload.enabled = false;
  auto in = std::make_unique<HeldInputs>(*m);
  Simulation sim(m, opt, std::move(in));
  sim.startFrom(0.0, nominalState(*m, 200.0));
  const EnergyTerms e0 = sim.outputs().energy;
  const double total0 = e0.kinetic + e0.elastic + e0.gravity;
  e0out = e0.kinetic;
  double worst = 0.0;
  const int nOut = 200;
  for (int k = 1; k <= nOut; ++k) {
    sim.advanceTo(tEnd * k / nOut);
    const EnergyTerms e = sim.outputs().energy;
    EXPECT_EQ(e.dissipated, 0.0);
    EXPECT_EQ(e.inputWork, 0.0);
    worst = std::max(worst, std::fabs(e.kinetic + e.elastic + e.gravity - total0));
  }
  return worst / e0.kinetic;
}

}  // namespace

// Energy: velocity Verlet is symplectic for these position-only forces, so its energy error is
// bounded and falls with h^2; halving the step must cut the drift by well over half.
TEST(Energy, ConservedAndDriftShrinksWithTheStep) {
  auto m = std::make_shared<const Model>(assemble(conservativeDrive()));
  const double tEnd = 2.0 * 2.0 * kPi / 200.0 * 1.5;  // three crank revolutions at 200 rad/s
  IntegratorSettings coarse, fine;
  coarse.method = fine.method = named<IntegratorMethod>("fixed-verlet");
  coarse.fixed.step = 2e-6;
  fine.fixed.step = 1e-6;
  double ek = 0.0;
  const double dCoarse = energyDrift(m, coarse, tEnd, ek);
  const double dFine = energyDrift(m, fine, tEnd, ek);
  std::printf("kinetic energy %.3f J; relative energy drift over 3 revolutions: h=2us %.3e, h=1us %.3e (ratio %.2f)\n",
              ek, dCoarse, dFine, dCoarse / dFine);
  EXPECT_LT(dCoarse, 1e-3);
  EXPECT_LT(dFine, 0.5 * dCoarse);
}

// The adaptive explicit integrator: the drift shrinks with its tolerance.
TEST(Energy, AdaptiveDriftShrinksWithTolerance) {
  auto m = std::make_shared<const Model>(assemble(conservativeDrive()));
  const double tEnd = 0.01;
  IntegratorSettings loose, tight;
  loose.method = tight.method = named<IntegratorMethod>("arkode-erk");
  loose.adaptive.rtol = 1e-5;
  tight.adaptive.rtol = 1e-7;
  double ek = 0.0;
  const double dLoose = energyDrift(m, loose, tEnd, ek);
  const double dTight = energyDrift(m, tight, tEnd, ek);
  std::printf("arkode-erk relative energy drift over 10 ms: rtol 1e-5 %.3e, rtol 1e-7 %.3e\n", dLoose, dTight);
  EXPECT_LT(dLoose, 1e-3);
  EXPECT_LT(dTight, 0.2 * dLoose);
}

// Static tension split (a classic result): at low speed with constant camshaft torques the
// mean tight-span force minus the mean slack-span force equals sum(M_cam) / R_cam. The probes sit
// next to the camshaft sprockets (tight: after the intake cam, slack: before the exhaust cam), so
// no guide friction acts between them. Tolerance 3 %; the polygonal action changes the
// effective radius by less than 1 - cos(pi/42) = 0.3 %.
TEST(Balance, TightMinusSlackEqualsCamTorquesOverPitchRadius) {
  auto m = std::make_shared<const Model>(assemble(defaultDriveDescription()));
  const double w = 300.0 * 2.0 * kPi / 60.0;  // 300 rpm
  auto in = std::make_unique<HarmonicInputs>(*m, w);
  const double tauI = 6.0, tauE = 4.0;
  in->setLoad(m->rotorIndex("camshaftIntake"), tauI);
  in->setLoad(m->rotorIndex("camshaftExhaust"), tauE);
  SimulationOptions opt;
  opt.integrator.method = named<IntegratorMethod>("fixed-verlet");
  opt.integrator.fixed.step = 2.5e-6;
  Simulation sim(m, opt, std::move(in));
  sim.start(0.0);
  const double rCam = m->sprockets[m->rotors[m->rotorIndex("camshaftIntake")].element].gap.pitchRadius;
  // average over one revolution of the crankshaft after 20 ms
  double tight = 0.0, slack = 0.0;
  const int samples = 400;
  const double t0 = 0.02, t1 = t0 + 2.0 * kPi / w;
  sim.advanceTo(t0);
  for (int k = 1; k <= samples; ++k) {
    sim.advanceTo(t0 + (t1 - t0) * k / samples);
    tight += sim.outputs().tightSpanForce;
    slack += sim.outputs().slackSpanForce;
  }
  tight /= samples;
  slack /= samples;
  const double expected = (tauI + tauE) / rCam;
  std::printf("tight %.2f N, slack %.2f N, difference %.2f N, sum(M)/R = %.2f N (%.2f %%)\n", tight, slack, tight - slack,
              expected, 100.0 * (tight - slack - expected) / expected);
  EXPECT_NEAR(tight - slack, expected, 0.03 * expected);
}

// Polygonal action (a classic result): with a very stiff chain, constant crankshaft speed and
// no load, the camshaft speed ripples at the crankshaft meshing frequency z n / 60.
TEST(Polygon, CamshaftSpeedRipplesAtTheMeshingFrequency) {
  auto m = std::make_shared<const Model>(assemble(modifiedDefault([](json& j) {
    j["chain"]["joint"]["stiffness"] = 1.2e9;  // ten times stiffer: chain modes far above meshing
    j["chain"]["joint"]["damping"] = 150.0;
  })));
  const double rpm = 1200.0, w = rpm * 2.0 * kPi / 60.0;
  const double fMesh = 21.0 * rpm / 60.0;  // 420 Hz
  auto in = std::make_unique<HarmonicInputs>(*m, w);
  SimulationOptions opt;
  opt.integrator.method = named<IntegratorMethod>("fixed-verlet");
  opt.integrator.fixed.step = 8e-7;
  Simulation sim(m, opt, std::move(in));
  sim.start(0.0);
  const double t0 = 0.01, span = 0.1;  // 42 meshing periods, resolution 10 Hz
  const int n = 2000;
  std::vector<double> x(n);
  sim.advanceTo(t0);
  const int cam = m->rotorIndex("camshaftIntake");
  for (int k = 0; k < n; ++k) {
    sim.advanceTo(t0 + span * (k + 1) / n);
    x[k] = sim.outputs().rotorRate[cam];
  }
  double mean = 0.0;
  for (double v : x) mean += v / n;
  // discrete Fourier amplitude with a Hann window, 20 Hz .. 2 kHz
  double bestF = 0.0, bestA = 0.0;
  for (double f = 20.0; f <= 2000.0; f += 1.0) {
    std::complex<double> acc = 0.0;
    for (int k = 0; k < n; ++k) {
      const double win = 0.5 - 0.5 * std::cos(2.0 * kPi * k / (n - 1));
      acc += win * (x[k] - mean) * std::exp(std::complex<double>(0.0, -2.0 * kPi * f * span * k / n));
    }
    if (std::abs(acc) > bestA) {
      bestA = std::abs(acc);
      bestF = f;
    }
  }
  std::printf("camshaft speed %.3f rad/s, dominant ripple at %.1f Hz (meshing frequency %.1f Hz)\n", mean, bestF, fMesh);
  // tolerance: the window resolution is 1/span = 10 Hz
  EXPECT_NEAR(bestF, fMesh, 10.0);
  EXPECT_NEAR(mean, 0.5 * w, 0.005 * w);
}
