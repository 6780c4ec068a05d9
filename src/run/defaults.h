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

struct SolverDefaults {
  Scene scene;
  Fidelity fidelity;
  IntegratorMethod method;
  double step;       // [s] the fixed step (adaptive methods: none unless given)
  double tolerance;  // the adaptive methods' relative tolerance
};

// clang-format off
// (why each row is what it is, with the measurements behind it: docs/defaults.md)
inline constexpr SolverDefaults kSolverDefaults[] = {
  {Scene::TimingDrive, Fidelity::Link, IntegratorMethod::FixedVerlet, 2.5e-6, 1e-5},
  {Scene::TimingDrive, Fidelity::Span, IntegratorMethod::FixedVerlet, 1e-4 / 3, 1e-5},
  {Scene::Cvt, Fidelity::Link, IntegratorMethod::FixedVerlet, 5e-7, 1e-5},
};
// clang-format on

/// The row of a scene and fidelity (every pair that runs has one).
constexpr const SolverDefaults& solverDefaults(Scene scene, Fidelity fidelity = Fidelity::Link) {
  for (const SolverDefaults& row : kSolverDefaults)
    if (row.scene == scene && row.fidelity == fidelity) return row;
  return kSolverDefaults[0];  // (unreachable for the pairs above; a constexpr function must return)
}

/// Sets the method, the fixed step and the tolerance of a row into integrator settings.
inline void applySolverDefaults(const SolverDefaults& row, IntegratorSettings& settings) {
  settings.method = row.method;
  settings.fixed.step = row.step;
  settings.adaptive.rtol = row.tolerance;
}

}  // namespace chaindrive
