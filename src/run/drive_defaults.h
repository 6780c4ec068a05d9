// A timing drive's own solver defaults: the rows of the one table (run/defaults.h) with the steps
// that fit the drive (docs/defaults.md#a-step-that-fits-the-drive). Each timing row's step is the
// largest kStepInterval / n not above margin x estimate, where
// - the estimate is the drive's stable step for the row's method: for the link rows the default
//   drive's measured closed-loop limit at 6000 rpm scaled by the ratio of the drive's stiffest link
//   mode's step to the default's (dynamics/link_modes.h: the real-time method with the joints'
//   damping implicit, plain Verlet with it explicit), for the span row the span model's own
//   (span/span_modes.h);
// - the margin is the default drive's: its row's step over its own estimate, so that the default
//   drive keeps the table's steps bit for bit (1e-4 / 28, 2.5e-6 = 1e-4 / 40, 1e-4 / 3) and every
//   result made with them.
// A link row of a drive other than the default (whose steps are its measured closed-loop ones)
// is then checked on the drive's own dynamics (step_probe.h), which the estimate does not see: the
// step is the probe's first step from the estimate's down that passes.
// The span row never exceeds the table's 1e-4 / 3, the step its accuracy was checked at (it lies far
// inside its stable step). The CVT's row is the CVT's.
#pragma once

#include <optional>
#include <string>

#include "assembly/model.h"
#include "run/defaults.h"
#include "run/step_probe.h"

namespace chaindrive {

/// A row of the defaults for one drive: the table's method and tolerance with the drive's step,
/// and why.
struct DriveRow {
  SolverDefaults row;       // the table's row with the drive's step
  long long divisions = 0;  // row.step = kStepInterval / divisions (0: a row no drive changes)
  long long estimateDivisions = 0;  // the division within margin x estimate (before the probe)
  std::optional<ProbedStep> probe;  // a link row of a drive other than the default: its step checked
                                    // on the drive's own dynamics (step_probe.h)
  double estimate = 0.0;    // [s] the drive's estimated stable step for the row's method (0: none)
  double margin = 0.0;      // the default drive's row step over its estimate
  std::string limitedBy;    // what sets the estimate, in words
  std::string reason;       // one line: "step 3.571e-06 s = 1e-4/28: the drive's stability estimate ..."
};

/// The drive's row for a row of the table; `checkOnDynamics` false: the estimate's step alone,
/// without the probe (what the estimate's own tests look at). Throws DescriptionError for the span
/// row of a drive without a span model (span_model.h).
DriveRow driveRow(const Model& m, const SolverDefaults& tableRow, bool checkOnDynamics = true);

/// The step of a run and why: `given` as given, else the step of the drive's row for `method`
/// (defaultStepRow on the run's own table row `own`).
struct StepChoice {
  double step = 0.0;   // [s]
  std::string reason;  // one line
};
StepChoice chooseStep(const Model& m, const SolverDefaults& own, IntegratorMethod method,
                      std::optional<double> given = std::nullopt);

/// What a run that blew up at the fixed step `step` should try, one clause to append to its
/// failure: the step it ran with and the drive's stable step of `stableRow` (the drive's row for
/// its method), or, where the step was not above it, a shorter one. `stepName` names the step's
/// setting where the failure is read ("solver.step", "--step").
std::string stepAdvice(const Model& m, const SolverDefaults& stableRow, double step, const std::string& stepName);

}  // namespace chaindrive
