// The solver defaults of every entry point, per scene and fidelity, in one table: chaindrive-run,
// chaindrive-cvt, both FMUs and the harness (which reads it through `chaindrive-info --defaults`)
// start from these rows, so that a run is the same run whichever way it is started. Each row is
// the fastest setting whose results were checked against a finer reference (docs/defaults.md).
#pragma once

#include "choice.h"
#include "description/choices.h"
#include "integrators/ode_system.h"

namespace chaindrive {

/// The scenes: the roller-chain timing drive (ChainDrive.fmu, chaindrive-run) and the chain CVT
/// (CVTChain.fmu, chaindrive-cvt).
enum class Scene { TimingDrive, Cvt };
template <>
struct ChoiceNames<Scene> {
  static constexpr ChoiceName<Scene> table[] = {{Scene::TimingDrive, "timing"}, {Scene::Cvt, "cvt"}};
};

/// [s] The communication step every timing row's step divides (the FMU's 0.1 ms): a row's step is
/// kStepInterval / n for a whole n.
constexpr double kStepInterval = 1e-4;

struct SolverDefaults {
  Scene scene;
  Fidelity fidelity;
  bool clearanceOrRigid;  // the row of runs the real-time method does not serve: joints with clearance
                          // (their damping not constant) or rigid contacts (time stepping's step)
  IntegratorMethod method;
  double step;       // [s] the fixed step (adaptive methods: none unless given)
  double tolerance;  // the adaptive methods' relative tolerance
};

// clang-format off
// (why each row is what it is, with the measurements behind it: docs/defaults.md). The timing
// rows are the default drive's: another drive's steps follow from its stability estimate
// (run/drive_defaults.h), the same rows for the default drive.
inline constexpr SolverDefaults kSolverDefaults[] = {
  {Scene::TimingDrive, Fidelity::Link, false, IntegratorMethod::FixedVerletImplicitJointDamping, 1e-4 / 28, 1e-5},
  {Scene::TimingDrive, Fidelity::Link, true, IntegratorMethod::FixedVerlet, 2.5e-6, 1e-5},
  {Scene::TimingDrive, Fidelity::Span, false, IntegratorMethod::FixedVerlet, 1e-4 / 3, 1e-5},
  {Scene::Cvt, Fidelity::Link, false, IntegratorMethod::FixedVerlet, 5e-7, 1e-5},
};
// clang-format on

/// The row of a scene and fidelity (every pair that runs has one) for a run with joints with
/// clearance or rigid contacts, or not: the link fidelity's real-time method makes the joints'
/// damping implicit, which needs it constant (no clearance), and it integrates compliant contacts;
/// a drive with clearance runs plain Verlet at its checked step, time stepping that step. Where no
/// row names them the fidelity's one row holds for both.
constexpr const SolverDefaults& solverDefaults(Scene scene, Fidelity fidelity = Fidelity::Link,
                                               bool clearanceOrRigid = false) {
  const SolverDefaults* found = nullptr;
  for (const SolverDefaults& row : kSolverDefaults)
    if (row.scene == scene && row.fidelity == fidelity && (!found || row.clearanceOrRigid == clearanceOrRigid))
      found = &row;
  return found ? *found : kSolverDefaults[0];  // (kSolverDefaults[0]: unreachable for the pairs above)
}

/// The row whose step `method` takes where none is given: the own row for its method, else the
/// scene and fidelity's row of that method, else its row for joints with clearance or rigid
/// contacts (plain Verlet's checked step: a method without a row of its own is not checked at the
/// real-time method's longer step), else the own row.
constexpr const SolverDefaults& defaultStepRow(const SolverDefaults& own, IntegratorMethod method) {
  if (method == own.method) return own;
  for (const SolverDefaults& row : kSolverDefaults)
    if (row.scene == own.scene && row.fidelity == own.fidelity && row.method == method) return row;
  return solverDefaults(own.scene, own.fidelity, true);  // (the own row where there is no such row)
}

/// The fixed step [s] of `method` where none is given, for the default drive (defaultStepRow's
/// row; a drive's own steps: run/drive_defaults.h).
constexpr double defaultStep(const SolverDefaults& own, IntegratorMethod method) {
  return defaultStepRow(own, method).step;
}

/// Sets the method, the fixed step and the tolerance of a row into integrator settings.
inline void applySolverDefaults(const SolverDefaults& row, IntegratorSettings& settings) {
  settings.method = row.method;
  settings.fixed.step = row.step;
  settings.adaptive.rtol = row.tolerance;
}

}  // namespace chaindrive
