// Integrators: failures are reported with the time and the reason; identical runs are bit for
// bit identical; the methods agree with each other on a short run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>

#include "allocation_counter.h"
#include "test_util.h"

using namespace chaindrive;
using namespace chaindrive::test;

namespace {

// Samples of one output (by member pointer) of a 3000 rpm run with constant camshaft loads.
std::vector<double> series(const std::string& method, double rtolOrStep, double tEnd, int n,
                           double (*get)(const Outputs&)) {
  auto m = defaultModel();
  SimulationOptions opt;
  opt.integrator.method = named<IntegratorMethod>(method);
  if (method.rfind("fixed", 0) == 0 || method == "arkode-erk-fixed") opt.integrator.fixed.step = rtolOrStep;
  else opt.integrator.adaptive.rtol = rtolOrStep;
  Simulation sim(m, opt, constantLoads(*m, 3000.0));
  sim.start(0.0);
  std::vector<double> out;
  for (int k = 1; k <= n; ++k) {
    sim.advanceTo(tEnd * k / n);
    out.push_back(get(sim.outputs()));
  }
  return out;
}

double tensionerForce(const Outputs& o) { return o.tensionerForce; }
double guideAngle(const Outputs& o) { return o.rotorAngle[3]; }  // rotors: crank, exhaust, intake, tension guide
double camAngle(const Outputs& o) { return o.rotorAngle[2]; }

std::vector<double> tensionerSeries(const std::string& method, double rtolOrStep, double tEnd, int n) {
  return series(method, rtolOrStep, tEnd, n, tensionerForce);
}

}  // namespace

TEST(Integrators, UnknownNameListsTheKnownOnes) {
  try {
    parseChoice<IntegratorMethod>("rk45", "solver.method");
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "solver.method: 'rk45' is unknown; allowed: cvode-bdf-klu, cvode-bdf-band, arkode-erk, arkode-erk-fixed, "
              "fixed-verlet, fixed-verlet-implicit-damping, fixed-verlet-implicit-joint-damping, fixed-newmark");
  }
}

// Every choice's table: names and values one to one, so that parsing a name gives the value back.
template <class E>
void expectRoundTrip() {
  for (const auto& c : ChoiceNames<E>::table) {
    EXPECT_EQ(choiceOf<E>(c.name), c.value) << c.name;
    EXPECT_STREQ(choiceName(c.value), c.name);
  }
  EXPECT_FALSE(choiceOf<E>("").has_value());
}

TEST(Choices, NamesAndValuesAreOneToOne) {
  expectRoundTrip<IntegratorMethod>();
  expectRoundTrip<ContactMethod>();
  expectRoundTrip<JointModel>();
  expectRoundTrip<ContactLawModel>();
  expectRoundTrip<Fidelity>();
  expectRoundTrip<Rotation>();
  EXPECT_EQ(choiceOf<ContactMethod>("lcp"), std::nullopt);
  EXPECT_EQ(unknownChoiceText("beam", choiceNames<Fidelity>()), "'beam' is unknown; allowed: link, span");
}

// An explicit step far beyond the stability limit (about 3.5 us for this drive) blows up; the
// run stops with an IntegrationError naming the time and the joint, not with garbage.
TEST(Integrators, BlowUpIsDetectedAndReported) {
  auto m = defaultModel();
  SimulationOptions opt;
  opt.integrator.method = named<IntegratorMethod>("fixed-verlet");
  opt.integrator.fixed.step = 8e-6;
  Simulation sim(m, opt, constantLoads(*m, 3000.0));
  sim.start(0.0);
  try {
    for (int k = 1; k <= 100; ++k) sim.advanceTo(1e-4 * k);
    FAIL() << "expected a blow-up";
  } catch (const IntegrationError& e) {
    EXPECT_GT(e.time(), 0.0);
    EXPECT_LT(e.time(), 0.01);
    EXPECT_TRUE(e.reason().find("blow-up") != std::string::npos || e.reason().find("non-finite") != std::string::npos)
        << e.reason();
    // the kind is the one the check that found it set, and its keyword agrees with the text
    EXPECT_TRUE(e.failureKind() == FailureKind::BlowUp || e.failureKind() == FailureKind::NonFinite) << e.kind();
    EXPECT_NE(e.reason().find(e.kind()), std::string::npos) << e.kind() << ": " << e.reason();
    std::printf("reported: %s\n", e.what());
  }
}

