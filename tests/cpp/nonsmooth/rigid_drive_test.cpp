// The default drive with rigid contacts: time stepping runs and is deterministic, its contact
// forces carry the load; the event-driven method on the drive reports its event storm as a
// failure with the time and the rate; ideal joints hold as bilateral constraints.
#include <gtest/gtest.h>

#include <cmath>

#include "test_util.h"

using namespace chaindrive;
using namespace chaindrive::test;

namespace {

std::vector<double> run(const std::string& method, const std::string& joints, double step, double tEnd, int n,
                        Simulation** keep = nullptr) {
  auto m = defaultModel();
  SimulationOptions opt;
  opt.contactMethod = named<ContactMethod>(method);
  opt.jointModel = namedOrDrive<JointModel>(joints);
  opt.integrator.fixed.step = step;
  auto sim = std::make_unique<Simulation>(m, opt, constantLoads(*m, 3000.0));
  sim->start(0.0);
  std::vector<double> out;
  for (int k = 1; k <= n; ++k) {
    sim->advanceTo(tEnd * k / n);
    const Outputs& o = sim->outputs();
    out.push_back(o.tensionerForce);
    out.push_back(o.tightSpanForce);
    out.push_back(o.crankTorque);
    EXPECT_GT(o.contacts, 10) << "closed contacts at sample " << k;
  }
  if (keep) *keep = sim.release();
  return out;
}

}  // namespace

// Time stepping with journal-bearing joints (the step must resolve them: 2 us): finite,
// plausible forces (tensioner 0..3 kN, spans below the chain's 9 kN strength), one LCP per step,
// bit-identical on repetition.
TEST(RigidDrive, TimeSteppingRunsDeterministically) {
  Simulation* sim = nullptr;
  const auto a = run("time-stepping", "", 2e-6, 1e-3, 5, &sim);
  std::unique_ptr<Simulation> owner(sim);
  for (std::size_t k = 0; k < a.size(); k += 3) {
    EXPECT_TRUE(std::isfinite(a[k]) && std::isfinite(a[k + 1]) && std::isfinite(a[k + 2]));
    EXPECT_GE(a[k], 0.0);
    EXPECT_LT(a[k], 3000.0);
    EXPECT_LT(std::fabs(a[k + 1]), 9000.0);
  }
  const ns::NsStats* st = owner->contactStats();
  ASSERT_NE(st, nullptr);
  EXPECT_EQ(st->lcpSolves, st->steps);
  EXPECT_EQ(st->steps, 500);
  EXPECT_GT(st->lcpSizeMax, 30);  // tens of closed contacts, three LCP variables each with friction
  std::printf("time stepping: %lld steps, mean LCP size %.1f, max %lld, %.1f pivots per LCP\n", st->steps,
              static_cast<double>(st->lcpSizeSum) / static_cast<double>(st->lcpSolves), st->lcpSizeMax,
              static_cast<double>(st->pivots) / static_cast<double>(st->lcpSolves));
  const auto b = run("time-stepping", "", 2e-6, 1e-3, 5);
  EXPECT_EQ(a, b);
}

// The event-driven method meets an event storm on the drive (contacts of vibrating links open
// and close every fraction of a microsecond): with a cap of 1e5 events per second it stops with a
// runaway-event error naming the count and the time, instead of grinding on.
TEST(RigidDrive, EventDrivenRefusesAHydraulicTensioner) {
  SimulationOptions opt;
  opt.contactMethod = named<ContactMethod>("event-driven");
  try {
    Simulation sim(defaultModel(), opt, constantLoads(*defaultModel(), 3000.0));
    FAIL() << "expected the combination to be refused";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'event-driven' does not integrate a hydraulic tensioner's chamber"),
              std::string::npos) << e.what();
  }
}

TEST(RigidDrive, EventDrivenReportsTheEventStorm) {
  auto m = std::make_shared<const Model>(assemble(test::modifiedDefault(test::useSpringDamperTensioner)));
  SimulationOptions opt;
  opt.contactMethod = named<ContactMethod>("event-driven");
  opt.integrator.adaptive.rtol = 1e-4;
  opt.integrator.eventDriven.maxEventsPerSecond = 1e5;
  Simulation sim(m, opt, constantLoads(*m, 3000.0));
  sim.start(0.0);
  try {
    for (int k = 1; k <= 100; ++k) sim.advanceTo(1e-4 * k);
    FAIL() << "expected a runaway-event failure";
  } catch (const IntegrationError& e) {
    EXPECT_NE(e.reason().find("runaway events"), std::string::npos) << e.reason();
    EXPECT_EQ(e.failureKind(), FailureKind::RunawayEvents) << e.kind();
    EXPECT_LT(e.time(), 0.01);
    std::printf("reported: %s\n", e.what());
  }
}

// Ideal joints: the chain as bilateral constraints; time stepping keeps every joint closed to
// 1e-6 m (the constraints are stabilised at velocity level).
TEST(RigidDrive, IdealJointsHold) {
  Simulation* sim = nullptr;
  const auto a = run("time-stepping", "ideal", 1e-5, 1e-3, 5, &sim);
  std::unique_ptr<Simulation> owner(sim);
  for (double v : a) EXPECT_TRUE(std::isfinite(v));
  EXPECT_LT(owner->outputs().maxJointDeformation, 1e-6);
}

TEST(RigidDrive, CompliantContactsWithIdealJointsIsAnError) {
  auto m = defaultModel();
  SimulationOptions opt;
  opt.contactMethod = named<ContactMethod>("compliant");
  opt.jointModel = namedOrDrive<JointModel>("ideal");
  EXPECT_THROW(Simulation(m, opt, constantLoads(*m, 3000.0)), std::invalid_argument);
}
