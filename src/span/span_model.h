// The span model: the cheap fidelity of a drive, assembled from the same description (through
// the link model's assembled path). The rotors are those of the link model (same indices, same
// state layout of angles and rates); the chain is a set of free spans, one between each pair of
// consecutive sprockets of the route (guides in between belong to the span), each a
// longitudinal spring-damper whose stiffness and damping are the joints' in series and whose
// mass is lumped at its end sprockets, together with the links wrapped on them.
//
// Kinematics of a span from sprocket A (where the chain leaves) to sprocket B (where it
// arrives), with the tension guide's angle psi:
//   stretch  e = l(psi) - l(psi0) - (s_A(theta_A) - s_B(theta_B))
//   s(theta) = chain passed through the sprocket's tangent point when it has turned theta in the
//              running sense: p round(u) + R sin(theta_rel), u = (theta + phase) / (2 pi / z),
//              theta_rel = (u - round(u)) 2 pi / z, so ds/dtheta = R cos(theta_rel): the polygonal
//              action (effective radius R cos(theta_rel) within one pitch; chain speed ratio
//              cos(pi / z)), and exactly one pitch per tooth
//   l(psi)   = path length between fixed reference points on A and B (the tangent points at the
//              assembled pose), from a table over the guide's angle range; the chain runs over
//              a guide's face between tangent points, and where a tangent point would lie
//              beyond the face's end it bends over that end (the pitch line's height about it).
// Forces: spring tension T = f(e) + c e', f the span's engagement law identified from the link
// model's statics (span_calibration.h; without one f = k e); a span is bilateral: it stays valid
// while in tension; over a guide of wrap angle beta the tension above the centrifugal part rho v^2 grows by the
// capstan factor exp(mu beta) in the running direction; the guide feels the normal and friction
// loads of (T - rho v^2); a sprocket feels (T_leaving - T_arriving) R cos(theta_rel).
#pragma once

#include <string>
#include <vector>

#include "assembly/model.h"

