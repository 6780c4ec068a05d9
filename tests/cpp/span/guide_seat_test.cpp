// The tension guide's seat on its chain (span_model.h: GuideSeat): with it, the span model's
// guide has the link model's stiffness against its turn with the sprockets held (what the seat is
// identified from); a run with it keeps its energy balance and gives the same bits when restored;
// the description's spanModel section (off by default, a number or "identified") and its errors.
#include <cmath>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "dynamics/body_forces.h"
#include "run/simulation.h"
#include "span/span_calibration.h"
#include "span/span_dynamics.h"
#include "span/span_system.h"
#include "statics/preload.h"
#include "test_util.h"

namespace chaindrive::span {
namespace {

using test::constantLoads;
using test::named;

std::shared_ptr<const Model> seatedModel(const char* damping = "joints") {
  return std::make_shared<const Model>(assemble(test::modifiedDefault([&](nlohmann::json& j) {
    j["spanModel"] = {{"guideSeat", "identified"}, {"damping", damping}};
  })));
}

// The guide's stiffness against its turn at the link model's reference pose (the sprockets held
// at its angles), its seat solved at every angle: less the tensioner's, the link model's chain's.
TEST(GuideSeat, GivesTheGuideTheLinkModelsStiffness) {
  const auto m = seatedModel();
  const SpanModel sm = assembleSpanModel(*m);
  ASSERT_TRUE(sm.seats.at(0).present());
  SpanModel unseated = sm;
  unseated.seats.assign(sm.tables.size(), GuideSeat{});
  const SeatIdentification id = identifyGuideSeats(unseated).at(0);
  const InputValues in = seatReferenceInputs(*m);
  PreloadReport report;
  const std::vector<double> yLink = initialState(*m, in, PreloadOptions{}, report);
  // (at the nominal motion of the reference speed, as the identification measures the spans)
  std::vector<double> y = nominalSpanState(sm, kSeatReferenceSpeed);
  for (std::size_t r = 0; r < m->rotors.size(); ++r) y[sm.stateAngle[r]] = yLink[m->rotors[r].stateAngle];
  SpanData d(sm);
  holdChamberAtRest(m->tensioner, in.supplyPressure, d.chamber);
  HeldInputs held(*m);
  held.values = in;
  held.values.crankSpeed = kSeatReferenceSpeed;
  const int guide = sm.tables[0].rotor, angle = sm.stateAngle[guide];
  auto torque = [&](double dpsi) {
    std::vector<double> yy = y;
    yy[angle] += dpsi;
    evaluateSpanForces(sm, d, held, 0.0, yy.data());
    return d.rotorGen[guide];
  };
  const double stiffness = -(torque(1e-6) - torque(-1e-6)) / 2e-6 - id.tensionerStiffness;
  EXPECT_NEAR(stiffness, id.linkStiffness, 0.01 * id.linkStiffness);
  EXPECT_LT(id.linkStiffness, 0.9 * id.seat.spanStiffness);  // (the default drive's chain gives under its guide)
}

SimulationOptions seatedRunOptions() {
  SimulationOptions opt;
  opt.fidelity = named<Fidelity>("span");
  opt.integrator.method = named<IntegratorMethod>("fixed-verlet");
  opt.integrator.fixed.step = 1e-5;
  return opt;
}

// Input work = dissipated energy + change of the stored energy (the seat's spring among it).
TEST(GuideSeat, RunKeepsItsEnergyBalance) {
  const auto m = seatedModel();
  Simulation sim(m, seatedRunOptions(), constantLoads(*m, 3000.0, 8.0, 12.0));
  sim.start(0.0);
  sim.advanceTo(0.02);
  const EnergyTerms a = sim.outputs().energy;
  sim.advanceTo(0.12);
  const EnergyTerms b = sim.outputs().energy;
  const double dissipated = b.dissipated - a.dissipated;
  const double stored = (b.kinetic + b.elastic + b.gravity) - (a.kinetic + a.elastic + a.gravity);
  EXPECT_GT(dissipated, 0.0);
  EXPECT_NEAR(b.inputWork - a.inputWork - stored, dissipated, 0.01 * dissipated);
}

TEST(GuideSeat, RestoredRunIsBitIdentical) {
  const auto m = seatedModel();
  Simulation sim(m, seatedRunOptions(), constantLoads(*m, 3000.0));
  sim.start(0.0);
  sim.advanceTo(0.01);
  sim.restart(0.0);  // (as an FMU's communication point: the integrator from the state alone)
  const long long k1 = sim.gridIndex();
  const std::vector<double> y1 = sim.state();
  std::vector<double> first, second;
  for (int k = 1; k <= 30; ++k) {
    sim.advanceTo(0.01 + k * 1e-4);
    first.push_back(sim.outputs().tensionerForce);
  }
  sim.restoreAt(k1, y1);
  for (int k = 1; k <= 30; ++k) {
    sim.advanceTo(0.01 + k * 1e-4);
    second.push_back(sim.outputs().tensionerForce);
  }
  EXPECT_EQ(first, second);
}

TEST(GuideSeat, OffByDefaultAndTheSectionsErrorsNameTheField) {
  EXPECT_FALSE(assembleSpanModel(*test::defaultModel()).seats.at(0).present());
  EXPECT_EQ(test::defaultModel()->description.spanModel.damping, SpanModelDesc::Source::Off);
  const auto problem = [](const nlohmann::json& section) {
    return test::problemLines(test::problemsOf([&](nlohmann::json& j) { j["spanModel"] = section; }));
  };
  EXPECT_NE(problem({{"guideSeat", true}}).find("spanModel.guideSeat: must be a number (N m/rad) or \"none\""),
            std::string::npos);
  EXPECT_NE(problem({{"guideSeat", "maybe"}}).find("spanModel.guideSeat"), std::string::npos);
  EXPECT_NE(problem({{"damping", -2.0}}).find("spanModel.damping: -2"), std::string::npos);
  EXPECT_NE(problem({{"dampers", "identified"}}).find("spanModel.dampers"), std::string::npos);
  const DriveDescription given = test::modifiedDefault([](nlohmann::json& j) {
    j["spanModel"] = {{"guideSeat", 5000.0}, {"damping", 3.0}};
  });
  EXPECT_EQ(given.spanModel.guideSeat, SpanModelDesc::Source::Given);
  EXPECT_EQ(given.spanModel.guideSeatStiffness, 5000.0);
  EXPECT_EQ(given.spanModel.dampingScale, 3.0);
}

}  // namespace
}  // namespace chaindrive::span
