// A drive's own solver defaults: the steps from its stability estimate (src/run/drive_defaults.h).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "integrators/stable_step.h"
#include "dynamics/link_modes.h"
#include "run/drive_defaults.h"
#include "run/step_probe.h"
#include "test_util.h"

using namespace chaindrive;
using namespace chaindrive::test;

namespace {

const SolverDefaults& linkRow() { return solverDefaults(Scene::TimingDrive, Fidelity::Link); }
const SolverDefaults& plainRow() { return solverDefaults(Scene::TimingDrive, Fidelity::Link, true); }
const SolverDefaults& spanRow() { return solverDefaults(Scene::TimingDrive, Fidelity::Span); }

Model testDrive(const std::string& name) {
  return assemble(loadDriveDescription(std::string(CHAINDRIVE_SOURCE_DIR) + "/tests/drives/" + name + ".json"));
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

// The default drive keeps the table's steps bit for bit: 1e-4/28, 2.5e-6 = 1e-4/40 and 1e-4/3, so
// that every committed result of it stays as it is; its estimates are the measured closed-loop limits.
TEST(DriveDefaults, TheDefaultDriveKeepsTheTablesSteps) {
  const Model& m = *defaultModel();
  const DriveRow link = driveRow(m, linkRow()), plain = driveRow(m, plainRow()), span = driveRow(m, spanRow());
  EXPECT_EQ(link.row.step, 1e-4 / 28);
  EXPECT_EQ(link.divisions, 28);
  EXPECT_EQ(plain.row.step, 2.5e-6);
  EXPECT_EQ(plain.divisions, 40);
  EXPECT_EQ(span.row.step, 1e-4 / 3);
  EXPECT_EQ(span.divisions, 3);
  for (const DriveRow* r : {&link, &plain, &span}) {
    EXPECT_FALSE(r->probe.has_value());  // (its steps are its measured closed-loop ones)
    EXPECT_EQ(r->row.method, (r == &link ? linkRow() : r == &plain ? plainRow() : spanRow()).method);
    EXPECT_NEAR(r->margin * r->estimate, r->row.step, 1e-12 * r->row.step);
  }
  // the real-time method's closed-loop limit ran at 1e-4/24 and blew up at 1e-4/23; plain Verlet's at 1e-4/33, 1e-4/32
  EXPECT_NEAR(link.estimate, 1e-4 / std::sqrt(24.0 * 23.0), 1e-18);
  EXPECT_NEAR(plain.estimate, 1e-4 / std::sqrt(33.0 * 32.0), 1e-18);
  EXPECT_NEAR(link.margin, 0.839, 0.001);
  EXPECT_TRUE(contains(link.reason, "step 3.571e-06 s = 1e-4/28: the drive's stability estimate 4.256 us")) << link.reason;
  EXPECT_TRUE(contains(link.reason, "roller-sprocket contact 2e+08 N/m on a 3.9 g link")) << link.reason;
  EXPECT_TRUE(contains(link.reason, "the default drive's margin")) << link.reason;
  EXPECT_TRUE(contains(span.reason, "1e-4/3: the span model's stability estimate")) << span.reason;
  // a row no drive changes
  const DriveRow cvt = driveRow(m, solverDefaults(Scene::Cvt));
  EXPECT_EQ(cvt.row.step, solverDefaults(Scene::Cvt).step);
  EXPECT_EQ(cvt.divisions, 0);
}

// A lighter link or a stiffer contact: a shorter step for every link row, snapped to the largest
// 1e-4/n not above margin x estimate.
TEST(DriveDefaults, ALighterLinkOrAStifferContactGivesAShorterStep) {
  const Model& def = *defaultModel();
  for (const auto& edit : std::vector<std::function<void(nlohmann::json&)>>{
           [](nlohmann::json& j) { j["chain"]["linkMass"] = 0.5 * 0.0039; },
           [](nlohmann::json& j) { j["chain"]["linkInertia"] = 0.5 * 7e-8; },
           [](nlohmann::json& j) { j["contact"]["rollerSprocket"]["stiffness"] = 4e8; }}) {
    const Model m = assemble(modifiedDefault(edit));
    for (const SolverDefaults* table : {&linkRow(), &plainRow()}) {
      const DriveRow r = driveRow(m, *table, false), d = driveRow(def, *table);
      EXPECT_LT(r.estimate, d.estimate);
      EXPECT_LT(r.row.step, d.row.step);
      EXPECT_EQ(r.row.step, 1e-4 / static_cast<double>(r.divisions));
      EXPECT_EQ(r.divisions, r.estimateDivisions);
      EXPECT_LE(r.row.step, r.margin * r.estimate);
      EXPECT_GT(1e-4 / static_cast<double>(r.divisions - 1), r.margin * r.estimate);
      EXPECT_EQ(r.margin, d.margin);
    }
  }
}

// Joints twice as stiff at the default's damping: the real-time method's estimate loses part of what
// its implicit joints' damping gains, as the joints' damping ratio (1/sqrt(2) of the default's) to
// the power 0.75 (measured: 0.65 of the default's open-loop limit, the modes alone say 0.84); with
// the damping ratio kept (the damping times sqrt(2)) nothing is lost. Plain Verlet's estimate counts
// the joints' damping in its modes and takes no such factor.
TEST(DriveDefaults, StifferJointsAtTheSameDampingLoseTheImplicitDampingsGain) {
  const Model& def = *defaultModel();
  const Model stiff = assemble(modifiedDefault([](nlohmann::json& j) { j["chain"]["joint"]["stiffness"] = 2.4e8; }));
  const Model damped = assemble(modifiedDefault([](nlohmann::json& j) {
    j["chain"]["joint"]["stiffness"] = 2.4e8;
    j["chain"]["joint"]["damping"] = 250.0 * std::sqrt(2.0);
  }));
  const double modes = linkModeStep(stiff, false).step / linkModeStep(def, false).step;
  const DriveRow d = driveRow(def, linkRow()), s = driveRow(stiff, linkRow(), false), c = driveRow(damped, linkRow(), false);
  EXPECT_NEAR(s.estimate / d.estimate, modes * std::pow(std::sqrt(0.5), 0.75), 1e-12);
  EXPECT_NEAR(s.estimate / d.estimate, 0.65, 0.01);
  EXPECT_TRUE(contains(s.reason, "the joints' damping ratio")) << s.reason;
  EXPECT_NEAR(c.estimate / d.estimate, modes, 1e-12);
  EXPECT_FALSE(contains(c.reason, "the joints' damping ratio")) << c.reason;
  const double plainModes = linkModeStep(stiff, true).step / linkModeStep(def, true).step;
  EXPECT_NEAR(driveRow(stiff, plainRow(), false).estimate / driveRow(def, plainRow()).estimate, plainModes, 1e-12);
}

// The test drives (tests/drives/README.md): the 06B drives have the default's estimate and the
// 8 mm chain's lighter links a shorter one, inside its measured open-loop limit 3.125 us (ran;
// 3.226 us blew up) with a margin no smaller than the default's to its own (0.66); every span
// model keeps 1e-4/3 or shorter.
TEST(DriveDefaults, TheTestDrivesEstimates) {
  for (const char* name : {"sohc_single_cam", "diesel_pump", "idler"}) {
    const Model m = testDrive(name);
    EXPECT_EQ(driveRow(m, linkRow(), false).row.step, 1e-4 / 28) << name;
    EXPECT_EQ(driveRow(m, plainRow(), false).row.step, 2.5e-6) << name;
    EXPECT_LE(driveRow(m, spanRow()).row.step, 1e-4 / 3) << name;
  }
  const Model m = testDrive("dohc_8mm");
  const DriveRow link = driveRow(m, linkRow(), false);
  EXPECT_LT(link.row.step, 0.66 * 3.125e-6);
  EXPECT_GT(link.row.step, 1.5e-6);
  EXPECT_TRUE(contains(link.reason, "on a 1.44 g link")) << link.reason;
  EXPECT_LT(driveRow(m, plainRow(), false).row.step, 2.5e-6);
}

// The probe's limit is the default drive's own energy balance at its steps: its probe passes at
// 1e-4/28 (real-time method) and 1e-4/40 (plain Verlet), the real-time method's within a third of
// the limit (the limit is that balance, rounded up), and fails a step a quarter longer.
TEST(DriveDefaults, TheProbesLimitIsTheDefaultDrivesBalance) {
  const Model& m = *defaultModel();
  const ProbeRun own = probeRun(m, linkRow().method, 28);
  EXPECT_TRUE(own.passes()) << own.energyBalance << " " << own.failure;
  EXPECT_GT(std::fabs(own.energyBalance), 2.0 / 3.0 * kProbeBalanceLimit);
  EXPECT_TRUE(probeRun(m, plainRow().method, 40).passes());
  EXPECT_FALSE(probeRun(m, linkRow().method, 22).passes());
}

// Each test drive's link steps checked on its dynamics: the probe's ladder starts at the estimate's
// division and stops at the first rung that passes, every rung before it failing; the pump and
// idler drives, whose dynamic roller forces the estimate does not see, get a shorter real-time
// step than the default's 1e-4/28, the idler's the shortest (measured closed loop at 6000 rpm:
// docs/study/drive_steps/), and the reason says so.
TEST(DriveDefaults, TheTestDrivesStepsCheckedOnTheirDynamics) {
  long long realtime[4] = {};
  int k = 0;
  for (const char* name : {"dohc_8mm", "sohc_single_cam", "diesel_pump", "idler"}) {
    const Model m = testDrive(name);
    for (const SolverDefaults* table : {&linkRow(), &plainRow()}) {
      const DriveRow r = driveRow(m, *table);
      ASSERT_TRUE(r.probe.has_value()) << name;
      const ProbedStep& p = *r.probe;
      EXPECT_TRUE(p.passed) << name << ": " << r.reason;
      EXPECT_EQ(p.runs.front().divisions, r.estimateDivisions) << name;
      EXPECT_EQ(p.runs.back().divisions, r.divisions) << name;
      EXPECT_EQ(r.row.step, 1e-4 / static_cast<double>(r.divisions)) << name;
      for (std::size_t i = 0; i + 1 < p.runs.size(); ++i) EXPECT_FALSE(p.runs[i].passes()) << name;
      EXPECT_TRUE(contains(r.reason, "checked on the drive's dynamics")) << r.reason;
      if (table == &linkRow()) realtime[k] = r.divisions;
    }
    ++k;
  }
  EXPECT_GT(realtime[2], 28);
  EXPECT_GT(realtime[3], realtime[2]);
  // the default drive with the spring-damper tensioner: another drive, probed too (and so cached
  // for the FMI call fuzz's sequences on its FMU, tests/fuzz/fuzz_supervisor.cpp)
  const Model springDamper =
      assemble(loadDriveDescription(std::string(CHAINDRIVE_SOURCE_DIR) + "/tests/data/drives/default_drive_spring_damper.json"));
  for (const SolverDefaults* table : {&linkRow(), &plainRow()}) {
    const DriveRow r = driveRow(springDamper, *table);
    ASSERT_TRUE(r.probe.has_value());
    EXPECT_TRUE(r.probe->passed) << r.reason;
  }
}

// A step given is the step; a method named without one takes its row's, the drive's (plain
// Verlet's row for a method without a row of its own), and says so.
TEST(DriveDefaults, ChooseStep) {
  const Model& m = *defaultModel();
  const StepChoice given = chooseStep(m, linkRow(), IntegratorMethod::FixedVerlet, 3e-6);
  EXPECT_EQ(given.step, 3e-6);
  EXPECT_TRUE(contains(given.reason, "given")) << given.reason;
  EXPECT_EQ(chooseStep(m, linkRow(), linkRow().method).step, 1e-4 / 28);
  EXPECT_EQ(chooseStep(m, linkRow(), IntegratorMethod::FixedVerlet).step, 2.5e-6);
  const StepChoice newmark = chooseStep(m, linkRow(), IntegratorMethod::FixedNewmark);
  EXPECT_EQ(newmark.step, 2.5e-6);
  EXPECT_TRUE(contains(newmark.reason, "(fixed-newmark takes the step of fixed-verlet)")) << newmark.reason;
  const Model light = testDrive("dohc_8mm");
  EXPECT_EQ(chooseStep(light, linkRow(), linkRow().method).step, driveRow(light, linkRow()).row.step);
}

// A blow-up's advice: the step it ran with and, where that was above the drive's stable step, the
// stable step to try under the name of its setting; else a fifth shorter than the step that failed.
TEST(DriveDefaults, StepAdvice) {
  const Model light = testDrive("dohc_8mm");
  const DriveRow r = driveRow(light, linkRow());
  const std::string above = stepAdvice(light, linkRow(), 1e-4 / 28, "solver.step");
  char expected[160];
  std::snprintf(expected, sizeof expected, "the step was 3.571 us, above this drive's estimated stable step: try "
                "solver.step = %.4g s (1e-4/%lld)", r.row.step, r.divisions);
  EXPECT_EQ(above, expected);
  EXPECT_TRUE(contains(stepAdvice(light, linkRow(), 1e-4 / 28, "--step"), "try --step ")) << above;
  const std::string within = stepAdvice(*defaultModel(), linkRow(), 1e-4 / 28, "solver.step");
  EXPECT_TRUE(contains(within, "the step was 3.571 us, not above this drive's estimated stable step (1e-4/28 for "
                               "fixed-verlet-implicit-joint-damping)")) << within;
  EXPECT_TRUE(contains(within, "try a shorter one, solver.step = 2.857e-06 s (1e-4/35)")) << within;
}

// A description no run can take (a link of 1e-300 kg: its modes' step near 1e-150 s) is named, not
// turned into an overflowing division or a probe of endless steps; divisionsWithin saturates.
TEST(DriveDefaults, AStepNoRunCanTakeIsNamed) {
  EXPECT_EQ(divisionsWithin(1e-4, 1e-300), kNoDivision);
  EXPECT_EQ(divisionsWithin(1e-4, std::nan("")), kNoDivision);
  EXPECT_EQ(divisionsWithin(1e-4, 1e-4 / 28), 28);
  const Model m = assemble(modifiedDefault([](nlohmann::json& j) { j["chain"]["linkMass"] = 1e-300; }));
  for (const SolverDefaults* table : {&linkRow(), &plainRow()}) {
    try {
      driveRow(m, *table);
      ADD_FAILURE() << "a step was chosen";
    } catch (const DescriptionError& e) {
      EXPECT_TRUE(contains(e.what(), "the link model's estimated stable step")) << e.what();
      EXPECT_TRUE(contains(e.what(), "no run can take it")) << e.what();
    }
  }
}
