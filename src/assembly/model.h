// The assembled, immutable model of a drive (built once from a DriveDescription by assemble())
// and the layout of the state vector. Everything that changes while stepping lives in Data
// (data.h). Naming: link quantities are per chain link, rotor quantities per rotating body
// (sprockets and pivoting guides); the generalized coordinates are the 3 per link (x, y, gamma)
// followed by one angle per rotor.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "assembly/chain_path.h"
#include "assembly/chamber_oil.h"
#include "description/drive_description.h"
#include "assembly/geometry.h"
#include "math/vec2.h"

namespace chaindrive {

struct ChainModel {
  int links = 0;             // number of links (= joints = rollers)
  double pitch = 0.0;        // [m]
  double mass = 0.0;         // [kg] per link
  double inertia = 0.0;      // [kg m^2] per link
  double rollerRadius = 0.0; // [m]
  double depthScale = 0.0;   // [m] a contact deeper than HealthLimits::tunnellingDepth times this has
                             // tunnelled: the roller radius; a CVT's rocker pins: a quarter pitch
  double plateHalfHeight = 0.0;
  double jointStiffness = 0.0, jointDamping = 0.0, jointClearance = 0.0;
};

/// A rotating rigid body: a sprocket (prescribed or free) or a pivoting guide; on a CVT a pulley.
struct RotorModel {
  std::string name;
  bool isSprocket = true;    // a wheel the chain wraps, driven or loaded (sprocket or pulley); false: a guide
  int element = -1;          // index into Model::sprockets, Model::guides or Model::pulleys
  Vec2 axis;                 // [m]
  double inertia = 0.0;      // [kg m^2]
  bool prescribed = false;   // angle follows the crankshaft-speed input
  int stateAngle = -1;       // index in the state vector
  int stateRate = -1;        // index in the state vector; -1 when prescribed
  double initialAngle = 0.0; // [rad] at the assembled pose (math sense)
};

struct SprocketModel {
  std::string name;
  int rotor = -1;
  Vec2 center;
  ToothGap gap;
  double reach2 = 0.0;        // (tip radius + roller radius)^2: rollers beyond cannot touch
  std::vector<Vec2> gapDirs;  // (cos, sin) of k * 2 pi / z, k = 0..z-1
  std::vector<Vec2> toothDirs;  // (cos, sin) of (k - 1/2) 2 pi / z: the tooth axis before gap k
};

struct GuideModel {
  std::string name;
  int rotor = -1;             // -1: fixed
  Vec2 pivot;                 // rotation axis (fixed guides: origin)
  std::vector<GuideFace> faces;
  Vec2 boundCenter;           // bounding circle of the faces (drawn pose)
  double boundRadius = 0.0;
  double mass = 0.0;
  Vec2 centerOfMass;          // drawn pose
  double pivotDamping = 0.0;
};

/// A CVT's pulley (cvt/): the chain's rocker pins clamped between its two conical sheaves, whose
/// axial distance the transmission ratio sets (RatioTable), so a pin's axial compression follows
/// from its radius alone.
struct PulleyModel {
  std::string name;
  int rotor = -1;
  Vec2 center;
  double runningRadius = 0.0;  // [m] the pins' circle at the assembled pose
  double freeRadius = 0.0;     // [m] where the sheaves' gap equals the pin's length: a pin inside it
                               // is compressed, one outside it is free
};

/// A CVT's sheave positions over its transmission ratio (cvt/cvt_assembly.h): at the ratios
/// lo + k step, each pulley's running and free radius (the sheaves placed so that the chain closes
/// at that ratio, pre-tensioned by the clamping force). Empty: the ratio stays the assembled one,
/// lo.
struct RatioTable {
  double lo = 0.0, step = 0.0;
  std::vector<double> running[2], free[2];  // (points) [m] driving, driven
  bool empty() const { return running[0].empty(); }
  double hi() const { return empty() ? lo : lo + step * static_cast<double>(running[0].size() - 1); }
  /// The radii at ratio i (linear between the points; i within [lo, hi]).
  void at(double i, double running[2], double free[2]) const;
};

/// The rocker pins between the sheaves (dynamics/pin_sheave.h): each pin a bolt with linear axial
/// stiffness pressed between two cones of wedge half-angle beta.
struct PinSheaveLaw {
  double tanWedge = 0.0, cosWedge = 1.0;  // tan and cos of beta
  double axialStiffness = 0.0;            // [N/m] the pin with its end contacts
  double axialDamping = 0.0;              // [N s/m]
  double friction = 0.0;                  // Coulomb coefficient on each sheave face
  double restitution = 0.0;               // rigid pins: Newton's coefficient at pulley entry
};

struct TensionerModel {
  bool present = false;
  int rotor = -1;
  Vec2 housing, direction, pad;  // pad: contact point on the guide at the drawn pose
  double preload = 0.0, stiffness = 0.0, dampingRetract = 0.0, dampingExtend = 0.0;
  double nominalStroke = 0.0;    // dot(pad - housing, direction) at the drawn pose
  TensionerKind kind = TensionerKind::SpringDamper;  // spring-damper: the damping rates; hydraulic: the device
  HydraulicTensionerDesc hydraulic;                  // (the preload and stiffness are its plunger spring)
  ChamberOilLaw chamberOil;                          // (hydraulic) the chamber's pressure over its content
  bool hydraulicChamber() const { return present && kind == TensionerKind::Hydraulic; }
};

struct ContactLaw {
  bool huntCrossley = true;
  double stiffness = 0.0, exponent = 1.0, dampingFactor = 0.0, damping = 0.0, friction = 0.0, restitution = 0.5;
};

/// A fixed measuring point on a span: the force there is interpolated between the two joints
/// that bracket it.
struct SpanProbe {
  bool present = false;
  Vec2 point, direction;
};

/// Nominal (rigid, polygonal) motion of one pin at the assembled pose.
struct PinNominal {
  Vec2 position;
  enum class On { Sprocket, Guide, Span } on = On::Span;  // (Sprocket: a wheel, also a CVT's pulley)
  int rotor = -1;     // sprocket rotor (On::Sprocket)
  Vec2 center;        // arc centre (Sprocket/Guide)
  double radius = 0;  // arc radius (Guide)
  Vec2 tangent;       // running direction
};

struct AssemblyReport {
  std::string closureElement;
  double closureValue = 0.0;       // guide rotation [rad] or sprocket shift [m]
  double closureResidual = 0.0;    // [m] gap of the closing joint
  double maxJointGap = 0.0;        // [m] over all joints at the assembled pose
  double pathLength = 0.0;         // [m]
  std::vector<std::string> notes;
};

/// The accumulators behind the step-mean chain torques: the chain's angular impulse on each rotor
/// [N m s] (math sense) and the time it accumulated over [s], at the end of a state (link and span
/// models alike; a saved state of the layout before them is a prefix). Zeroed at every FMU
/// communication step, so that impulse / time is the torque averaged over the step: what a
/// co-simulation coupling passes on without sampling the roller impacts (14-20 us) at its step.
struct ImpulseStates {
  int first = -1;  // rotor r's impulse at first + r
  int time = -1;
};

/// The accumulators' derivatives: the chain torques (math sense) and the time's rate, 1.
inline void accumulateImpulses(const ImpulseStates& s, const std::vector<double>& chainTorque, double* ydot) {
  std::copy(chainTorque.begin(), chainTorque.end(), ydot + s.first);
  ydot[s.time] = 1.0;
}

/// Their scales in an adaptive method's error norm: so wide that they never steer its steps
/// (nothing depends on them; the impacts in the torques would only shorten the steps).
inline void impulseToleranceScales(const ImpulseStates& s, int rotors, double* scale) {
  std::fill_n(scale + s.first, rotors, 1e9);
  scale[s.time] = 1e9;
}

/// Appends the accumulators for `rotors` rotors at state index `next` (advanced past them).
inline ImpulseStates layOutImpulseStates(int& next, int rotors) {
  ImpulseStates s;
  s.first = next;
  next += rotors;
  s.time = next++;
  return s;
}

struct Model {
  std::string name;
  double sense = -1.0;         // running direction: +1 counterclockwise, -1 clockwise
  Vec2 gravity;
  ChainModel chain;
  std::vector<SprocketModel> sprockets;
  std::vector<GuideModel> guides;
  std::vector<RotorModel> rotors;
  TensionerModel tensioner;
  ContactLaw rollerSprocket, plateGuide;
  std::vector<PulleyModel> pulleys;  // a CVT's (then no sprockets, guides or tensioner)
  PinSheaveLaw pinSheave;
  RatioTable ratioTable;
  double frictionRegularization = 0.05;
  int drivenRotor = -1;        // the rotor with prescribed motion, -1 if none
  std::vector<double> rotorOutputSign;  // (rotors) sprockets: running sense; guides: towards the chain
  std::vector<SpanProbe> spanProbes;   // (route elements) the span leaving each, at the middle of its free part
  SpanProbe tightSpan, slackSpan;      // the measured spans' probes (description.measurement)
  int monitoredLink = 0;

