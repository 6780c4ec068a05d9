// The damped-mode fit the span model's damping calibration measures both models with, on signals
// with known answers: a mode over two channels with their own amplitudes, phases and slow drifts,
// sampled at the steps the calibration uses and at an uneven grid, with and without noise.
#include "run/mode_fit.h"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace chaindrive {
namespace {

struct Signal {
  std::vector<double> t;
  std::vector<std::vector<double>> channels;
};

// Two channels of one mode (frequency f [Hz], damping ratio zeta) with drifts, from 2 ms to 20 ms
// at `step`, times jittered by up to `jitter` of a step, noise of rms `noise` of the amplitude.
Signal mode(double f, double zeta, double step, double jitter, double noise, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> n(0.0, 1.0);
  const double omega = 2.0 * M_PI * f, sigma = zeta * omega / std::sqrt(1.0 - zeta * zeta);
  Signal s;
  s.channels.resize(2);
  for (double t = 0.002; t <= 0.02 + 1e-12; t += step) {
    const double tt = t + jitter * step * u(rng), e = std::exp(-sigma * (tt - 0.002));
    s.t.push_back(tt);
    s.channels[0].push_back(1e-3 * e * std::cos(omega * tt + 0.3) + 2e-4 + 5e-3 * tt + 1e-3 * noise * n(rng));
    s.channels[1].push_back(0.8e-3 * e * std::cos(omega * tt + 0.2) - 3e-3 * tt * tt + 1e-3 * noise * n(rng));
  }
  return s;
}

TEST(ModeFit, FindsTheModeFinerThanTheBinAtEveryStep) {
  struct Case {
    double step, f, zeta;
  };
  std::vector<Case> cases = {{1e-5, 371.3, 0.026}};  // (a tenth of the output step: the slowest fit)
  for (double step : {1e-4, 1e-4 / 3})
    for (double f : {160.0, 371.3, 887.0, 1450.0})
      for (double zeta : {0.003, 0.026, 0.08}) cases.push_back({step, f, zeta});
  for (const auto& [step, f, zeta] : cases) {
    const Signal s = mode(f, zeta, step, 0.0, 0.0, 1);
    const FittedMode m = fitDampedMode(s.t, s.channels, 111.0, 2000.0);
    EXPECT_NEAR(m.frequency, f, 1e-4 * f) << step << " " << f << " " << zeta;
    EXPECT_NEAR(m.dampingRatio, zeta, 1e-3 * zeta) << step << " " << f << " " << zeta;
    EXPECT_LT(m.residual, 1e-4);
    EXPECT_FALSE(m.atBound);
  }
}

TEST(ModeFit, HoldsOnAnUnevenGridAndUnderNoise) {
  const Signal s = mode(371.3, 0.026, 1e-4, 0.3, 0.02, 7);
  const FittedMode m = fitDampedMode(s.t, s.channels, 111.0, 2000.0);
  EXPECT_NEAR(m.frequency, 371.3, 0.005 * 371.3);
  EXPECT_NEAR(m.dampingRatio, 0.026, 0.15 * 0.026);
  EXPECT_GT(m.residual, 0.0);
  EXPECT_LT(m.residual, 0.2);
}

TEST(ModeFit, AModeOutsideTheSearchEndsAtItsBound) {
  const Signal s = mode(60.0, 0.02, 1e-4, 0.0, 0.0, 1);
  EXPECT_TRUE(fitDampedMode(s.t, s.channels, 111.0, 2000.0).atBound);
}

TEST(ModeFit, RefusesTooFewSamplesOrChannelsOfAnotherLength) {
  Signal s = mode(371.3, 0.026, 1e-4, 0.0, 0.0, 1);
  s.channels[1].pop_back();
  EXPECT_THROW(fitDampedMode(s.t, s.channels, 111.0, 2000.0), std::invalid_argument);
  EXPECT_THROW(fitDampedMode({0.0, 1.0}, {{0.0, 1.0}}, 111.0, 2000.0), std::invalid_argument);
}

}  // namespace
}  // namespace chaindrive
