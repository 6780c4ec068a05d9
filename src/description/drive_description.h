// The drive description: one JSON schema for a timing drive, parsed and validated into plain
// SI data. Validation reports every error at once, each naming the field and the allowed range.
// The geometric checks that need an assembled layout (overlaps, closure of the chain) live in
// assembly.cpp and report in the same format.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "description/choices.h"
#include "description/hydraulic_tensioner.h"
#include "math/vec2.h"

namespace chaindrive {

/// Thrown when a drive description (or a parameter applied to it) is invalid. what() lists every
/// problem found, one per line, each starting with the field path.
class DescriptionError : public std::runtime_error {
 public:
  explicit DescriptionError(std::vector<std::string> problems);
  const std::vector<std::string>& problems() const { return problems_; }

 private:
  std::vector<std::string> problems_;
};

struct ToothProfileDesc {
  std::string form = "mean";           // ISO 606 tooth form: "min", "mean" or "max"
  std::optional<double> seatRadius;    // r_i [m], overrides the form
  std::optional<double> seatAngle;     // alpha [rad] (full angle), overrides the form
  std::optional<double> flankRadius;   // r_e [m], overrides the form
  std::optional<double> tipDiameter;   // d_a [m], overrides the form
};

struct SprocketDesc {
  std::string name;
  Vec2 center;                 // [m]
  int teeth = 0;
  ToothProfileDesc toothProfile;
  double inertia = 0.0;        // [kg m^2] sprocket and everything rigidly attached (camshaft)
  bool prescribed = false;     // driven by the crankshaft-speed input (true) or free
  bool loaded = false;         // free with a load torque (motion "free"); false: prescribed, or an idler
                               // (motion "idler": free, no load, so an FMU has no load input for it)
};

struct JointDesc {
  JointModel model = JointModel::JournalBearing;  // radial spring-damper (paper Fig. 2) or ideal (bilateral constraints)
  double stiffness = 0.0;                 // [N/m] radial, per joint (the link's longitudinal stiffness)
  double damping = 0.0;                   // [N s/m]
  double clearance = 0.0;                 // [m] radial clearance of the journal bearing
};

struct ChainDesc {
  double pitch = 0.0;          // [m]
  int numberOfLinks = 0;       // even: inner and outer links alternate
  double linkMass = 0.0;       // [kg] per link
  double linkInertia = 0.0;    // [kg m^2] per link, about its centre
  double rollerDiameter = 0.0; // [m]
  double plateHeight = 0.0;    // [m]
  JointDesc joint;
  std::vector<std::string> route;  // sprockets and guides in running order
};

struct GuideFeatureDesc {
  enum class Type { Arc, Line } type = Type::Arc;
  // arc
  Vec2 center;
  double radius = 0.0;
  double startAngle = 0.0;  // [rad] counterclockwise from startAngle to endAngle
  double endAngle = 0.0;
  bool convex = true;       // true: the chain runs outside the circle (guide material inside)
  // line
  Vec2 from, to;            // the chain runs on the left of from->to when leftSide, else right
  bool leftSide = true;
};

struct GuideDesc {
  std::string name;
  bool pivoting = false;
  Vec2 pivot;                    // [m] pivoting guides only
  double inertia = 0.0;          // [kg m^2] about the pivot
  double mass = 0.0;             // [kg] only for the weight moment (optional)
  Vec2 centerOfMass;             // [m] at the drawn pose
  double pivotDamping = 0.0;     // [N m s/rad] viscous pivot friction
  double angleMin = -0.2;        // [rad] admissible rotation from the drawn pose (closure search)
  double angleMax = 0.2;
  std::vector<GuideFeatureDesc> profile;  // the guide face, world coordinates at the drawn pose
};

struct TensionerDesc {
  bool present = false;
  std::string guide;          // the pivoting guide it pushes
  Vec2 housing;               // [m] fixed point of the plunger axis
  Vec2 direction;             // unit vector, plunger extension direction
  Vec2 contactPoint;          // [m] contact pad on the guide, world coordinates at the drawn pose
  double preload = 0.0;       // [N] force at the drawn (nominal) pose
  double stiffness = 0.0;     // [N/m]
  double damping = 0.0;       // [N s/m] when the plunger retracts (leak-down)
  double dampingExtension = 0.0;  // [N s/m] when the plunger extends (check valve open)
  TensionerKind kind = TensionerKind::SpringDamper;  // the damping fields apply to spring-damper only
  HydraulicTensionerDesc hydraulic;  // the device of kind hydraulic (its defaults otherwise)
};

struct ContactLawDesc {
  ContactLawModel model = ContactLawModel::HuntCrossley;
  double stiffness = 0.0;    // k [N/m^exponent]
  double exponent = 1.0;     // n: F = k delta^n (...)
  double dampingFactor = 0.0;  // hunt-crossley: F = k delta^n (1 + 1.5 alpha delta_dot) [s/m]
  double damping = 0.0;        // spring-damper: F = k delta^n + c delta_dot [N s/m]
  double friction = 0.0;     // Coulomb coefficient (kinetic)
  double restitution = 0.5;  // Newton restitution for the rigid contact methods
};

struct ContactDesc {
  ContactMethod method = ContactMethod::Compliant;  // a force law, or rigid contacts (event driven, time stepping)
  double frictionRegularization = 0.05;  // [m/s] velocity scale of the regularised Coulomb law
  ContactLawDesc rollerSprocket;
  ContactLawDesc plateGuide;
};

struct ClosureDesc {
  enum class Kind { Guide, Sprocket } kind = Kind::Guide;
  std::string element;   // guide (rotated) or sprocket (shifted) that closes the chain
  Vec2 direction;        // sprocket shift direction
  double rangeMin = 0.0, rangeMax = 0.0;  // [rad] or [m]
};

/// The span fidelity's dynamics beyond the statics' laws (docs/fidelities.md#calibrated-dynamics):
/// the tension guide's seat on its chain (span_model.h, GuideSeat) and the spans' damping. Off by
/// default: on the drives measured they put the span model's modes on the link model's without
/// bringing its cycle means nearer (docs/study/span_dynamics.md).
struct SpanModelDesc {
  enum class Source { Off, Identified, Given };
  Source guideSeat = Source::Off;  // off: the chain on the guide's face moves with it
  double guideSeatStiffness = 0.0;  // [N m/rad] when given
  Source damping = Source::Off;     // off: the joints' dampers in series
  double dampingScale = 1.0;        // when given: the spans' dampers over the joints' in series
};

struct MeasurementDesc {
  std::vector<std::string> tightSpan;  // two consecutive route elements; empty: none
  std::vector<std::string> slackSpan;
  int monitoredLink = 0;
};

/// The most sprockets and guides a drive may have: the contact search marks the elements near
/// each link as bits of one 32-bit word (two per sprocket, for the roller at either end; one
/// per guide).
constexpr int kMaxSprockets = 16, kMaxGuides = 32;

struct DriveDescription {
  std::string name;
  double rotationSense = -1.0;   // +1 counterclockwise, -1 clockwise (running direction in the drawing)
  Vec2 gravity{0.0, -9.81};      // [m/s^2] acting on the links
  ChainDesc chain;
  std::vector<SprocketDesc> sprockets;
  std::vector<GuideDesc> guides;
  TensionerDesc tensioner;
  ContactDesc contact;
  std::optional<ClosureDesc> closure;  // default: the tensioner's guide
  MeasurementDesc measurement;
  SpanModelDesc spanModel;
  std::string canonicalText;     // the description as parsed, in one canonical JSON form (a cache key's part)

  int sprocketIndex(std::string_view name) const;  // -1 if none
  int guideIndex(std::string_view name) const;     // -1 if none
};

/// Parses and validates a description. Throws DescriptionError listing every problem.
DriveDescription parseDriveDescription(std::string_view jsonText);
/// Reads a file; a missing or unreadable file is a DescriptionError naming the path.
DriveDescription loadDriveDescription(const std::string& path);
/// The default drive (paper Fig. 11), embedded in the library.
DriveDescription defaultDriveDescription();
/// Whether `desc` is the default drive's description (by its canonical text; the parameter
/// overrides applied to it do not make it another drive).
bool isDefaultDrive(const DriveDescription& desc);
std::string_view defaultDriveJson();

/// ISO 606 sprocket tooth-form values for z teeth and roller diameter d1 (all SI).
struct Iso606ToothForm {
  double seatRadius, seatAngle, flankRadius, tipDiameter;
};
Iso606ToothForm iso606ToothForm(int teeth, double pitch, double rollerDiameter, const std::string& form);

}  // namespace chaindrive