// CVODE stopping on too much work is an error with its flag name and the time reached.
TEST(Integrators, SolverFailureCarriesTheFlagAndTime) {
  auto m = defaultModel();
  SimulationOptions opt;
  opt.integrator.method = named<IntegratorMethod>("cvode-bdf-klu");
  opt.integrator.adaptive.rtol = 1e-6;
  opt.integrator.adaptive.maxStepsPerOutput = 20;
  Simulation sim(m, opt, constantLoads(*m, 3000.0));
  sim.start(0.0);
  try {
    sim.advanceTo(1e-3);
    FAIL() << "expected a failure";
  } catch (const IntegrationError& e) {
    EXPECT_NE(e.reason().find("CV_TOO_MUCH_WORK"), std::string::npos) << e.reason();
    EXPECT_EQ(e.failureKind(), FailureKind::StepSizeCollapse) << e.kind();
    EXPECT_STREQ(e.kind(), "step-size-collapse");
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

// The methods solve the same equations. Compared on position-level outputs (NUMERICS: errors
// on continuous quantities, not on velocities at impacts), over 2 ms, before the drift of the
// chaotic link-level motion sets in. Reference: fixed-verlet at 0.5 us.
//  - the adaptive methods stay within 1e-6 rad of it in tension-guide and camshaft angle, a
//    fraction of a percent of what these angles move in the window (printed);
//  - fixed-verlet converges to it: halving its step from 2 us to 1 us cuts its deviation to less
//    than 0.6 of what it was (second order would give 0.25 and first order 0.5).
TEST(Integrators, MethodsAgreeOnAShortRun) {
  const double tEnd = 2e-3;
  const int n = 10;
  ASSERT_EQ(defaultModel()->rotors[3].name, "tensionGuide");
  ASSERT_EQ(defaultModel()->rotors[2].name, "camshaftIntake");
  const auto refGuide = series("fixed-verlet", 5e-7, tEnd, n, guideAngle);
  const auto refCam = series("fixed-verlet", 5e-7, tEnd, n, camAngle);
  auto range = [](const std::vector<double>& v) {
    return *std::max_element(v.begin(), v.end()) - *std::min_element(v.begin(), v.end());
  };
  std::printf("reference motion over 2 ms: tension guide %.3e rad, camshaft %.3e rad\n", range(refGuide), range(refCam));
  auto deviation = [&](const char* method, double setting, double& g, double& a) {
    const auto gs = series(method, setting, tEnd, n, guideAngle);
    const auto as = series(method, setting, tEnd, n, camAngle);
    g = a = 0.0;
    for (int k = 0; k < n; ++k) {
      g = std::max(g, std::fabs(gs[k] - refGuide[k]));
      a = std::max(a, std::fabs(as[k] - refCam[k]));
    }
    std::printf("%-14s %-8g largest deviation: tension guide %.3e rad, camshaft %.3e rad\n", method, setting, g, a);
  };
  double g, a;
  for (const auto& [method, setting] : {std::pair<const char*, double>{"arkode-erk", 1e-6}, {"cvode-bdf-klu", 1e-5}}) {
    deviation(method, setting, g, a);
    EXPECT_LT(g, 1e-6) << method;
    EXPECT_LT(a, 1e-6) << method;
  }
  double g2, a2, g1, a1;
  deviation("fixed-verlet", 2e-6, g2, a2);
  deviation("fixed-verlet", 1e-6, g1, a1);
  EXPECT_LT(g1, 0.6 * g2);
  EXPECT_LT(a1, 0.6 * a2);
}

// The fixed-step scheme is for real-time use: a communication step (restart from the state,
// integrate, outputs) allocates nothing once the simulation has run one step, in both fidelities
// and with either fixed-step scheme, on one thread and on two (solver.threads: the counter counts
// every thread's).
TEST(Integrators, FixedStepCommunicationStepAllocatesNothing) {
  if (!chaindrive::test::allocationCountingAvailable()) GTEST_SKIP() << "allocation counting needs glibc";
  auto m = defaultModel();
  for (const auto& [fidelity, method, threads] :
       {std::tuple<const char*, const char*, int>{"link", "fixed-verlet", 1}, {"span", "fixed-verlet", 1},
        {"link", "fixed-newmark", 1}, {"link", "fixed-verlet-implicit-joint-damping", 1},
        {"link", "fixed-verlet-implicit-damping", 1}, {"link", "fixed-verlet-implicit-joint-damping", 2}}) {
    SimulationOptions opt;
    opt.fidelity = named<Fidelity>(fidelity);
    opt.integrator.method = named<IntegratorMethod>(method);
    opt.integrator.fixed.step = 2.5e-6;
    opt.threads = threads;
    Simulation sim(m, opt, constantLoads(*m, 3000.0));
    sim.start(0.0);
    sim.restart(0.0);
    sim.advanceTo(1e-4);
    (void)sim.outputs();
    double t = 1e-4;
    const long n = chaindrive::test::countAllocations([&] {
      for (int k = 0; k < 20; ++k) {
        sim.restart(0.0);
        t += 1e-4;
        sim.advanceTo(t);
        (void)sim.outputs().tensionerForce;
      }
    });
    EXPECT_EQ(n, 0) << fidelity << " " << method << " on " << threads << " threads";
    if (threads > 1) {
      EXPECT_GT(sim.threadBarriers(), 20 * 40 * 6 - 1);  // (they ran: 40 steps a 0.1 ms)
    }
  }
  // the counter works: a vector allocated in a counted region is counted
  EXPECT_GE(chaindrive::test::countAllocations([] { std::vector<double> v(10); v[0] = 1.0; }), 1);
}
