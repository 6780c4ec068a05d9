// fixed-newmark on a damped linear oscillator whose whole force is the stiff part: no step limit,
// the amplitude kept (gamma 1/2) or damped (gamma > 1/2), second order at gamma 1/2; refused
// without a stiff part or with gamma out of range. On the drive: stable far beyond Verlet's
// step, bit-identical repeats, and a step too long for the contacts still a named failure.
#include <gtest/gtest.h>

#include <cmath>

#include "integrators/integrators.h"
#include "test_util.h"

using namespace chaindrive;
using namespace chaindrive::test;

namespace {

// x'' = -omega^2 x - c x'; state (x, v, energy accumulator of the damper)
class Oscillator : public OdeSystem {
 public:
  Oscillator(double omega, double c, bool stiff) : k_(omega * omega), c_(c), stiff_(stiff) {}
  int size() const override { return 3; }
  int rhs(double, const double* y, double* ydot) noexcept override {
    ydot[0] = y[1];
    ydot[1] = -k_ * y[0] - c_ * y[1];
    ydot[2] = c_ * y[1] * y[1];
    return 0;
  }
  bool hasStiffSolve() const override { return stiff_; }
  int solveStiff(double a, double b, double* r) noexcept override {
    r[1] /= 1.0 + a * c_ + b * k_;
    return 0;
  }
  void toleranceScales(double* s) const override { s[0] = s[1] = s[2] = 1.0; }
  int velocityOf(int i) const override { return i == 0 ? 1 : -1; }
  bool isVelocity(int i) const override { return i == 1; }
  bool healthy(double, const double* y, Failure& why) noexcept override {
    if (std::isfinite(y[0]) && std::isfinite(y[1])) return true;
    why = {FailureKind::NonFinite, "not finite"};
    return false;
  }
  const Failure& lastError() const override { return error_; }
  double energy(const double* y) const { return 0.5 * (k_ * y[0] * y[0] + y[1] * y[1]); }

 private:
  double k_, c_;
  bool stiff_;
  Failure error_;
};

std::vector<double> integrate(Oscillator& sys, double gamma, double h, double tEnd) {
  IntegratorSettings s;
  s.method = named<IntegratorMethod>("fixed-newmark");
  s.fixed.step = h;
  s.newmark.gamma = gamma;
  auto integrator = makeIntegrator(sys, s);
  std::vector<double> y = {1.0, 0.0, 0.0};
  integrator->reset(0.0, y.data());
  integrator->advance(tEnd, y.data());
  return y;
}

}  // namespace

TEST(FixedNewmark, StableFarBeyondTheExplicitLimitAndKeepsTheAmplitude) {
  Oscillator sys(1.0, 0.0, true);
  const double e0 = 0.5;
  const auto kept = integrate(sys, 0.5, 10.0, 1e4);    // omega h = 10: Verlet's limit is 2
  EXPECT_NEAR(sys.energy(kept.data()), e0, 1e-12);
  const auto damped = integrate(sys, 0.6, 10.0, 1e3);
  EXPECT_LT(sys.energy(damped.data()), 1e-6 * e0);     // the unresolved mode damped away
}

TEST(FixedNewmark, SecondOrderAtGammaOneHalfFirstBeyond) {
  Oscillator sys(2.0 * kPi, 0.5, true);
  auto error = [&](double gamma, double h) {
    const auto y = integrate(sys, gamma, h, 1.0);
    // exact solution of x'' + c x' + w^2 x = 0, x(0) = 1, v(0) = 0
    const double w = 2.0 * kPi, zeta = 0.25 / w, wd = w * std::sqrt(1.0 - zeta * zeta);
    const double exact = std::exp(-zeta * w) * (std::cos(wd) + zeta * w / wd * std::sin(wd));
    return std::fabs(y[0] - exact);
  };
  const double order2 = std::log2(error(0.5, 1e-2) / error(0.5, 5e-3));
  const double order1 = std::log2(error(0.6, 1e-2) / error(0.6, 5e-3));
  std::printf("observed orders: gamma 0.5 %.2f, gamma 0.6 %.2f\n", order2, order1);
  EXPECT_NEAR(order2, 2.0, 0.1);
  EXPECT_NEAR(order1, 1.0, 0.15);
}

TEST(FixedNewmark, RefusesASystemWithoutStiffPartAndGammaOutOfRange) {
  Oscillator plain(1.0, 0.0, false), stiff(1.0, 0.0, true);
  EXPECT_THROW(integrate(plain, 0.5, 0.1, 1.0), std::invalid_argument);
  for (double gamma : {0.4, 1.5, std::nan("")}) {
    try {
      integrate(stiff, gamma, 0.1, 1.0);
      FAIL() << "gamma " << gamma << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("gamma"), std::string::npos) << e.what();
    }
  }
}

namespace {

std::vector<double> driveRun(double step, double gamma, double tEnd) {
  IntegratorSettings s;
  s.method = named<IntegratorMethod>("fixed-newmark");
  s.fixed.step = step;
  s.newmark.gamma = gamma;
  return chaindrive::test::tensionerRun(defaultModel(), s, tEnd);
}

}  // namespace

// Verlet blows up beyond about 3.5 us on this drive (Integrators.BlowUpIsDetectedAndReported);
// with the joints and contacts implicit the step grows sixfold. At 50 us a roller reaches far
// into its tooth within one step: the run stops with the tunnelling check, not with garbage.
TEST(FixedNewmark, OnTheDriveStableAtTwentyMicrosecondsAndFailsNamedBeyond) {
  const auto a = driveRun(2e-5, 0.6, 0.02), b = driveRun(2e-5, 0.6, 0.02);
  ASSERT_EQ(a.size(), 200u);
  for (std::size_t k = 0; k < a.size(); ++k) ASSERT_EQ(a[k], b[k]) << "sample " << k;
  for (double f : a) EXPECT_TRUE(f > 0.0 && f < 1e3) << f;
  try {
    driveRun(5e-5, 0.6, 0.02);
    FAIL() << "expected a failure at 50 us";
  } catch (const IntegrationError& e) {
    EXPECT_TRUE(e.failureKind() == FailureKind::Tunnelling || e.failureKind() == FailureKind::BlowUp) << e.what();
    std::printf("reported: %s\n", e.what());
  }
}
