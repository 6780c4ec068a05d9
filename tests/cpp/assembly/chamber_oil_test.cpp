// A hydraulic chamber's state in both fidelities (its oil content): the tabulated pressure against
// the mixture's law it inverts, its modulus against the effective bulk modulus, cavitation at the
// floor, and the step convergence the content state was made for (the span model's).
#include "assembly/chamber_oil.h"

#include <cmath>

#include <gtest/gtest.h>

#include "dynamics/hydraulic_tensioner.h"
#include "run/inputs.h"
#include "run/simulation.h"
#include "test_util.h"

namespace chaindrive {
namespace {

using test::defaultModel;
using test::named;

TEST(ChamberOil, TablePressureInvertsTheMixtureLaw) {
  const OilDesc oil;
  const ChamberOilLaw law(oil);
  const double floor = oil.vapourPressure - oil.atmosphericPressure;
  for (double p = floor + 10.0; p < 1e8; p = p < 1e5 ? p + 0.37e4 : p * 1.07) {  // through every table interval kind
    const double back = law.pressureAt(law.volumeRatio(p));
    EXPECT_NEAR(back, p, 1e-3 + 1e-7 * std::fabs(p)) << "at " << p << " Pa";  // (the table: about 2e-8)
  }
}

// -v / v' of the law is the effective bulk modulus (dynamics/hydraulic_tensioner.h) within the free
// air's fraction (the law leaves the oil's own compression out of the air's share).
TEST(ChamberOil, ModulusIsTheEffectiveBulkModulusWithinTheAirFraction) {
  const OilDesc oil;
  const ChamberOilLaw law(oil);
  for (double p : {0.0, 1e5, 3e5, 1e6, 5e6, 2e7}) {
    const double h = 1e-4 * std::max(p, 1e5);
    const double v = law.volumeRatio(p), dv = (law.volumeRatio(p + h) - law.volumeRatio(p - h)) / (2.0 * h);
    EXPECT_NEAR(-v / dv, effectiveBulkModulus(oil, p), oil.airFraction * effectiveBulkModulus(oil, p)) << p << " Pa";
  }
}

TEST(ChamberOil, CavitatesAtTheFloor) {
  const OilDesc oil;
  const ChamberOilLaw law(oil);
  const double floor = oil.vapourPressure - oil.atmosphericPressure;
  EXPECT_EQ(law.pressureAt(1.01 * law.floorRatio()), floor);
  EXPECT_NEAR(law.pressureAt(law.floorRatio()), floor, 1e-6);
  EXPECT_GT(law.pressureAt(0.999 * law.floorRatio()), floor);
}

// The chamber pumped up by the guide's motion at 6000 rpm: the tensioner force's mean at a 50 us
// step within 2 % of a 5 us step's (with the pressure as the state the trapezoidal rule lent the
// hydraulic spring energy: 13 % too high at 20 us, the chamber emptied at 50 us).
double meanTensionerForce(double step) {
  const auto m = defaultModel();
  SimulationOptions opt;
  opt.fidelity = named<Fidelity>("span");
  opt.integrator.method = named<IntegratorMethod>("fixed-verlet");
  opt.integrator.fixed.step = step;
  auto in = std::make_unique<HarmonicInputs>(*m, 6000.0 * 2.0 * kPi / 60.0);
  in->addOrder({2.0, 0.2 * kPi / 180.0, 0.0});
  in->addOrder({4.0, 0.1 * kPi / 180.0, 0.0});
  in->setLoad(m->rotorIndex("camshaftIntake"), 8.0);
  in->setLoad(m->rotorIndex("camshaftExhaust"), 8.0);
  Simulation sim(m, opt, std::move(in));
  sim.start(0.0);
  double sum = 0.0;
  int n = 0;
  for (int k = 1; k <= 3000; ++k) {
    sim.advanceTo(k * 1e-4);
    if (k <= 1000) continue;
    sum += sim.outputs().tensionerForce;
    ++n;
  }
  return sum / n;
}

TEST(ChamberOil, PumpedUpChamberConvergesWithTheStep) {
  const double fine = meanTensionerForce(5e-6), coarse = meanTensionerForce(5e-5);
  EXPECT_GT(fine, 300.0);  // pumped up from about 30 N at rest
  EXPECT_NEAR(coarse, fine, 0.02 * fine);
}

}  // namespace
}  // namespace chaindrive
