// The mutable side: inputs, per-evaluation kinematics, forces and contact lists, sized once
// from a Model so that evaluating the dynamics never allocates.
#pragma once

#include <vector>

#include "assembly/model.h"
#include "vec2.h"

namespace chaindrive {

/// Input values at one instant. Signs are those users see: the crankshaft speed is positive in
/// the running direction, a load torque is positive when it opposes the running direction.
struct InputValues {
  double crankSpeed = 0.0;         // [rad/s] of the driven sprocket
  double crankAcceleration = 0.0;  // [rad/s^2] (used by the acceleration-level contact methods)
  std::vector<double> loadTorque;  // [N m] per rotor (only free sprockets use it)
};

/// Source of inputs over time. Implementations must be deterministic and must not allocate.
class InputSignal {
 public:
  virtual ~InputSignal() = default;
  virtual void evaluate(double t, InputValues& v) const = 0;
};

/// Inputs held constant (co-simulation: the value set before a communication step).
class HeldInputs : public InputSignal {
 public:
  explicit HeldInputs(const Model& m) { values.loadTorque.assign(m.rotors.size(), 0.0); }
  void evaluate(double, InputValues& v) const override {
    v.crankSpeed = values.crankSpeed;
    v.crankAcceleration = 0.0;
    for (std::size_t i = 0; i < v.loadTorque.size() && i < values.loadTorque.size(); ++i) v.loadTorque[i] = values.loadTorque[i];
  }
  InputValues values;
};

/// Kinematics of one link, evaluated from the state.
struct LinkKin {
  Vec2 c;          // centre
  Vec2 v;          // centre velocity
  double w = 0.0;  // angular velocity
  Vec2 e;          // unit axis (rear pin -> front pin)
  Vec2 rear, front;    // pin positions
  Vec2 vRear, vFront;  // pin velocities
};

struct JointState {
  Vec2 force;               // on the front pin of link j (from link j+1)
  double tension = 0.0;     // [N] positive in tension
  double deformation = 0.0; // [m] radial displacement beyond the clearance
};

/// One closed (or nearly closed) contact with its kinematics: gap, normal and tangent, lever
/// arms, relative velocities. Its W-matrix columns follow from these (contact_kinematics.h).
struct ContactPoint {
  enum class Kind { RollerSprocket, PlateGuide } kind = Kind::RollerSprocket;
  int link = -1;          // chain link
  int end = 0;            // roller contacts: 0 rear pin, 1 front pin
  int element = -1;       // sprocket or guide index
  int face = -1;          // guide face
  int rotor = -1;         // rotor of the element, -1 for a fixed guide
  double gap = 0.0;       // [m] negative = penetration
  Vec2 normal, tangent;   // unit; the normal points from the element to the chain, tangent = perp(normal)
  Vec2 rLink;             // force application point relative to the link centre
  Vec2 rRotor;            // contact point relative to the rotor axis
  double vN = 0.0, vT = 0.0;  // relative velocity chain minus element
  double fN = 0.0, fT = 0.0;  // force on the chain along normal and tangent
};

struct Data {
  explicit Data(const Model& m);

  // what generalizedForces evaluates: the rigid-contact methods switch off the compliant contacts
  // (and, for ideal joints, the journal bearings) and treat them as constraints instead
  bool compliantContacts = true;
  bool jointForces = true;

  InputValues inputs;
  std::vector<LinkKin> links;                 // (links)
  std::vector<double> rotorAngle, rotorRate;  // (rotors) math sense
  std::vector<double> rotorCos, rotorSin;     // (rotors)
  std::vector<JointState> joints;             // (links) joint j: link j front pin - link j+1 rear pin
  std::vector<ContactPoint> contacts;         // capacity fixed at construction
  std::vector<PlacedFace> placedFaces;        // (most faces of a guide) a guide's faces at its angle
  std::vector<int> gapHints;                  // (rollers x sprockets) tooth gap found last: a search
                                              // guess only (results never depend on it)
  int nContacts = 0;
  std::vector<double> gen;                    // (nGen) generalized forces
  // tensioner
  double tensionerForce = 0.0, tensionerStroke = 0.0, tensionerRate = 0.0;
  // power terms
  double powerInput = 0.0, powerDissipated = 0.0;
  long long rhsEvaluations = 0;
};

}  // namespace chaindrive
