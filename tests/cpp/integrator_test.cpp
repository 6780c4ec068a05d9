// Integrators: failures are reported with the time and the reason; identical runs are bit for
// bit identical; the methods agree with each other on a short run.
#include <gtest/gtest.h>

#include <cmath>

#include "test_util.h"

using namespace chaindrive;
using namespace chaindrive::test;

namespace {

std::shared_ptr<const Model> defaultModel() {
  static const std::shared_ptr<const Model> m = std::make_shared<const Model>(assemble(defaultDriveDescription()));
  return m;
}

std::unique_ptr<InputSignal> loads(const Model& m, double rpm) {
  auto in = std::make_unique<HarmonicInputs>(m, rpm * 2.0 * kPi / 60.0);
  in->setLoad(m.rotorIndex("camshaftIntake"), 3.0);
  in->setLoad(m.rotorIndex("camshaftExhaust"), 3.0);
  return in;
}

std::vector<double> tensionerSeries(const std::string& method, double rtolOrStep, double tEnd, int n) {
  auto m = defaultModel();
  SimulationOptions opt;
  opt.integrator.method = method;
  if (method.rfind("fixed", 0) == 0 || method == "arkode-erk-fixed") opt.integrator.fixedStep = rtolOrStep;
  else opt.integrator.rtol = rtolOrStep;
  Simulation sim(m, opt, loads(*m, 3000.0));
  sim.start(0.0);
  std::vector<double> out;
  for (int k = 1; k <= n; ++k) {
    sim.advanceTo(tEnd * k / n);
    out.push_back(sim.outputs().tensionerForce);
  }
  return out;
}

}  // namespace

TEST(Integrators, UnknownNameListsTheKnownOnes) {
  auto m = defaultModel();
  SimulationOptions opt;
  opt.integrator.method = "rk45";
  try {
    Simulation sim(m, opt, loads(*m, 1000.0));
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("fixed-verlet"), std::string::npos) << e.what();
  }
}

// An explicit step far beyond the stability limit (about 3.5 us for this drive) blows up; the
// run stops with an IntegrationError naming the time and the joint, not with garbage.
TEST(Integrators, BlowUpIsDetectedAndReported) {
  auto m = defaultModel();
  SimulationOptions opt;
  opt.integrator.method = "fixed-verlet";
  opt.integrator.fixedStep = 8e-6;
  Simulation sim(m, opt, loads(*m, 3000.0));
  sim.start(0.0);
  try {
    for (int k = 1; k <= 100; ++k) sim.advanceTo(1e-4 * k);
    FAIL() << "expected a blow-up";
  } catch (const IntegrationError& e) {
    EXPECT_GT(e.time(), 0.0);
    EXPECT_LT(e.time(), 0.01);
    EXPECT_TRUE(e.reason().find("blow-up") != std::string::npos || e.reason().find("non-finite") != std::string::npos)
        << e.reason();
    std::printf("reported: %s\n", e.what());
  }
}

// CVODE stopping on too much work is an error with its flag name and the time reached.
TEST(Integrators, SolverFailureCarriesTheFlagAndTime) {
  auto m = defaultModel();
  SimulationOptions opt;
  opt.integrator.method = "cvode-bdf-klu";
  opt.integrator.rtol = 1e-6;
  opt.integrator.maxStepsPerOutput = 20;
  Simulation sim(m, opt, loads(*m, 3000.0));
  sim.start(0.0);
  try {
    sim.advanceTo(1e-3);
    FAIL() << "expected a failure";
  } catch (const IntegrationError& e) {
    EXPECT_NE(e.reason().find("CV_TOO_MUCH_WORK"), std::string::npos) << e.reason();
    EXPECT_GT(e.time(), 0.0);
  }
}

TEST(Integrators, IdenticalRunsAreBitIdentical) {
  const auto a = tensionerSeries("fixed-verlet", 2e-6, 2e-3, 20);
  const auto b = tensionerSeries("fixed-verlet", 2e-6, 2e-3, 20);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_EQ(a[k], b[k]) << "sample " << k;
  const auto c = tensionerSeries("cvode-bdf-klu", 1e-4, 1e-3, 5);
  const auto d = tensionerSeries("cvode-bdf-klu", 1e-4, 1e-3, 5);
  for (std::size_t k = 0; k < c.size(); ++k) EXPECT_EQ(c[k], d[k]) << "sample " << k;
}

// The methods solve the same equations: over 2 ms the tensioner force of each stays within 2 N
// (about 2 % of its level) of a fine fixed-step reference.
TEST(Integrators, MethodsAgreeOnAShortRun) {
  const double tEnd = 2e-3;
  const int n = 10;
  const auto ref = tensionerSeries("fixed-verlet", 5e-7, tEnd, n);
  struct Case {
    const char* method;
    double setting;
  };
  for (const Case& c : {Case{"fixed-verlet", 2e-6}, Case{"arkode-erk", 1e-6}, Case{"cvode-bdf-klu", 1e-5}}) {
    const auto x = tensionerSeries(c.method, c.setting, tEnd, n);
    double worst = 0.0;
    for (int k = 0; k < n; ++k) worst = std::max(worst, std::fabs(x[k] - ref[k]));
    std::printf("%-14s largest tensioner-force deviation from the reference over 2 ms: %.4f N\n", c.method, worst);
    EXPECT_LT(worst, 2.0) << c.method;
  }
}
