// The choices of a drive and of a run, each an enum with its one table of names (choice.h): the
// description reader, the command-line tools and the FMUs parse the names; below them, code
// compares these values. (The integrator methods are numerics: integrators/ode_system.h.)
#pragma once

#include "choice.h"

namespace chaindrive {

/// How contacts act: a compliant force law, or rigid unilateral contacts with Newton impacts,
/// event driven or by Moreau-Jean time stepping.
enum class ContactMethod { Compliant, EventDriven, TimeStepping };
template <>
struct ChoiceNames<ContactMethod> {
  static constexpr ChoiceName<ContactMethod> table[] = {
      {ContactMethod::Compliant, "compliant"},
      {ContactMethod::EventDriven, "event-driven"},
      {ContactMethod::TimeStepping, "time-stepping"}};
};

/// The links' joints: journal bearings (radial spring-dampers, paper Fig. 2) or ideal bilateral
/// constraints (with a rigid-contact method only).
enum class JointModel { JournalBearing, Ideal };
template <>
struct ChoiceNames<JointModel> {
  static constexpr ChoiceName<JointModel> table[] = {{JointModel::JournalBearing, "journal-bearing"},
                                                     {JointModel::Ideal, "ideal"}};
};

/// A compliant contact's normal law: Hunt-Crossley damping (proportional to the force) or a
/// linear damper.
enum class ContactLawModel { HuntCrossley, SpringDamper };
template <>
struct ChoiceNames<ContactLawModel> {
  static constexpr ChoiceName<ContactLawModel> table[] = {{ContactLawModel::HuntCrossley, "hunt-crossley"},
                                                          {ContactLawModel::SpringDamper, "spring-damper"}};
};

/// The running direction of a drive or a CVT, seen from the front: its sign (+1 counterclockwise,
/// -1 clockwise) turns every rotor.
enum class Rotation { Clockwise, Counterclockwise };
template <>
struct ChoiceNames<Rotation> {
  static constexpr ChoiceName<Rotation> table[] = {{Rotation::Clockwise, "clockwise"},
                                                   {Rotation::Counterclockwise, "counterclockwise"}};
};
inline double rotationSense(Rotation r) { return r == Rotation::Clockwise ? -1.0 : 1.0; }

/// The model of the drive: link by link, or rotors and spans (src/span/).
enum class Fidelity { Link, Span };
template <>
struct ChoiceNames<Fidelity> {
  static constexpr ChoiceName<Fidelity> table[] = {{Fidelity::Link, "link"}, {Fidelity::Span, "span"}};
};

}  // namespace chaindrive
