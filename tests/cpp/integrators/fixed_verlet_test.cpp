// fixed-verlet with the damping implicit: the joints' by one Jacobi sweep
// (fixed-verlet-implicit-joint-damping) keeps a motion the joints do not resist exactly as plain
// Verlet kicks it and shrinks the kick of neighbours moving against each other; on the drive it
// runs at a step where plain Verlet blows up, repeats bit for bit, gives the same bits with the
// per-link loops in 2 lanes (SSE2, every x86-64 CPU) and in 4 (AVX2), stops with a named failure at
// a step beyond its limit, and is refused where the joints' damping is not constant (clearance) or
// there are no joints (span fidelity).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <utility>

#include "dynamics/link_loops.h"
#include "integrators/integrators.h"
#include "run/simulation.h"
#include "test_util.h"

using namespace chaindrive;
using namespace chaindrive::test;

namespace {

// The tensioner force every 0.1 ms of a 3000 rpm run from the preload.
std::vector<double> tensionerRun(const std::shared_ptr<const Model>& m, const std::string& method, double step,
                                 double tEnd) {
  IntegratorSettings s;
  s.method = named<IntegratorMethod>(method);
  s.fixed.step = step;
  return chaindrive::test::tensionerRun(m, s, tEnd);
}

// The kicks of h/2 a system's damped-kick interface gives for link accelerations `field` (x, y,
// gamma of every link), at the state of a running drive.
std::vector<double> jointDampedKicks(const std::vector<double>& field, double hh) {
  auto m = defaultModel();
  auto in = constantLoads(*m, 3000.0);
  DriveSystem sys(m, *in, HealthLimits{});
  const std::vector<double> y = runningState(*m, *in);
  std::vector<double> ydot(y.size()), kick(y.size());
  EXPECT_EQ(sys.rhs(0.0, y.data(), ydot.data()), 0);
  const int n = m->chain.links;
  std::copy(field.begin(), field.end(), ydot.begin() + m->linkState(0, Model::kVx));
  sys.dampedKicks(hh, true, kick.data());
  EXPECT_TRUE(sys.dampOffDiagonal(hh, ydot.data()));
  std::vector<double> out(3 * n);
  for (int i = 0; i < 3 * n; ++i) {
    const int s = m->linkState(0, Model::kVx) + i;
    out[i] = kick[s] * ydot[s];
  }
  return out;
}

// The state after 10 ms of `method` at `step` from a running state at 3000 rpm, with the per-link
// loops and the contact search in `lanes` lanes.
std::vector<double> stateAfter(const std::string& method, double step, int lanes) {
  auto m = defaultModel();
  auto in = constantLoads(*m, 3000.0);
  DriveSystem sys(m, *in, HealthLimits{});
  sys.data().vectorLanes = lanes;
  std::vector<double> y = runningState(*m, *in);
  IntegratorSettings s;
  s.method = named<IntegratorMethod>(method);
  s.fixed.step = step;
  auto integrator = makeIntegrator(sys, s);
  integrator->reset(0.0, y.data());
  integrator->advance(0.01, y.data());
  return y;
}

}  // namespace

// A rigid translation of the chain stretches no joint: the damped kick is plain Verlet's h/2 a
// (to rounding). Neighbours shifting against each other along x (the stiffest motion) are damped
// at the rate 4 c / m, twice a link's own rate D = 2 c / m: the implicit kick is h/2 a / (1 + h/2
// 2 D), one Jacobi sweep from h/2 a gives h/2 a (1 - h/2 D) / (1 + h/2 D), a little less.
TEST(FixedVerlet, JointSweepKeepsARigidKickAndShrinksTheStiffest) {
  auto m = defaultModel();
  const int n = m->chain.links;
  const double hh = 0.5 * 3.5e-6;
  std::vector<double> rigid(3 * n, 0.0), alternating(3 * n, 0.0);
  for (int i = 0; i < n; ++i) {
    rigid[i] = 120.0, rigid[n + i] = -45.0;
    alternating[i] = i % 2 == 0 ? 100.0 : -100.0;
  }
  const std::vector<double> a = jointDampedKicks(rigid, hh);
  for (int i = 0; i < 3 * n; ++i) EXPECT_NEAR(a[i], hh * rigid[i], 1e-12 * hh * 120.0) << i;
  const std::vector<double> b = jointDampedKicks(alternating, hh);
  const double own = hh * 2.0 * m->chain.jointDamping / m->chain.mass;
  for (int i = 0; i < n; ++i) {
    EXPECT_LT(std::fabs(b[i]), hh * 100.0 / (1.0 + 2.0 * own)) << i;
    EXPECT_NEAR(b[i], hh * alternating[i] * (1.0 - own) / (1.0 + own), 1e-9 * hh * 100.0) << i;
  }
}

