// The global time grid (src/integrators/time_grid.h): requested times are turned into integer grid indices,
// so that how a caller forms its times does not change which states a run reaches, nor their bits.
#include <gtest/gtest.h>

#include <cmath>

#include "test_util.h"
#include "integrators/time_grid.h"

using namespace chaindrive;
using namespace chaindrive::test;

namespace {

// The three ways masters form the end of communication step k (0-based) of length H.
enum class TimeForm { KTimesH, Accumulated, StepAsDifference };

struct PointFormer {
  TimeForm form;
  double H, t = 0.0;
  // the end of step k as a master of this kind computes it (called for k = 0, 1, 2, ...)
  double end(long long k) {
    switch (form) {
      case TimeForm::KTimesH: return static_cast<double>(k + 1) * H;
      case TimeForm::Accumulated: return t += H;
      case TimeForm::StepAsDifference: {
        const double cp = static_cast<double>(k) * H;
        return cp + (static_cast<double>(k + 1) * H - cp);
      }
    }
    return 0.0;
  }
};

}  // namespace

// Every way of forming 1e5 communication points of 100 us maps to the same grid points of a
// 2.5 us grid (40 steps each), although the accumulated times drift from k H (checked).
TEST(TimeGrid, MasterRoundingSnapsToTheSameGridPoints) {
  const TimeGrid grid{0.0, 2.5e-6};
  for (TimeForm form : {TimeForm::KTimesH, TimeForm::Accumulated, TimeForm::StepAsDifference}) {
    PointFormer master{form, 1e-4};
    long long wrong = 0;
    for (long long k = 0; k < 100000; ++k) wrong += grid.indexOf(master.end(k)) != 40 * (k + 1);
    EXPECT_EQ(wrong, 0) << static_cast<int>(form);
  }
  PointFormer accumulated{TimeForm::Accumulated, 1e-4};
  double t = 0.0;
  for (long long k = 0; k < 100000; ++k) t = accumulated.end(k);
  EXPECT_NE(t, 100000 * 1e-4);  // the premise: accumulation drifts (by about 1e-11 s here)
}

// 1/60 s passed as 0.016666666666666677 (rounded up) on a grid that divides 1/60 s.
TEST(TimeGrid, RoundedSixtiethOfASecondIsOnTheGrid) {
  const double rounded = 0.016666666666666677;
  ASSERT_NE(rounded, 1.0 / 60.0);
  const TimeGrid grid{0.0, (1.0 / 60.0) / 6000.0};
  EXPECT_EQ(grid.indexOf(rounded), 6000);
  EXPECT_EQ(grid.indexOf(rounded + rounded + rounded), 18000);
  EXPECT_TRUE(grid.contains(3.0 * rounded));
}

// Off the grid: the point before; within 1 % of a unit: the nearest point, on either side.
TEST(TimeGrid, OffGridPointsGoToThePointBefore) {
  const TimeGrid grid{0.5, 2.5e-6};
  EXPECT_EQ(grid.indexOf(0.5 + 1e-4 / 3.0), 13);
  EXPECT_FALSE(grid.contains(0.5 + 1e-4 / 3.0));
  EXPECT_EQ(grid.indexOf(0.5 + 40.009 * 2.5e-6), 40);
  EXPECT_EQ(grid.indexOf(0.5 + 39.991 * 2.5e-6), 40);
  EXPECT_EQ(grid.indexOf(0.5 + 39.98 * 2.5e-6), 39);
  EXPECT_EQ(grid.indexOf(0.5 - 2.5e-6), -1);
  EXPECT_TRUE(grid.reaches(1e3));
  EXPECT_FALSE(grid.reaches(1e20));
  EXPECT_FALSE(grid.reaches(std::nan("")));
}

namespace {

// The state after 1 ms of a run with 3000 rpm and a crankshaft vibration (time-dependent inputs)
// whose intermediate output times are formed as `form`, in steps of H.
std::vector<double> stateAfter(const std::string& method, double step, TimeForm form, double H) {
  auto m = defaultModel();
  SimulationOptions opt;
  opt.integrator.method = named<IntegratorMethod>(method);
  opt.integrator.fixed.step = step;
  auto in = std::make_unique<HarmonicInputs>(*m, 3000.0 * 2.0 * kPi / 60.0);
  in->addOrder({2.0, 0.01, 0.0});
  Simulation sim(m, opt, std::move(in));
  sim.start(0.0);
  PointFormer master{form, H};
  const long long n = std::llround(1e-3 / H);
  for (long long k = 0; k < n; ++k) sim.advanceTo(master.end(k));
  EXPECT_EQ(sim.gridIndex(), std::llround(1e-3 / step));
  return sim.state();
}

}  // namespace

// Fixed-step methods take whole steps of exactly h at the grid times t0 + k h: the state at a
// grid point is the same, bit for bit, however the output times in between were formed and
// however many there were.
TEST(TimeGrid, FixedStepStatesDoNotDependOnTheOutputTimes) {
  for (const auto& [method, step] : {std::pair<std::string, double>{"fixed-verlet", 2.5e-6}, {"arkode-erk-fixed", 2e-6}}) {
    const std::vector<double> reference = stateAfter(method, step, TimeForm::KTimesH, 1e-4);
    EXPECT_EQ(stateAfter(method, step, TimeForm::Accumulated, 1e-4), reference) << method;
    EXPECT_EQ(stateAfter(method, step, TimeForm::StepAsDifference, 1e-4), reference) << method;
    EXPECT_EQ(stateAfter(method, step, TimeForm::KTimesH, 5e-4), reference) << method;
  }
}

// A request off the grid is integrated to the grid point before it; the next request is mapped
// from its own time, so the remainder is carried and nothing drifts.
TEST(TimeGrid, SimulationCarriesTheRemainderOfOffGridRequests) {
  auto m = defaultModel();
  SimulationOptions opt;
  opt.integrator.method = named<IntegratorMethod>("fixed-verlet");
  opt.integrator.fixed.step = 2.5e-6;
  Simulation sim(m, opt, constantLoads(*m, 3000.0));
  sim.start(0.25);
  EXPECT_EQ(sim.grid().unit, 2.5e-6);
  for (int k = 1; k <= 6; ++k) {
    const double master = 0.25 + k * 1e-4 / 3.0;
    const double reached = sim.advanceTo(master);
    EXPECT_EQ(sim.gridIndex(), (40 * k) / 3) << k;
    EXPECT_LE(reached, master);
    EXPECT_LT(master - reached, 2.5e-6);
  }
  EXPECT_THROW(sim.advanceTo(1e30), std::invalid_argument);
}

// Adaptive methods stop on the 1 us quantum by the same rule.
TEST(TimeGrid, AdaptiveMethodsStopOnTheQuantum) {
  auto m = defaultModel();
  SimulationOptions opt;
  opt.integrator.method = named<IntegratorMethod>("arkode-erk");
  Simulation sim(m, opt, constantLoads(*m, 3000.0));
  sim.start(0.0);
  EXPECT_EQ(sim.grid().unit, kAdaptiveTimeQuantum);
  EXPECT_EQ(sim.advanceTo(2.5e-5 + 3e-13), 25 * kAdaptiveTimeQuantum);
  EXPECT_EQ(sim.gridIndex(), 25);
  EXPECT_EQ(sim.advanceTo(3.33e-5), 33 * kAdaptiveTimeQuantum);
}