namespace chaindrive::span {

/// One end of a span on a sprocket.
struct SpanEnd {
  int rotor = -1;           // the sprocket's rotor
  double radius = 0.0;      // pitch radius R [m]
  double toothAngle = 0.0;  // 2 pi / z [rad]
  double pitch = 0.0;       // [m]
  double phase = 0.0;       // running-sense angle from the tangent point to the nearest roller at the start,
                            // in [-toothAngle / 2, toothAngle / 2)
  double passedAtPhase = 0.0;  // R sin(phase): s(theta) counts from the start
};

/// Geometry of a span that holds a pivoting guide, at equidistant guide angles: the span's
/// reference length and its slope, and the torque on the guide per tension entering and leaving
/// its wrap (normal and friction loads together).
struct GuideTable {
  int rotor = -1;
  double angle0 = 0.0, dAngle = 0.0;  // [rad] first node and node spacing (guide rotation from the drawn pose)
  std::vector<double> length, slope;  // l [m], dl/dpsi [m/rad]
  std::vector<double> torqueIn, torqueOut;  // [m] torque = torqueIn T'_in + torqueOut T'_out
  double angleMin() const { return angle0; }
  double angleMax() const { return angle0 + dAngle * (static_cast<double>(length.size()) - 1.0); }
};

/// A pivoting guide's seat on its chain: the link model's chain gives under its guide (the links
/// beside the face bend off their line, the plates press into it), so its guide is softer with
/// the sprockets held than the spans alone make it. A spring in series between the guide and the
/// spans makes up the difference: the spans' path follows the face angle chi where the spans'
/// torque on the face, the seat passes to the guide (angle psi):
///   torque_face(chi) = torque0 + stiffness (chi - psi),
/// solved for chi at every evaluation (the seat holds no mass: the chain on the face moves with
/// the guide; the links that bend are few and light). At the reference pose (the spans' torque
/// torque0) chi = psi. Identified from the link model's statics (seat_calibration.h); stiffness
/// 0: no seat, chi = psi.
struct GuideSeat {
  double stiffness = 0.0;      // [N m/rad]
  double torque0 = 0.0;        // [N m] the spans' torque on the guide at the reference pose
  double spanStiffness = 0.0;  // [N m/rad] the spans' against the face's turn there (the solve's slope)
  bool present() const { return stiffness > 0.0; }
};

/// A span's tension over its stretch where the link model's rollers seat in the tooth gaps and
/// its links settle on the guides: soft at small tensions, stiffer once the rollers sit on the
/// flanks. Nodes (stretch, tension) identified from the link model's statics under several loads
/// (span_calibration.h), linear between them and beyond the ends with the end segments' slopes.
/// The stretch counts from the nominal path (the law holds the seating slack). Empty: T = k e.
struct EngagementLaw {
  std::vector<double> stretch, tension;  // [m], [N] nodes, both increasing
  std::vector<double> energy;            // [J] integral of the tension from the first node
  bool empty() const { return stretch.empty(); }
  double tensionAt(double e, double* slope = nullptr) const;  // [N]; its slope dT/de [N/m] into *slope
  double energyAt(double e) const;       // [J] integral of the tension from the first node to e
};

struct Span {
  std::string name;           // "<from>-><to>"
  SpanEnd from, to;           // A: the chain leaves it into the span; B: the chain arrives on it
  double links = 0.0;         // links the span holds at the assembled pose (path length / pitch)
  double stiffness = 0.0;     // [N/m] joint stiffness / links
  double damping = 0.0;       // [N s/m] joint damping / links, times the model's dampingScale
  double jointDamping = 0.0;  // [N s/m] joint damping / links
  double mass = 0.0;          // [kg] chain in the span
  double length0 = 0.0;       // [m] reference length at the assembled pose
  EngagementLaw engagement;   // identified from the link model's statics (empty: T = stiffness e)
  std::vector<double> parts;  // [m] lengths of the free parts between guides (guides + 1 parts)
  double partsLength = 0.0;   // [m] their sum
  std::vector<double> wraps;  // [rad] wrap angles of the guides in the span, running order
  int table = -1;             // guide table of its pivoting guide, -1: the span holds none
  int tableGuide = -1;        // index of that guide among the span's guides
  double firstModeFrequency = 0.0;  // [Hz] first longitudinal mode of the span with fixed ends
};

/// Where a point of the assembled path lies in the span model: on a sprocket's wrap (between the
/// span arriving there and the span leaving), on a guide's wrap, or on a free part of a span.
struct PathPart {
  enum class Kind { Sprocket, Guide, Free } kind = Kind::Free;
  int span = -1;      // the span leaving the sprocket / holding the guide or free part
  int part = 0;       // free part index; guides: the part before the guide
  int spanIn = -1;    // sprockets: the span arriving
};

struct SpanModel {
  const Model* links = nullptr;   // the link model it was assembled from (rotors, tensioner, path)
  std::vector<Span> spans;        // in route order, the first leaving the route's first sprocket
  std::vector<GuideTable> tables;
  std::vector<GuideSeat> seats;   // (tables) each pivoting guide's seat on its chain
  std::vector<double> rotorInertia;  // [kg m^2] rotor inertia with the chain lumped on it
  std::vector<int> sprocketSpanIn, sprocketSpanOut;  // (rotors) spans arriving at / leaving each sprocket
  std::vector<PathPart> pathParts;   // (segments of the link model's path)
  double chainDensity = 0.0;      // [kg/m] link mass / pitch
  double dampingScale = 1.0;      // the spans' dampers over the joints' in series (setDampingScale)
  double guideFriction = 0.0, frictionRegularization = 0.05;
  struct Probe { bool present = false; int span = -1, part = 0; } tightProbe, slackProbe;
  std::vector<Probe> spanProbes;  // (route elements) the free part leaving each
  std::vector<double> monitoredStart;  // (links) path position of each link's centre at the start [m]
  std::vector<std::string> notes;

  // state layout: the link model's rotor part (angle [, rate] per rotor) then input work and
  // dissipated energy, the chamber's oil content and the step means' accumulators (model.h)
  int nStates = 0;
  std::vector<int> stateAngle, stateRate;  // (rotors); rate -1 when prescribed
  int stateInputWork = -1, stateDissipated = -1;
  int stateChamberOil = -1;  // a hydraulic tensioner's chamber: its oil content [m3] (-1: none)
  ImpulseStates chainImpulse;
};

/// Assembles the span model of an assembled link model (which must outlive it), with its spans'
/// engagement laws calibrated from the link model's statics (span/calibration_cache.h) unless
/// `calibrate` is false (then T = k e). Throws
/// DescriptionError naming the field when the drive has no span model (fewer than two sprockets
/// in the route, a span holding more than one pivoting guide).
SpanModel assembleSpanModel(const Model& m, bool calibrate = true);

/// Sets the spans' dampers to `scale` times the joints' in series (run/span_damping.h fits it
/// to the link model's camshafts' mode).
void setDampingScale(SpanModel& sm, double scale);

/// s(theta) and ds/dtheta of a span end (see the header comment); theta in the running sense.
double chainPassed(const SpanEnd& e, double theta, double& effectiveRadius);

}  // namespace chaindrive::span
