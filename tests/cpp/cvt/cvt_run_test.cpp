// The checks of a stationary CVT run (paper example 4.1) on the default CVT at 2000 rpm.
#include "cvt/cvt_run.h"

#include <cmath>
#include <memory>
#include <stdexcept>

#include <gtest/gtest.h>

#include "allocation_counter.h"
#include "cvt/cvt_assembly.h"
#include "dynamics/pin_sheave.h"
#include "run/simulation.h"
#include "test_util.h"

using namespace chaindrive;
using chaindrive::test::named;

namespace {

// 0.08 s (1.3 chain revolutions) at 0.5 us, the means over its second half.
CvtRunResult stationaryRun(double loadTorque) {
  static const auto model = std::make_shared<const Model>(assembleCvt(defaultCvtDescription()));
  CvtRunOptions opt;
  opt.loadTorque = loadTorque;
  opt.duration = 0.08;
  opt.outputStep = 1e-4;
  opt.integrator.fixed.step = 5e-7;
  return runCvt(model, opt);
}

}  // namespace

TEST(CvtRun, NoLoadRunsAtTheGeometricRatio) {
  CvtLayout layout;
  const Model m = assembleCvt(defaultCvtDescription(), &layout);
  const CvtSummary s = stationaryRun(0.0).summary;
  EXPECT_LT(std::fabs(s.speedRatioError), 0.005);  // within 0.5 %
  EXPECT_LT(std::fabs(s.energyBalanceError), 0.01);
  // the sheaves press the pins of the wraps and none of the strands': as many as the wrap holds
  for (int k = 0; k < 2; ++k) {
    const double wrapPins = layout.wrapAngle[k] * layout.runningRadius[k] / m.chain.pitch;
    EXPECT_NEAR(s.pinsInContact[k], wrapPins, 1.5) << "pulley " << k;
  }
}

TEST(CvtRun, LoadedRunBalancesTorqueAndEnergyAndSlipsMore) {
  const CvtSummary none = stationaryRun(0.0).summary, half = stationaryRun(50.0).summary,
                   full = stationaryRun(100.0).summary;
  for (const CvtSummary* s : {&half, &full}) {
    // (F_tight - F_slack) r2 = the torque the chain turns the driven pulley with, within 2 %
    EXPECT_NEAR(s->torqueBalanceDriven, s->drivenTorque, 0.02 * std::fabs(s->drivenTorque));
    EXPECT_LT(std::fabs(s->energyBalanceError), 0.01);
    EXPECT_GT(s->tightStrandForce, s->slackStrandForce);
  }
  EXPECT_NEAR(full.drivenTorque, 100.0, 2.0);  // stationary: the chain's torque holds the load
  EXPECT_LT(none.slip, half.slip);
  EXPECT_LT(half.slip, full.slip);
}

TEST(CvtRun, SameInputsSameBits) {
  const auto model = std::make_shared<const Model>(assembleCvt(defaultCvtDescription()));
  CvtRunOptions opt;
  opt.loadTorque = 80.0;
  opt.duration = 0.005;
  const CvtRunResult a = runCvt(model, opt), b = runCvt(model, opt);
  ASSERT_EQ(a.samples.size(), b.samples.size());
  for (std::size_t k = 0; k < a.samples.size(); ++k) {
    EXPECT_EQ(a.samples[k].cvt.drivenSpeed, b.samples[k].cvt.drivenSpeed);
    EXPECT_EQ(a.samples[k].cvt.tightStrandForce, b.samples[k].cvt.tightStrandForce);
  }
}

TEST(CvtRun, MethodsWithoutPinSheaveJacobiansAreRefused) {
  const auto model = std::make_shared<const Model>(assembleCvt(defaultCvtDescription()));
  for (const char* method : {"cvode-bdf-klu", "fixed-newmark", "fixed-verlet-implicit-damping"}) {
    SimulationOptions so;
    so.integrator.method = named<IntegratorMethod>(method);
    try {
      Simulation sim(model, so, std::make_unique<HeldInputs>(*model));
      FAIL() << method << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("allowed on a CVT"), std::string::npos) << e.what();
    }
  }
  for (const char* contactMethod : {"event-driven"}) {
    SimulationOptions so;
    so.contactMethod = named<ContactMethod>(contactMethod);
    try {
      Simulation sim(model, so, std::make_unique<HeldInputs>(*model));
      FAIL() << contactMethod << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("allowed: compliant, time-stepping"), std::string::npos) << e.what();
    }
  }
}

// Time stepping with the pins' friction as complementarity (Moreau-Jean, Lemke): a short loaded
// run from the nominal state keeps every pressed pin's friction within its Coulomb disc (the
// polygon lies inside it), loads no pin of the strands, turns the driven pulley forwards, and
// repeats to the bit.
TEST(CvtRun, TimeSteppingKeepsThePinsFrictionInTheirCone) {
  const auto model = std::make_shared<const Model>(assembleCvt(defaultCvtDescription()));
  CvtRunOptions opt;
  opt.contactMethod = named<ContactMethod>("time-stepping");
  opt.integrator.fixed.step = 5e-6;
  opt.integrator.rigid.frictionFacets = 4;
  opt.loadTorque = 100.0;
  opt.duration = 0.002;
  opt.outputStep = 1e-4;
  const CvtRunResult a = runCvt(model, opt), b = runCvt(model, opt);
  ASSERT_TRUE(a.contactStats.has_value());
  EXPECT_EQ(a.contactStats->lcpSolves, a.steps);
  const PinSheaveLaw& law = model->pinSheave;
  int pressed = 0;
  for (std::size_t k = 0; k < a.samples.size(); ++k) {
    const CvtOutputs& c = a.samples[k].cvt;
    const double friction = std::hypot(c.pinRadialFriction, c.pinCircumferentialFriction);
    EXPECT_LE(friction, pinFrictionLimit(law, c.pinAxialForce) * (1.0 + 1e-9) + 1e-9) << a.samples[k].time;
    if (c.pinAxialForce == 0.0) {
      EXPECT_EQ(friction, 0.0) << a.samples[k].time;
    }
    pressed += c.pinAxialForce > 0.0 ? 1 : 0;
    EXPECT_GT(c.drivenSpeed, 0.0);
    EXPECT_EQ(c.drivenSpeed, b.samples[k].cvt.drivenSpeed);
    EXPECT_EQ(c.tightStrandForce, b.samples[k].cvt.tightStrandForce);
  }
  EXPECT_GT(pressed, 0);
}

