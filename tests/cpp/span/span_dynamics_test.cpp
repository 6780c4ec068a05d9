// The span model against analytic references (static tension split, polygonal speed
// fluctuation, span eigenfrequency), its options' errors, and the bit-identity of a run restored
// from a saved state (its calibration against the link model's statics: span_calibration_test.cpp).
#include "span/span_dynamics.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "run/inputs.h"
#include "run/simulation.h"
#include "test_util.h"

namespace chaindrive::span {
namespace {

using test::constantLoads;
using test::defaultModel;
using test::named;
using test::namedOrDrive;

SimulationOptions spanOptions(const std::string& integrator = "fixed-verlet", double step = 2e-5) {
  SimulationOptions opt;
  opt.fidelity = named<Fidelity>("span");
  opt.integrator.method = named<IntegratorMethod>(integrator);
  opt.integrator.fixed.step = step;
  opt.integrator.adaptive.rtol = 1e-8;
  return opt;
}

double pitchRadius(const Model& m, const std::string& sprocket) {
  return m.sprockets[m.description.sprocketIndex(sprocket)].gap.pitchRadius;
}

// At slow constant speed the camshafts' mean load torques are carried by the difference of the
// tight and slack span forces at the camshaft sprockets: T_tight - T_slack = sum(M) / R_cam.
TEST(SpanDynamics, StaticTensionSplitCarriesTheCamshaftTorques) {
  const auto m = defaultModel();
  Simulation sim(m, spanOptions(), constantLoads(*m, 60.0, 3.0, 5.0));
  sim.start(0.0);
  double sum = 0.0;
  int n = 0;
  for (int k = 1; k <= 2000; ++k) {
    sim.advanceTo(k * 1e-3);
    if (k <= 1000) continue;
    const Outputs& o = sim.outputs();
    sum += o.tightSpanForce - o.slackSpanForce;
    ++n;
  }
  const double expected = (3.0 + 5.0) / pitchRadius(*m, "camshaftIntake");
  EXPECT_NEAR(sum / n, expected, 0.01 * expected);
}

// The chain leaving a sprocket turning at constant speed moves at omega R cos(theta_rel): over
// one pitch its speed swings between omega R cos(pi / z) and omega R (Mahalingam's ratio).
TEST(SpanDynamics, PolygonalSpeedOfAFreeSpanFollowsCosPiOverZ) {
  const auto m = defaultModel();
  const SpanModel sm = assembleSpanModel(*m, false);
  SpanData d(sm);
  const double w = 100.0;
  HarmonicInputs in(*m, w);
  std::vector<double> y(sm.nStates, 0.0);
  for (std::size_t r = 0; r < m->rotors.size(); ++r) y[sm.stateAngle[r]] = m->rotors[r].initialAngle;
  const int crank = m->drivenRotor;
  double vMin = 1e9, vMax = 0.0;
  for (int k = 0; k < 2000; ++k) {
    y[sm.stateAngle[crank]] = m->rotors[crank].initialAngle + m->sense * k * (2.0 * kPi / 21.0) / 1000.0;
    evaluateSpanForces(sm, d, in, 0.0, y.data());
    vMin = std::min(vMin, d.spans[0].speedFrom);
    vMax = std::max(vMax, d.spans[0].speedFrom);
  }
  const double ratio = std::cos(kPi / 21.0);
  EXPECT_NEAR(vMax, w * pitchRadius(*m, "crankshaft"), 1e-6 * vMax);  // sampled 1000 times per pitch
  EXPECT_NEAR(1.0 - vMin / vMax, 1.0 - ratio, 0.02 * (1.0 - ratio));
}

// A two-sprocket drive without damping: the free camshaft oscillates against its two spans at
// f = sqrt(sum k_i R_i^2 / J) / (2 pi), with k_i = joint stiffness / links of span i, R_i the
// effective radius at the span's end on the camshaft, J the camshaft with the chain lumped on it.
TEST(SpanDynamics, SpanEigenfrequencyIsTheSpringMassValue) {
  const DriveDescription desc = test::modifiedDefault([](nlohmann::json& j) {
    j["chain"]["numberOfLinks"] = 80;
    j["chain"]["route"] = {"crankshaft", "camshaft"};
    j["chain"]["joint"]["damping"] = 0.0;
    j["sprockets"][1]["name"] = "camshaft";
    j["sprockets"][1]["center"] = {0.0, 0.2285};
    j["sprockets"].erase(2);
    j["guides"] = nlohmann::json::array();
    j.erase("tensioner");
    j["closure"] = {{"kind", "sprocket-shift"}, {"element", "camshaft"}, {"direction", {0.0, 1.0}},
                    {"shiftMin", -0.01}, {"shiftMax", 0.01}};
    j["measurement"] = {{"tightSpan", {"camshaft", "crankshaft"}}, {"slackSpan", {"crankshaft", "camshaft"}}};
  });
  const auto m = std::make_shared<const Model>(assemble(desc));
  const int cam = m->rotorIndex("camshaft");
  // the analytic value from the drive's data and the assembled path
  const auto& seg = m->path.segments();
  const double rho = m->chain.mass / m->chain.pitch, R = pitchRadius(*m, "camshaft");
  const SpanModel sm = assembleSpanModel(*m);
  double stiffness = 0.0, inertia = m->rotors[cam].inertia + rho * seg[2].length * R * R;
  for (int i = 0; i < 2; ++i) {
    const double len = seg[2 * i + 1].length;
    const SpanEnd& end = i == 0 ? sm.spans[0].to : sm.spans[1].from;
    stiffness += m->chain.jointStiffness * m->chain.pitch / len * std::pow(R * std::cos(end.phase), 2);
    inertia += 0.5 * rho * len * R * R;
  }
  const double expected = std::sqrt(stiffness / inertia) / (2.0 * kPi);
  // the simulated free vibration: zero crossings of the camshaft's rate
  SimulationOptions opt = spanOptions("fixed-verlet", 1e-7);
  opt.preload.enabled = false;
  Simulation sim(m, opt, std::make_unique<HarmonicInputs>(*m, 0.0));
  std::vector<double> y0(sm.nStates, 0.0);
  for (std::size_t r = 0; r < m->rotors.size(); ++r) y0[sm.stateAngle[r]] = m->rotors[r].initialAngle;
  y0[sm.stateAngle[cam]] += 1e-5;
  sim.startFrom(0.0, y0);
  std::vector<double> crossings;
  double prev = 0.0;
  for (int k = 1; k <= 20000 && crossings.size() < 11; ++k) {
    sim.advanceTo(k * 1e-6);
    const double w = sim.state()[sm.stateRate[cam]];
    if (k > 1 && (w > 0.0) != (prev > 0.0)) crossings.push_back(k * 1e-6);
    prev = w;
  }
  ASSERT_EQ(crossings.size(), 11u);
  const double measured = 5.0 / (crossings.back() - crossings.front());
  EXPECT_NEAR(measured, expected, 0.02 * expected) << "analytic " << expected << " Hz";
}

// What the span fidelity cannot run is an error naming the option and what is allowed.
TEST(SpanDynamics, OptionsItCannotRunAreErrors) {
  const auto m = defaultModel();
  auto message = [&](const std::function<void(SimulationOptions&)>& edit) {
    SimulationOptions opt = spanOptions();
    edit(opt);
    try {
      Simulation sim(m, opt, constantLoads(*m, 1000.0));
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message([](SimulationOptions& o) { o.contactMethod = named<ContactMethod>("time-stepping"); }).find("fidelity 'span'"),
            std::string::npos);
  EXPECT_NE(message([](SimulationOptions& o) { o.jointModel = namedOrDrive<JointModel>("ideal"); }).find("journal-bearing"), std::string::npos);
}

// A run restored from a saved state at grid point k1 repeats its outputs bit for bit.
TEST(SpanDynamics, RestoredRunIsBitIdentical) {
  const auto m = defaultModel();
  for (const std::string integrator : {"fixed-verlet", "cvode-bdf-klu", "arkode-erk"}) {
    Simulation sim(m, spanOptions(integrator, 2e-5), constantLoads(*m, 3000.0));
    sim.start(0.0);
    sim.advanceTo(0.01);
    sim.restart(0.0);
    const long long k1 = sim.gridIndex();
    const std::vector<double> y1 = sim.state();
    std::vector<double> first, second;
    for (int k = 1; k <= 50; ++k) {
      sim.advanceTo(0.01 + k * 1e-4);
      first.push_back(sim.outputs().tensionerForce);
    }
    sim.restoreAt(k1, y1);
    for (int k = 1; k <= 50; ++k) {
      sim.advanceTo(0.01 + k * 1e-4);
      second.push_back(sim.outputs().tensionerForce);
    }
    for (std::size_t i = 0; i < first.size(); ++i) ASSERT_EQ(first[i], second[i]) << integrator << " output " << i;
  }
}

}  // namespace
}  // namespace chaindrive::span
