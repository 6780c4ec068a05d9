// The link model's stiffest local modes and the fixed step an explicit scheme holds on them: what
// limits the step of the link fidelity (docs/defaults.md#a-step-that-fits-the-drive), in closed
// form from the chain's joints and its stiffest contact law against a link's mass and inertia.
//
// A link in a wrap has both its rollers seated (the rollers sit on every other link, one at each
// pin: dynamics/link_loops.h), its neighbours moving against it. Two modes of such a link:
// - translation across the chain: four joint stiffnesses (each joint deformed twice over by
//   neighbours moving the other way) and both contacts, (4 k_joint + 2 k_contact) / m;
// - rotation: the pins at +-p/2, (k_joint + k_contact / 2) p^2 / J.
// Each mode's stable step is Verlet's with the damping it takes explicitly (integrators/
// stable_step.h): the contacts' always (their Hunt-Crossley damping, 1.5 alpha times the spring
// force, is taken at the reference roller force below), the joints' only where the scheme takes
// them explicitly (plain Verlet; the real-time method takes them implicitly). Measured against
// the step limits of the default drive with its stiffnesses, masses and damping changed one by
// one (docs/defaults.md): the measured limits lie within about 10 % of the estimate's ratios for
// plain Verlet; for the real-time method the modes explain the contacts and the link's mass and
// inertia, not the gain the implicit joints' damping adds (stiffer joints lose more than the
// modes say). Rotors are not counted: a heavier idler or pump makes the step limit shorter, not
// longer (their rotors' own modes lie far below the links').
#pragma once

#include "assembly/model.h"

namespace chaindrive {

/// [N] The roller force the contacts' damping and nonlinear stiffness are taken at: about the
/// largest roller force of the default drive at 6000 rpm (its tight span's peak tension). The
/// contacts' damping grows with their force, and a drive's dynamic forces set how much it
/// shortens the step; the reference stands for a drive like the default.
constexpr double kReferenceContactForce = 1e3;

/// The stiffest link mode's stable step and what sets it.
struct LinkModeStep {
  double step = 0.0;              // [s] the smallest of the modes' Verlet stable steps
  const char* mode = "";          // "translation" or "rotation"
  const char* contact = "";       // the stiffest contact law: "roller-sprocket" or "plate-guide"
  double contactStiffness = 0.0;  // [N/m] its slope at the reference force
  double contactDamping = 0.0;    // [N s/m] its damping at the reference force
  double jointDampingRatio = 0.0; // that mode's damping ratio from the joints alone (their damping
                                  // over their stiffness's frequency), however the scheme takes it
};

/// The link model's explicit stable step from its stiffest modes: the joints and the stiffer of
/// the two contact laws (by their slope at kReferenceContactForce), on the links' mass and inertia,
/// with the joints' damping counted as explicit or not (the real-time method takes it implicitly).
LinkModeStep linkModeStep(const Model& m, bool jointDampingExplicit);

}  // namespace chaindrive
