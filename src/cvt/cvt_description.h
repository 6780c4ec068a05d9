// The description of a chain CVT (paper example 4.1): a rocker-pin chain clamped between the
// conical sheaves of a driving and a driven pulley. One JSON schema (chaindrive.cvt/1), parsed
// and validated as the timing drive's (description/): every problem at once, each naming the
// field and the allowed range.
#pragma once

#include <string>
#include <string_view>

#include "description/drive_description.h"

namespace chaindrive {

struct CvtDescription {
  std::string name;
  double rotationSense = 1.0;    // +1 counterclockwise, -1 clockwise
  Vec2 gravity{0.0, -9.81};      // [m/s^2] on the links
  // the chain
  double pitch = 0.0;            // [m]
  int numberOfLinks = 0;
  double linkMass = 0.0;         // [kg]
  double linkInertia = 0.0;      // [kg m^2] about the link's centre
  JointDesc joint;               // the two rocker pins of a joint rolling on each other, as a stiff spring-damper
  double pinAxialStiffness = 0.0;  // [N/m] a pin with its two end contacts, clamped between the sheaves
  double pinAxialDamping = 0.0;    // [N s/m]
  // the pulleys: the driving one at the origin, the driven one at (centerDistance, 0)
  double centerDistance = 0.0;   // [m]
  double wedgeHalfAngle = 0.0;   // [rad] of the sheaves' cones
  double drivenInertia = 0.0;    // [kg m^2] the driven pulley and what turns with it
  double ratio = 1.0;            // the driven pulley's running radius over the driving one's
  double ratioMin = 1.0, ratioMax = 1.0;  // the range a ratio input may move the sheaves over (default: the ratio)
  double clampingForce = 0.0;    // [N] the driven pulley's axial force at the assembled pose
  // the pin-sheave contact
  double friction = 0.0;         // Coulomb coefficient (traction fluid)
  double frictionRegularization = 0.02;  // [m/s] velocity scale of the regularised Coulomb law
  double restitution = 0.0;      // Newton's coefficient of a pin's impact at pulley entry (rigid pins)
};

/// Parses and validates a CVT description. Throws DescriptionError listing every problem.
CvtDescription parseCvtDescription(std::string_view jsonText);
/// Reads a file; a missing or unreadable file is a DescriptionError naming the path.
CvtDescription loadCvtDescription(const std::string& path);
/// The default CVT (src/drives/default_cvt.json), embedded in the library.
CvtDescription defaultCvtDescription();
std::string_view defaultCvtJson();

}  // namespace chaindrive
