#include "run/drive_defaults.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "dynamics/link_modes.h"
#include "integrators/stable_step.h"
#include "math/elementary.h"
#include "span/span_modes.h"

namespace chaindrive {

namespace {

// The default drive's measured closed-loop step limits at 6000 rpm (python -m harness run --rpm
// 6000 --cycles 120 --method M --solver-step 1e-4/N, docs/defaults.md): the largest division of
// kStepInterval that ran 120 cycles and the smallest that blew up. A drive's link estimate is
// their geometric mean scaled by its link modes.
struct MeasuredLimit {
  IntegratorMethod method;
  int ran, blewUp;  // kStepInterval / ran ran, kStepInterval / blewUp blew up
  double step() const { return kStepInterval / std::sqrt(static_cast<double>(ran) * blewUp); }
};
constexpr MeasuredLimit kDefaultDriveLimits[] = {
    {IntegratorMethod::FixedVerletImplicitJointDamping, 24, 23},  // 4.167 us ran, 4.348 us blew up
    {IntegratorMethod::FixedVerlet, 33, 32},                      // 3.030 us ran, 3.125 us blew up
};

// The real-time method's closed-loop limit lies 1.42 times above the explicit step of the default
// drive's stiffest link mode: what its implicit joints' damping adds. That gain shrinks where the
// joints are damped less for their stiffness than the default's: measured on the default drive
// with its joints 1.5, 2 and 3 times as stiff at its damping (open loop at 6000 rpm, 0.79, 0.65 and
// 0.55 of its limit where the modes say 0.91, 0.84 and 0.74; twice as stiff with the damping
// ratio kept, 0.82 where they say 0.84) it goes as the joints' damping ratio of the stiffest mode
// to this power; above the default's ratio it is not counted (a lighter link's or a more damped
// joint's gain was not measured larger).
constexpr double kJointDampingGainExponent = 0.75;

// The most steps per kStepInterval a drive's row may take (a step of 0.1 ns): a shorter estimate
// comes from a description no run can take (a link of 1e-300 kg), named rather than run.
constexpr long long kMostDivisions = 1000000;

// The real-time method takes the joints' damping implicitly; every other method is measured as
// plain Verlet (the row of joints with clearance or rigid contacts).
bool jointDampingExplicit(IntegratorMethod method) { return method != IntegratorMethod::FixedVerletImplicitJointDamping; }

const MeasuredLimit& measuredLimit(IntegratorMethod method) {
  return jointDampingExplicit(method) ? kDefaultDriveLimits[1] : kDefaultDriveLimits[0];
}

// The default drive's own estimates, once per process (an immutable constant: the default drive's
// model and its span model, uncalibrated).
struct DefaultEstimates {
  double realtimeModes = 0.0, plainModes = 0.0;  // [s] linkModeStep, joints' damping implicit, explicit
  double realtimeJointDampingRatio = 0.0;        // linkModeStep's, joints' damping implicit
  double span = 0.0;                             // [s] spanModeStep
};
const DefaultEstimates& defaultEstimates() {
  static const DefaultEstimates e = [] {
    const Model m = assemble(defaultDriveDescription());
    DefaultEstimates d;
    const LinkModeStep realtime = linkModeStep(m, false);
    d.realtimeModes = realtime.step;
    d.realtimeJointDampingRatio = realtime.jointDampingRatio;
    d.plainModes = linkModeStep(m, true).step;
    d.span = span::spanModeStep(span::assembleSpanModel(m, false)).step;
    return d;
  }();
  return e;
}

std::string format(const char* fmt, double a) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, a);
  return buf;
}

// "1e-4/28"
std::string division(long long n) { return "1e-4/" + std::to_string(n); }

// The link rows: the default's measured limit scaled by the drive's link modes.
void linkEstimate(const Model& m, DriveRow& r) {
  const bool jointsExplicit = jointDampingExplicit(r.row.method);
  const LinkModeStep modes = linkModeStep(m, jointsExplicit);
  const DefaultEstimates& d = defaultEstimates();
  const double limit = measuredLimit(r.row.method).step();
  r.estimate = limit * modes.step / (jointsExplicit ? d.plainModes : d.realtimeModes);
  r.margin = r.row.step / limit;
  r.limitedBy = std::string(modes.contact) + " contact " + format("%.3g", modes.contactStiffness) + " N/m on a " +
                format("%.3g", m.chain.mass * 1e3) + " g link, its " + modes.mode;
  if (!jointsExplicit && modes.jointDampingRatio < d.realtimeJointDampingRatio) {
    const double ratio = modes.jointDampingRatio / d.realtimeJointDampingRatio;
    r.estimate *= math::pow(ratio, kJointDampingGainExponent);
    r.limitedBy += "; the joints' damping ratio " + format("%.3g", modes.jointDampingRatio) + ", the default's " +
                   format("%.3g", d.realtimeJointDampingRatio) + ": x " + format("%.3g", math::pow(ratio, kJointDampingGainExponent));
  }
}

// The span row: the span model's own stable step.
void spanEstimate(const Model& m, DriveRow& r) {
  const span::SpanModeStep modes = span::spanModeStep(span::assembleSpanModel(m, false));
  r.estimate = modes.step;
  r.margin = r.row.step / defaultEstimates().span;
  r.limitedBy = "span " + modes.stiffestSpan + ", " + format("%.3g", modes.spanStiffness) + " N/m";
}