  // State layout: the links' states component by component, one array over the links each
  // (x of every link, then y, gamma, vx, vy, omega), so that the per-link loops of the solver run
  // over contiguous memory, several links per vector instruction; then per rotor its angle [,
  // rate]; then the two energy accumulators (input work, dissipated energy); then, with a
  // hydraulic tensioner, its chamber's oil content [m3] (assembly/chamber_oil.h); last the step
  // means' accumulators (ImpulseStates). The generalized
  // coordinates (and forces) are laid out alike: x, y, gamma of every link, then one per rotor,
  // so the link positions of a state are its first 3 links entries in generalized order.
  enum LinkComponent { kX = 0, kY = 1, kGamma = 2, kVx = 3, kVy = 4, kOmega = 5 };
  int nStates = 0;
  int nGen = 0;                // generalized force entries: 3 per link + 1 per rotor
  int stateInputWork = -1, stateDissipated = -1;
  int stateChamberOil = -1;  // -1: no hydraulic tensioner
  ImpulseStates chainImpulse;
  int linkState(int link, int component) const { return component * chain.links + link; }
  int linkGen(int link, int component) const { return component * chain.links + link; }
  int rotorGen(int rotor) const { return 3 * chain.links + rotor; }

  // assembled nominal pose
  ChainPath path;
  std::vector<PinNominal> pins;  // pin j is link j's rear pin and link j-1's front pin
  AssemblyReport assembly;
  DriveDescription description;  // as given (after parameter overrides)

  int rotorIndex(const std::string& name) const;  // -1 if none
};

/// The largest deviation of a joint of the pins' closed polygon from `chord` [m].
double largestChordError(const std::vector<PinNominal>& pins, double chord);

/// Lays out the state vector (the layout above) for the model's links and rotors.
void layOutState(Model& m);

/// Builds the model: tooth and guide geometry, the chain path, the closure solve, the rigid
/// assembled pose. Throws DescriptionError for geometric problems (naming the field).
Model assemble(const DriveDescription& desc);

}  // namespace chaindrive
