// A drive's link step checked on its own dynamics (docs/defaults.md#the-probe-the-drives-own-dynamics).
// The stability estimate (drive_defaults.h) sees the drive's chain, contacts and links but not
// its dynamic roller forces, which set how much the contacts' explicit Hunt-Crossley damping costs
// the step: the pump and idler drives have the default's chain, so its estimate and step, yet at
// that step their energy balance at 6000 rpm missed the main job's 5 % (-13 %) or they blew up.
// The probe runs the drive at the top speed the steps are measured at, open loop for 0.2 s (10
// engine cycles at 6000 rpm: the preload's transient and the tensioner's pumping up included),
// with a rotational vibration of order 2 and a constant load on every loaded sprocket, at the
// estimate's step; a blow-up, or an energy balance beyond the default drive's at its own step
// (kProbeBalanceLimit), takes the next step of a ladder about a tenth shorter, until one passes.
// Its result is kept in the cache folder of the span calibrations (span/calibration_cache.h), keyed
// by the drive, its parameter overrides, the code, the method and the step it started from, so
// a drive is probed once per machine (about 0.6 s of CPU per 0.2 s run at 1e-4/28).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "assembly/model.h"
#include "integrators/ode_system.h"

namespace chaindrive {

/// The probe's run: 6000 rpm, 0.2 s, crankshaft vibration of order 2 with 0.3 deg, 5 N m on every
/// loaded sprocket (+ opposing its rotation), as the step limits of docs/defaults.md were measured.
constexpr double kProbeSpeedRpm = 6000.0;
constexpr double kProbeDuration = 0.2;            // [s]
constexpr double kProbeVibrationOrder = 2.0;      // per crankshaft revolution
constexpr double kProbeVibrationDeg = 0.3;        // [deg] its angle amplitude
constexpr double kProbeLoad = 5.0;                // [N m]

/// |energy balance| of the probe, of its dissipated energy, that a step may reach: the default
/// drive's at its own step (-2.95 % at 1e-4/28 with the real-time method, whose closed-loop balance
/// at 6000 rpm is 4.7 %, inside the main job's 5 %), rounded up.
constexpr double kProbeBalanceLimit = 0.03;

/// Each rung of the ladder divides the step interval into at least a tenth more steps.
constexpr double kProbeLadderFactor = 1.1;
constexpr int kProbeMaxRuns = 12;                 // the ladder's last rung: about 1/3 of its first step
/// The shortest step probed, kStepInterval / kProbeMostDivisions (0.25 us, 7 times the default's
/// CPU per run): a row whose estimate lies below is not probed, and the ladder stops there.
constexpr long long kProbeMostDivisions = 400;

/// One probe run at kStepInterval / divisions.
struct ProbeRun {
  long long divisions = 0;
  bool blewUp = false;         // the run failed (its reason in failure)
  double energyBalance = 0.0;  // (input work - dissipated - change of stored energy) / dissipated
  std::string failure;
  bool passes() const;
};

/// The ladder's outcome: the first rung that passed (or the last one tried) and every run.
struct ProbedStep {
  long long divisions = 0;
  bool passed = false;
  std::vector<ProbeRun> runs;  // in the order run
};

/// One probe run of m with `method` (compliant contacts) at kStepInterval / divisions.
ProbeRun probeRun(const Model& m, IntegratorMethod method, long long divisions);

/// The ladder from `fromDivisions` (the estimate's step) up, or its cached outcome.
ProbedStep probeStep(const Model& m, IntegratorMethod method, long long fromDivisions);

/// The ladder as JSON (the cache's content, chaindrive-info --defaults): divisions, passed, the
/// balance limit, and per run its divisions, blewUp, energyBalance and failure.
nlohmann::json probeJson(const ProbedStep& p);

/// "energy balance -2.76 % at 1e-4/56 (1e-4/28 -18.46 %, 1e-4/31 blew up, ...)": the probe in words.
std::string describeProbe(const ProbedStep& p);

}  // namespace chaindrive
