// The span model's calibration against the link model's statics at loads and supply pressures
// off the calibration's grid, its guide geometry against the link model's guide torque, its pose
// design, the cache of calibrations (a hit has the same bits, a changed drive misses, a damaged
// file is calibrated afresh) and the read-only calibration file an FMU carries.
#include "span/calibration_cache.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "run/simulation.h"
#include "test_util.h"

namespace chaindrive::span {
namespace {

using test::defaultModel;
using test::named;

// Both fidelities' start states (their statics) at 3000 rpm under the given loads and supply.
struct StaticPair {
  Outputs link, span;
};

StaticPair statics(const std::shared_ptr<const Model>& m, double intake, double exhaust, double supply) {
  auto inputs = [&] {
    auto in = std::make_unique<HeldInputs>(*m);
    in->values.crankSpeed = 3000.0 * 2.0 * kPi / 60.0;
    in->values.loadTorque[m->rotorIndex("camshaftIntake")] = intake;
    in->values.loadTorque[m->rotorIndex("camshaftExhaust")] = exhaust;
    in->values.supplyPressure = supply;
    return in;
  };
  SimulationOptions linkOpt, spanOpt;
  linkOpt.integrator.method = spanOpt.integrator.method = named<IntegratorMethod>("fixed-verlet");
  spanOpt.fidelity = named<Fidelity>("span");
  spanOpt.integrator.fixed.step = 2e-5;
  Simulation link(m, linkOpt, inputs()), span(m, spanOpt, inputs());
  link.start(0.0);
  span.start(0.0);
  return {link.outputs(), span.outputs()};
}

// Within 2 %: the tensioner force and the tension guide's angle. (The camshafts' turn under
// load is within 2 to 17 %: a span's law holds its own tension, while the seating at the
// crankshaft sprocket follows both spans that meet there: docs/fidelities.md.)
TEST(SpanCalibration, StaticsUnderLoadsMatchTheLinkModel) {
  const auto m = defaultModel();
  const int guide = m->tensioner.rotor;
  struct Case {
    double intake, exhaust, supply;
  };
  for (const Case c : {Case{7.0, 3.0, 3e5}, Case{25.0, 15.0, 3e5}, Case{12.0, 30.0, 20e5}, Case{2.0, 2.0, 40e5}}) {
    const StaticPair s = statics(m, c.intake, c.exhaust, c.supply);
    const std::string at = "loads " + std::to_string(c.intake) + ", " + std::to_string(c.exhaust) + " N m, supply " +
                           std::to_string(c.supply / 1e5) + " bar";
    EXPECT_NEAR(s.span.tensionerForce, s.link.tensionerForce, 0.02 * s.link.tensionerForce) << at;
    EXPECT_NEAR(s.span.rotorAngle[guide], s.link.rotorAngle[guide], 0.02 * std::fabs(s.link.rotorAngle[guide])) << at;
  }
}

// The span model's guide geometry (the chain bends over the face's ends) gives the chain's
// torque on the tension guide that the link model's statics need, within 2 %, over every pose
// of the calibration (the tension guide turns 1.3 to 3.3 deg over them); its table covers the
// guide's whole angle range.
TEST(SpanCalibration, GuideGeometryHoldsTheLinkModelsTorque) {
  const auto m = defaultModel();
  const SpanModel sm = assembleSpanModel(*m, false);
  const SpanCalibration c = identifySpanLaws(sm);
  ASSERT_EQ(c.leverRatioMin.size(), 1u);
  EXPECT_GT(c.leverRatioMin[0], 0.98);
  EXPECT_LT(c.leverRatioMax[0], 1.02);
  const GuideDesc& gd = m->description.guides[m->description.guideIndex("tensionGuide")];
  EXPECT_DOUBLE_EQ(sm.tables[0].angleMin(), gd.angleMin);
  EXPECT_NEAR(sm.tables[0].angleMax(), gd.angleMax, 1e-12);
  EXPECT_GE(c.poses, 100);
}

// A second calibration of the same drive comes from the cache with the same bits; a changed
// drive misses; a damaged file is calibrated afresh.
TEST(SpanCalibration, CacheHitsMissesAndRecovers) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "chaindrive-calibration-test";
  std::filesystem::remove_all(dir);
  const char* before = std::getenv("CHAINDRIVE_CACHE_DIR");
  const std::string saved = before ? before : "";
  ASSERT_EQ(setenv("CHAINDRIVE_CACHE_DIR", dir.string().c_str(), 1), 0);
  const auto m = defaultModel();
  auto calibrated = [](const Model& model, bool& fromCache, std::string& file) {
    SpanModel sm = assembleSpanModel(model, false);
    calibrateSpanModel(sm, &fromCache, &file);
    return sm;
  };
  bool hit = true;
  std::string file;
  const SpanModel first = calibrated(*m, hit, file);
  EXPECT_FALSE(hit);
  ASSERT_TRUE(std::filesystem::exists(file)) << file;
  const SpanModel second = calibrated(*m, hit, file);
  EXPECT_TRUE(hit);
  for (std::size_t i = 0; i < first.spans.size(); ++i) {
    EXPECT_EQ(first.spans[i].engagement.stretch, second.spans[i].engagement.stretch);
    EXPECT_EQ(first.spans[i].engagement.tension, second.spans[i].engagement.tension);
    EXPECT_EQ(first.spans[i].engagement.energy, second.spans[i].engagement.energy);
  }
  DriveDescription changed = m->description;
  changed.tensioner.preload += 1.0;
  const Model other = assemble(changed);
  EXPECT_NE(calibrationKey(other), calibrationKey(*m));
  std::string otherFile;
  calibrated(other, hit, otherFile);
  EXPECT_FALSE(hit);
  EXPECT_NE(otherFile, file);
  std::ofstream(file) << "{ not a calibration";
  calibrated(*m, hit, file);
  EXPECT_FALSE(hit);
  calibrated(*m, hit, file);
  EXPECT_TRUE(hit);
  if (before) setenv("CHAINDRIVE_CACHE_DIR", saved.c_str(), 1);
  else unsetenv("CHAINDRIVE_CACHE_DIR");
  std::filesystem::remove_all(dir);
}

// The poses' loads: the full grid of six levels up to one loaded sprocket, and for two while it
// costs no more than the default drive's (its 36 combinations, in the order its calibration's
// bits depend on: the first sprocket's level changing fastest); else 6 + 5 n rows: the six levels
// on every sprocket together, then each sprocket's other five levels with the rest at the
// reference; every sprocket takes every level. An idler (motion "idler") is no loaded sprocket.
// The test drives: the default drive and the DOHC drive without a chamber keep the grid, the
// 8 mm DOHC drive (154 links) and the pump drive take the linear design.
TEST(SpanCalibration, PoseDesignIsTheFullGridWhereItCostsNoMoreThanTheDefaultDrivesThenGrowsLinearly) {
  const std::vector<double> levels = {-5.0, 0.0, 5.0, 10.0, 20.0, 40.0};
  EXPECT_EQ(calibrationLoads(0, 5, 120), std::vector<std::vector<double>>(1));
  EXPECT_EQ(calibrationLoads(1, 5, 400), fullLoadGrid(1));
  const auto two = calibrationLoads(2, 5, 120);
  ASSERT_EQ(two, fullLoadGrid(2));
  ASSERT_EQ(two.size(), 36u);
  for (std::size_t code = 0; code < two.size(); ++code)
    EXPECT_EQ(two[code], (std::vector<double>{levels[code % 6], levels[code / 6]})) << code;
  EXPECT_EQ(calibrationLoads(2, 5, 121), linearLoadDesign(2));
  EXPECT_EQ(calibrationLoads(2, 1, 200), fullLoadGrid(2));
  for (int n = 2; n <= 6; ++n) {
    const auto rows = linearLoadDesign(n);
    if (n >= 3) {
      EXPECT_EQ(calibrationLoads(n, 1, 50), rows) << n;
    }
    ASSERT_EQ(rows.size(), static_cast<std::size_t>(6 + 5 * n)) << n;
    for (int level = 0; level < 6; ++level) EXPECT_EQ(rows[level], std::vector<double>(n, levels[level])) << n;
    for (int k = 0; k < n; ++k)
      for (double level : levels)
        EXPECT_TRUE(std::any_of(rows.begin(), rows.end(), [&](const std::vector<double>& r) { return r[k] == level; }))
            << n << " sprockets: sprocket " << k << " never at " << level << " N m";
    for (std::size_t p = 6; p < rows.size(); ++p)  // one at a time: the others at the reference
      EXPECT_EQ(std::count(rows[p].begin(), rows[p].end(), 10.0), n - 1) << n << " sprockets, row " << p;
  }
  const auto m = defaultModel();
  EXPECT_EQ(loadedSprockets(*m), (std::vector<int>{m->rotorIndex("camshaftExhaust"), m->rotorIndex("camshaftIntake")}));
  const Model idler = assemble(loadDriveDescription(std::string(CHAINDRIVE_SOURCE_DIR) + "/tests/drives/idler.json"));
  EXPECT_EQ(loadedSprockets(idler), std::vector<int>{idler.rotorIndex("camshaft")});
  auto poses = [](const std::string& file) {
    const Model d = assemble(loadDriveDescription(std::string(CHAINDRIVE_SOURCE_DIR) + file));
    const std::size_t supplies = calibrationSupplies(d).size();
    return calibrationLoads(static_cast<int>(loadedSprockets(d).size()), static_cast<int>(supplies), d.chain.links)
               .size() * supplies;
  };
  EXPECT_EQ(poses("/src/drives/default_drive.json"), 180u);
  EXPECT_EQ(poses("/tests/drives/dohc_8mm.json"), 80u);
  EXPECT_EQ(poses("/tests/drives/sohc_single_cam.json"), 30u);
  EXPECT_EQ(poses("/tests/drives/diesel_pump.json"), 105u);
  EXPECT_EQ(poses("/tests/drives/idler.json"), 30u);
}

// The linear design gives the full grid's laws where both can be had: on the default drive (77 of
// its 80 poses against the grid's 172 of 180) every span's law lies within 15 um of the grid's
// over the tensions both reach (the grid's own fit leaves 7 to 20 um rms; the span between the
// camshafts differs most, 11 um).
TEST(SpanCalibration, LinearDesignGivesTheFullGridsLawsOnTheDefaultDrive) {
  const auto m = defaultModel();
  SpanModel grid = assembleSpanModel(*m, false);
  calibrateSpanModel(grid);  // (the default drive's design: the full grid, from the cache)
  const SpanCalibration linear = identifySpanLaws(assembleSpanModel(*m, false), linearLoadDesign(2));
  EXPECT_EQ(linear.poses + linear.posesRejected, 80);
  auto stretchAt = [](const EngagementLaw& law, double tension) {
    std::size_t k = 1;
    while (k + 1 < law.tension.size() && tension > law.tension[k]) ++k;
    return law.stretch[k - 1] +
           (law.stretch[k] - law.stretch[k - 1]) * (tension - law.tension[k - 1]) / (law.tension[k] - law.tension[k - 1]);
  };
  for (std::size_t i = 0; i < grid.spans.size(); ++i) {
    const EngagementLaw &a = grid.spans[i].engagement, &b = linear.laws[i];
    const double low = std::max(a.tension.front(), b.tension.front()), high = std::min(a.tension.back(), b.tension.back());
    ASSERT_LT(low, high) << grid.spans[i].name;
    for (int k = 0; k <= 100; ++k) {
      const double tension = low + (high - low) * k / 100.0;
      EXPECT_NEAR(stretchAt(b, tension), stretchAt(a, tension), 15e-6) << grid.spans[i].name << " at " << tension << " N";
    }
  }
}

// The calibration file an FMU carries (chaindrive-info --span-calibration: the cache's format and
// key, the cache file's bytes) is looked in before the cache: a span model built with it
// calibrates nothing (an empty cache folder stays empty) and has the laws' bits; a damaged file,
// one of another key and a missing one are passed over with a note naming the file and why, and
// the laws come from the cache. The SOHC test drive: one loaded sprocket, 30 poses.
TEST(SpanCalibration, ReadOnlyFileOfTheDrivesKeyIsTakenOthersArePassedOver) {
  namespace fs = std::filesystem;
  const fs::path base = fs::temp_directory_path() / "chaindrive-calibration-file-test";
  fs::remove_all(base);
  const fs::path cache = base / "cache", empty = base / "empty", file = base / "resources" / "span_calibration.json";
  const char* before = std::getenv("CHAINDRIVE_CACHE_DIR");
  const std::string saved = before ? before : "";
  ASSERT_EQ(setenv("CHAINDRIVE_CACHE_DIR", cache.string().c_str(), 1), 0);
  const auto m = std::make_shared<const Model>(
      assemble(loadDriveDescription(std::string(CHAINDRIVE_SOURCE_DIR) + "/tests/drives/sohc_single_cam.json")));
  SpanModel written = assembleSpanModel(*m, false);
  EXPECT_EQ(writeCalibrationFile(written, file.string()), CalibrationOrigin::Identified);
  const fs::path cacheFile = cache / ("span-" + calibrationKey(*m) + ".json");
  auto bytes = [](const fs::path& f) {
    std::ifstream in(f, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  ASSERT_TRUE(fs::exists(cacheFile));
  EXPECT_EQ(bytes(file), bytes(cacheFile));
  // the span fidelity of a run with the file (as the FMU sets it)
  auto spanModelWith = [&](const fs::path& f) {
    SimulationOptions opt;
    opt.fidelity = named<Fidelity>("span");
    opt.integrator.method = named<IntegratorMethod>("fixed-verlet");
    opt.integrator.fixed.step = 2e-5;
    opt.spanCalibrationFile = f.string();
    return Simulation(m, opt, std::make_unique<HeldInputs>(*m)).spanModel()->notes;
  };
  auto noted = [](const std::vector<std::string>& notes, const std::string& text) {
    return std::any_of(notes.begin(), notes.end(), [&](const std::string& n) { return n.find(text) != std::string::npos; });
  };
  ASSERT_EQ(setenv("CHAINDRIVE_CACHE_DIR", empty.string().c_str(), 1), 0);
  {
    SpanModel sm = assembleSpanModel(*m, false);
    std::string from;
    EXPECT_EQ(calibrateSpanModel(sm, file.string(), &from), CalibrationOrigin::File);
    EXPECT_EQ(from, file.string());
    for (std::size_t i = 0; i < sm.spans.size(); ++i) {
      EXPECT_EQ(sm.spans[i].engagement.stretch, written.spans[i].engagement.stretch);
      EXPECT_EQ(sm.spans[i].engagement.tension, written.spans[i].engagement.tension);
      EXPECT_EQ(sm.spans[i].engagement.energy, written.spans[i].engagement.energy);
    }
    const auto notes = spanModelWith(file);
    EXPECT_TRUE(noted(notes, "calibration: key " + calibrationKey(*m) + ", from the file " + file.string()));
    EXPECT_FALSE(noted(notes, "passed over"));
  }
  EXPECT_FALSE(fs::exists(empty) && !fs::is_empty(empty)) << "calibrated although the file holds the calibration";
  ASSERT_EQ(setenv("CHAINDRIVE_CACHE_DIR", cache.string().c_str(), 1), 0);
  const fs::path damaged = base / "damaged.json", otherKey = base / "other_key.json";
  std::ofstream(damaged) << "{ not a calibration";
  nlohmann::json j = nlohmann::json::parse(bytes(file));
  j["key"] = "0123456789abcdef";
  std::ofstream(otherKey) << j.dump(1);
  for (const auto& [f, why] : {std::pair{damaged, "not a calibration"}, std::pair{otherKey, "key \"0123456789abcdef\""},
                               std::pair{base / "missing.json", "no such file"}}) {
    const auto notes = spanModelWith(f);
    EXPECT_TRUE(noted(notes, "calibration: the file " + f.string() + " passed over: " + why)) << f;
    EXPECT_TRUE(noted(notes, ", from the cache " + cacheFile.string())) << f;
  }
  if (before) setenv("CHAINDRIVE_CACHE_DIR", saved.c_str(), 1);
  else unsetenv("CHAINDRIVE_CACHE_DIR");
  fs::remove_all(base);
}

}  // namespace
}  // namespace chaindrive::span
