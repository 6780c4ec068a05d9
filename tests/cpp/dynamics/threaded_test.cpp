// An evaluation on several threads (solver.threads) gives the bits of one thread, with either
// vector width, on the default drive and on one whose guide is a line; the runs it cannot split
// are refused by name.
#include "dynamics/threaded.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <thread>
#include <tuple>

#include "dynamics/dynamics.h"
#include "dynamics/link_loops.h"
#include "integrators/integrators.h"
#include "run/simulation.h"
#include "test_util.h"

using namespace chaindrive;
using namespace chaindrive::test;

namespace {

// The state after `duration` of the real-time method at 3000 rpm from the running state, its
// evaluations on `threads` threads with `lanes` vector lanes.
std::vector<double> stateAfter(const std::shared_ptr<const Model>& m, int threads, int lanes, double duration) {
  auto in = constantLoads(*m, 3000.0);
  DriveSystem sys(m, *in, HealthLimits{});
  sys.data().vectorLanes = lanes;
  IntegratorSettings s;
  s.method = named<IntegratorMethod>("fixed-verlet-implicit-joint-damping");
  s.fixed.step = 1e-4 / 28;
  auto integrator = makeIntegrator(sys, s);
  StagePool pool(threads);
  sys.data().useThreads(*m, &pool);
  EXPECT_EQ(evaluatesOnThreads(*m, sys.data()), threads > 1);
  std::vector<double> y = runningState(*m, *in);
  integrator->reset(0.0, y.data());
  integrator->advance(duration, y.data());
  return y;
}

void expectSameBits(const std::vector<double>& a, const std::vector<double>& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i)
    ASSERT_EQ(std::memcmp(&a[i], &b[i], sizeof(double)), 0) << what << ": state " << i << ": " << a[i] << " against "
                                                            << b[i];
}

// The default drive with a line face on its tension guide: the tangent to its arc at the arc's
// middle, 4 deg of the arc long (the chain on its right), on which the links pass there.
std::shared_ptr<const Model> lineGuideModel() {
  return std::make_shared<const Model>(assemble(modifiedDefault([](nlohmann::json& j) {
    nlohmann::json& profile = j["guides"][0]["profile"];
    const nlohmann::json arc = profile[0];
    const double r = arc["radius"], cx = arc["center"][0], cy = arc["center"][1];
    const double mid = 0.5 * (double(arc["startAngle_deg"]) + double(arc["endAngle_deg"])) * M_PI / 180.0;
    const double half = 2.0 * M_PI / 180.0, reach = r / std::cos(half);  // (the tangent's ends)
    profile.push_back({{"type", "line"},
                       {"from", {cx + reach * std::cos(mid - half), cy + reach * std::sin(mid - half)}},
                       {"to", {cx + reach * std::cos(mid + half), cy + reach * std::sin(mid + half)}},
                       {"chainSide", "right"}});
  })));
}

}  // namespace

// 3 ms: 840 steps, the search windows scanned again many times, rollers seating and leaving.
TEST(Threaded, SameBitsForOneTwoAndThreeThreads) {
  auto m = defaultModel();
  for (int lanes : {2, 4}) {
    if (lanes > supportedVectorLanes()) continue;
    const std::vector<double> one = stateAfter(m, 1, lanes, 3e-3);
    expectSameBits(one, stateAfter(m, 2, lanes, 3e-3), "2 threads, " + std::to_string(lanes) + " lanes");
    if (lanes == supportedVectorLanes())
      expectSameBits(one, stateAfter(m, 3, lanes, 3e-3), "3 threads, " + std::to_string(lanes) + " lanes");
  }
}

TEST(Threaded, SameBitsOnALineGuide) {
  auto m = lineGuideModel();
  bool line = false;
  for (const GuideModel& g : m->guides)
    for (const GuideFace& f : g.faces) line |= f.type == GuideFace::Type::Line;
  ASSERT_TRUE(line);
  const std::vector<double> one = stateAfter(m, 1, supportedVectorLanes(), 3e-3);
  expectSameBits(one, stateAfter(m, 2, supportedVectorLanes(), 3e-3), "2 threads, a line guide");
  // the line touched by then
  auto in = constantLoads(*m, 3000.0);
  Data d(*m);
  generalizedForces(*m, d, *in, 3e-3, one.data());
  int onLine = 0;
  for (int k = 0; k < d.nContacts; ++k)
    onLine += d.contacts[k].kind == ContactPoint::Kind::PlateGuide && d.contacts[k].element == 0 &&
              m->guides[0].faces[static_cast<std::size_t>(d.contacts[k].face)].type == GuideFace::Type::Line;
  EXPECT_GT(onLine, 0);
}

// Through a Simulation (the FMU's and chaindrive-run's path): the same outputs, and what threads
// cannot run refused with solver.threads named.
TEST(Threaded, SimulationSameOutputsAndRefusals) {
  auto m = defaultModel();
  auto run = [&](int threads, const std::string& method, const std::string& fidelity) {
    SimulationOptions opt;
    opt.threads = threads;
    opt.fidelity = named<Fidelity>(fidelity);
    opt.integrator.method = named<IntegratorMethod>(method);
    opt.integrator.fixed.step = fidelity == "span" ? 1e-4 / 3 : 2.5e-6;
    Simulation sim(m, opt, constantLoads(*m, 3000.0));
    sim.start(0.0);
    sim.advanceTo(2e-3);
    return sim.state();
  };
  expectSameBits(run(1, "fixed-verlet", "link"), run(2, "fixed-verlet", "link"), "fixed-verlet, 2 threads");
  auto refusal = [&](int threads, const std::string& method, const std::string& fidelity) -> std::string {
    try {
      run(threads, method, fidelity);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "not refused";
  };
  for (const auto& [threads, method, fidelity] :
       {std::tuple{2, "fixed-verlet", "span"}, {2, "fixed-newmark", "link"}, {2, "arkode-erk", "link"},
        {0, "fixed-verlet", "link"}, {17, "fixed-verlet", "link"}}) {
    const std::string what = refusal(threads, method, fidelity);
    EXPECT_EQ(what.rfind("solver.threads = " + std::to_string(threads) + ": ", 0), 0u)
        << threads << " " << method << " " << fidelity << ": " << what;
  }
}

// The barrier orders every thread's writes before every thread's reads, run after run, also after
// the threads fell asleep between runs.
TEST(StagePool, BarrierOrdersWritesAndThreadsWakeAgain) {
  for (int threads = 1; threads <= 3; ++threads) {
    StagePool pool(threads);
    std::vector<long> slots(static_cast<std::size_t>(threads), 0);
    std::atomic<int> wrong{0};
    for (int run = 0; run < 1000; ++run) {
      if (run == 500) std::this_thread::sleep_for(std::chrono::milliseconds(20));  // (beyond the spinning)
      auto task = [&](int t) {
        slots[static_cast<std::size_t>(t)] = run + 1;
        pool.barrier(t);
        long sum = 0;
        for (long s : slots) sum += s;
        if (sum != static_cast<long>(threads) * (run + 1)) ++wrong;  // (a data race on `wrong` only when wrong)
        pool.barrier(t);
      };
      pool.run(task);
    }
    EXPECT_EQ(wrong.load(), 0) << threads << " threads";
    EXPECT_EQ(pool.barriers(), threads == 1 ? 0 : 1000 * 3);
  }
  EXPECT_THROW(StagePool(0), std::invalid_argument);
}