// At 4 us plain Verlet blows up within 20 ms (its limit is about 3.2 us), and says which step to
// try (its row's, run/drive_defaults.h); with the joints' damping implicit the run goes on,
// bit-identical when repeated.
TEST(FixedVerlet, ImplicitJointDampingStableWherePlainVerletBlowsUp) {
  auto m = defaultModel();
  try {
    tensionerRun(m, "fixed-verlet", 4e-6, 0.02);
    FAIL() << "expected plain Verlet to blow up at 4 us";
  } catch (const IntegrationError& e) {
    EXPECT_TRUE(e.failureKind() == FailureKind::BlowUp || e.failureKind() == FailureKind::Tunnelling) << e.what();
    EXPECT_NE(std::string(e.what()).find("; the step was 4 us, above this drive's estimated stable step: try "
                                         "solver.step = 2.5e-06 s (1e-4/40)"), std::string::npos) << e.what();
  }
  const auto a = tensionerRun(m, "fixed-verlet-implicit-joint-damping", 4e-6, 0.02);
  const auto b = tensionerRun(m, "fixed-verlet-implicit-joint-damping", 4e-6, 0.02);
  ASSERT_EQ(a.size(), 200u);
  for (std::size_t k = 0; k < a.size(); ++k) ASSERT_EQ(a[k], b[k]) << "sample " << k;
  for (double f : a) EXPECT_TRUE(f > 0.0 && f < 1e3) << f;
}

// The chaotic dynamics turns a difference in the last bit into a visible one within milliseconds:
// 10 ms of the real-time method and of plain Verlet, with 2 lanes and with 4, end in the same bits
// (what makes a run on a CPU without AVX2 repeat this one).
TEST(FixedVerlet, SameBitsWithTwoAndFourLanes) {
  if (supportedVectorLanes() < 4) GTEST_SKIP() << "this CPU has no AVX2: the 4-lane loops are not run";
  for (const auto& [method, step] : {std::pair<std::string, double>{"fixed-verlet-implicit-joint-damping", 1e-4 / 28},
                                     {"fixed-verlet", 2.5e-6}}) {
    const std::vector<double> two = stateAfter(method, step, 2), four = stateAfter(method, step, 4);
    ASSERT_EQ(two.size(), four.size());
    for (std::size_t i = 0; i < two.size(); ++i)
      ASSERT_EQ(std::memcmp(&two[i], &four[i], sizeof(double)), 0) << method << ": state " << i;
  }
}

// Beyond its stable step (about 4.6 us) the real-time method stops with a named failure, not with
// garbage: at 8 us within 20 ms, naming the step it ran with and the drive's stable step to try.
TEST(FixedVerlet, ImplicitJointDampingBeyondItsLimitIsANamedFailure) {
  try {
    tensionerRun(defaultModel(), "fixed-verlet-implicit-joint-damping", 8e-6, 0.02);
    FAIL() << "expected a blow-up at 8 us";
  } catch (const IntegrationError& e) {
    EXPECT_TRUE(e.failureKind() == FailureKind::BlowUp || e.failureKind() == FailureKind::Tunnelling) << e.what();
    const std::string what = e.what();
    EXPECT_NE(what.find("; the step was 8 us, above this drive's estimated stable step: try solver.step = "
                        "3.571e-06 s (1e-4/28)"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;  // one line
  }
}

TEST(FixedVerlet, ImplicitJointDampingRefusedWithoutConstantJointDamping) {
  auto clearance = std::make_shared<const Model>(
      assemble(modifiedDefault([](nlohmann::json& j) { j["chain"]["joint"]["clearance"] = 2e-6; })));
  try {
    tensionerRun(clearance, "fixed-verlet-implicit-joint-damping", 3e-6, 1e-4);
    FAIL() << "expected a refusal with joint clearance";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("joints without clearance"), std::string::npos) << e.what();
  }
  auto m = defaultModel();
  SimulationOptions opt;
  opt.fidelity = named<Fidelity>("span");
  opt.integrator.method = named<IntegratorMethod>("fixed-verlet-implicit-joint-damping");
  try {
    Simulation sim(m, opt, constantLoads(*m, 3000.0));
    FAIL() << "expected a refusal in the span fidelity";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("does not apply to fidelity 'span'"), std::string::npos) << e.what();
  }
}