// Time stepping with rigid pins: the pins close on the running circles with Newton impacts (the
// default CVT's restitution 0), press the sheaves with a normal force and no radial friction, and
// their circumferential friction stays within the wedge's mu / sin(beta) of it.
TEST(CvtRun, RigidPinsCloseWithImpactsAndTheWedgesFriction) {
  const auto model = std::make_shared<const Model>(assembleCvt(defaultCvtDescription()));
  CvtRunOptions opt;
  opt.contactMethod = named<ContactMethod>("time-stepping");
  opt.integrator.rigid.rigidPins = true;
  opt.integrator.fixed.step = 5e-6;
  opt.loadTorque = 100.0;
  opt.duration = 0.004;
  opt.outputStep = 1e-4;
  const CvtRunResult r = runCvt(model, opt);
  ASSERT_TRUE(r.contactStats.has_value());
  EXPECT_GT(r.contactStats->impacts, 0);
  const PinSheaveLaw& law = model->pinSheave;
  const double wedgeFriction = law.friction / (law.tanWedge * law.cosWedge);
  int pressed = 0;
  for (const CvtSample& s : r.samples) {
    const CvtOutputs& c = s.cvt;
    EXPECT_GE(c.pinNormalForce, 0.0);
    EXPECT_EQ(c.pinRadialFriction, 0.0);
    EXPECT_LE(std::fabs(c.pinCircumferentialFriction), wedgeFriction * c.pinNormalForce * (1.0 + 1e-9) + 1e-9);
    pressed += c.pinNormalForce > 0.0 ? 1 : 0;
    if (s.time > 0.0) {  // (the forces are a step's)
      EXPECT_GT(c.pinsInContact[0] + c.pinsInContact[1], 20.0) << s.time;  // the wraps' pins
    }
  }
  EXPECT_GT(pressed, 0);
}

// The ratio input moves the sheaves: the chain climbs on the driving pulley and sinks into the
// driven one until the driven pulley turns at the new geometric ratio.
TEST(CvtRun, RatioInputShiftsTheChain) {
  const auto model = std::make_shared<const Model>(assembleCvt(defaultCvtDescription()));
  SimulationOptions so;
  so.integrator.method = named<IntegratorMethod>("fixed-verlet");
  so.integrator.fixed.step = 1e-6;
  auto inputs = std::make_unique<HeldInputs>(*model);
  HeldInputs& held = *inputs;
  const double w = 2000.0 * 3.14159265358979323846 / 30.0;
  held.values.crankSpeed = w;
  held.values.ratio = 1.0;
  Simulation sim(model, so, std::move(inputs));
  sim.startFrom(0.0, cvtNominalState(*model, w));
  // 1.0 -> 1.5 over 100 ms in steps of 0.1 ms, then 60 ms held
  for (int k = 1; k <= 1600; ++k) {
    held.values.ratio = 1.0 + 0.5 * std::min(1.0, k / 1000.0);
    sim.advanceTo(k * 1e-4);
  }
  const Outputs& out = sim.outputs();
  const CvtOutputs c = cvtOutputs(*model, *sim.outputData(), out, -1);
  EXPECT_NEAR(c.drivingSpeed / c.drivenSpeed, 1.5, 0.015);  // within 1 % of the new ratio
  EXPECT_LT(std::fabs(c.slip), 0.005);
}

// A communication step of the fixed-step mode on a CVT (restart, steps with the ratio input
// moving the sheaves, the CVT's outputs) makes no heap allocation: what hardware-in-the-loop needs.
TEST(CvtRun, FixedStepCommunicationStepAllocatesNothing) {
  if (!chaindrive::test::allocationCountingAvailable()) GTEST_SKIP() << "allocation counting needs glibc";
  const auto model = std::make_shared<const Model>(assembleCvt(defaultCvtDescription()));
  for (const char* method : {"fixed-verlet", "fixed-verlet-implicit-joint-damping"}) {
    SimulationOptions so;
    so.integrator.method = named<IntegratorMethod>(method);
    so.integrator.fixed.step = 1e-6;
    auto inputs = std::make_unique<HeldInputs>(*model);
    HeldInputs& held = *inputs;
    held.values.crankSpeed = 200.0;
    held.values.ratio = 1.0;
    Simulation sim(model, so, std::move(inputs));
    sim.startFrom(0.0, cvtNominalState(*model, 200.0));
    sim.advanceTo(1e-4);
    (void)cvtOutputs(*model, *sim.outputData(), sim.outputs(), -1);
    double t = 1e-4;
    const long n = chaindrive::test::countAllocations([&] {
      for (int k = 0; k < 20; ++k) {
        held.values.ratio = 1.0 + 1e-3 * k;
        sim.restart(0.0);
        t += 1e-4;
        sim.advanceTo(t);
        (void)cvtOutputs(*model, *sim.outputData(), sim.outputs(), -1).slip;
      }
    });
    EXPECT_EQ(n, 0) << method;
  }
}