// The link row's step checked on the drive's own dynamics (step_probe.h): not the default drive's
// (its steps are its measured closed-loop ones, whatever its tensioner's parameters), not a drive
// with rigid contacts (the probe runs compliant ones). Returns the reason's clause.
std::string probeLinkRow(const Model& m, DriveRow& r) {
  if (isDefaultDrive(m.description)) return "";
  if (m.description.contact.method != ContactMethod::Compliant)
    return "; not checked on the drive's dynamics (its contacts are rigid; the probe runs compliant ones)";
  if (r.divisions > kProbeMostDivisions)
    return "; not checked on the drive's dynamics (a step below " + division(kProbeMostDivisions) +
           ": a probe of " + format("%g", kProbeDuration) + " s would take minutes)";
  try {
    r.probe = probeStep(m, r.row.method, r.divisions);
  } catch (const std::exception& e) {  // (a drive the link model cannot start: its run says why)
    return std::string("; not checked on the drive's dynamics (") + e.what() + ")";
  }
  r.divisions = r.probe->divisions;
  return "; checked on the drive's dynamics (" + format("%g", kProbeDuration) + " s open loop at " +
         format("%g", kProbeSpeedRpm) + " rpm, " + format("%g", kProbeLoad) + " N m per loaded sprocket: |energy balance| " +
         "within " + format("%g", 100.0 * kProbeBalanceLimit) + " %): " + describeProbe(*r.probe) +
         (r.probe->passed ? "" : ", no step of the ladder passed");
}

}  // namespace

DriveRow driveRow(const Model& m, const SolverDefaults& tableRow, bool checkOnDynamics) {
  DriveRow r;
  r.row = tableRow;
  if (tableRow.scene != Scene::TimingDrive) {
    r.reason = "step " + format("%.4g", tableRow.step) + " s: the table's (a drive does not change it)";
    return r;
  }
  const bool span = tableRow.fidelity == Fidelity::Span;
  if (span) spanEstimate(m, r);
  else linkEstimate(m, r);
  const std::string what = span ? "the span model's" : "the drive's";
  // the largest division within margin x estimate (the span row: not beyond the table's)
  const long long tableDivisions = std::llround(kStepInterval / tableRow.step);
  r.divisions = std::isfinite(r.estimate) ? divisionsWithin(kStepInterval, r.margin * r.estimate) : 1;
  const bool capped = span && r.divisions < tableDivisions;
  if (capped) r.divisions = tableDivisions;
  if (r.divisions > kMostDivisions)
    throw DescriptionError({std::string(span ? "the span model's" : "the link model's") + " estimated stable step " +
                            format("%.3g", r.estimate) + " s (stiffest: " + r.limitedBy + ") is below " +
                            format("%.3g", kStepInterval / static_cast<double>(kMostDivisions)) +
                            " s: no run can take it; check the chain's link mass and inertia and its stiffnesses"});
  r.estimateDivisions = r.divisions;
  const std::string probed = span || !checkOnDynamics ? "" : probeLinkRow(m, r);
  r.row.step = kStepInterval / static_cast<double>(r.divisions);
  r.reason = "step " + format("%.4g", r.row.step) + " s = " + division(r.divisions) + ": " + what +
             " stability estimate " + format("%.4g", r.estimate * 1e6) + " us (stiffest: " + r.limitedBy + ") x " +
             format("%.3g", r.margin) + ", the default drive's margin" +
             (r.divisions != r.estimateDivisions ? ", " + division(r.estimateDivisions) : "") + probed;
  if (capped) r.reason += "; not above " + division(tableDivisions) + ", the step its accuracy was checked at";
  return r;
}

StepChoice chooseStep(const Model& m, const SolverDefaults& own, IntegratorMethod method, std::optional<double> given) {
  if (given) return {*given, "step " + format("%.4g", *given) + " s: given"};
  const SolverDefaults& tableRow = defaultStepRow(own, method);
  DriveRow r = driveRow(m, tableRow);
  if (tableRow.method != method)
    r.reason += std::string(" (") + choiceName(method) + " takes the step of " + choiceName(tableRow.method) + ")";
  return {r.row.step, r.reason};
}

std::string stepAdvice(const Model& m, const SolverDefaults& stableRow, double step, const std::string& stepName) {
  const DriveRow r = driveRow(m, stableRow);
  const std::string ran = "the step was " + format("%.4g", step * 1e6) + " us, ";
  const std::string stable = r.divisions > 0 ? "this drive's estimated stable step" : "the step its row was checked at";
  auto setting = [&](double h, long long n) {
    const std::string value = format("%.4g", h);
    return (stepName.rfind("--", 0) == 0 ? stepName + " " + value : stepName + " = " + value + " s") +
           (n > 0 ? " (" + division(n) + ")" : std::string());
  };
  if (step > r.row.step * (1.0 + 1e-12)) return ran + "above " + stable + ": try " + setting(r.row.step, r.divisions);
  // not explained by the estimate: a fifth shorter than the step that failed
  const long long n = divisionsWithin(kStepInterval, 0.8 * step);
  return ran + "not above " + stable + " (" + (r.divisions > 0 ? division(r.divisions) : format("%.4g s", r.row.step)) +
         " for " + choiceName(stableRow.method) + "), which does not cover this run: try a shorter one, " +
         setting(kStepInterval / static_cast<double>(n), n);
}

}  // namespace chaindrive
