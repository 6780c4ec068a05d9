// The mutable side: inputs, per-evaluation kinematics, forces and contact lists, sized once
// from a Model so that evaluating the dynamics never allocates.
#pragma once

#include <cstdint>
#include <vector>

#include "assembly/model.h"
#include "dynamics/hydraulic_tensioner.h"
#include "math/vec2.h"
#include "threads.h"

namespace chaindrive {

/// Input values at one instant. Signs are those users see: the crankshaft speed is positive in
/// the running direction, a load torque is positive when it opposes the running direction.
/// What a hydraulic tensioner's chamber needs beyond the plunger's motion: its gauge pressure
/// and volume ratio (of its oil content, the state, at the plunger's stroke: fillChamber in
/// dynamics/body_forces.h), the supply's gauge pressure (an input) and the oil's viscosity at its
/// temperature (constant over a run: the work area computes it once). Unused by the spring-damper
/// law. Held (statics): the pressure stays as set, whatever the content.
struct ChamberState {
  double pressure = 0.0;        // [Pa]
  double ratio = 1.0;           // the chamber's volume over its oil content (assembly/chamber_oil.h)
  double supplyPressure = 0.0;  // [Pa]
  double viscosity = 0.0;       // [Pa s]
  bool held = false;
};

struct InputValues {
  double crankSpeed = 0.0;         // [rad/s] of the driven sprocket
  double supplyPressure = 0.0;     // [Pa] gauge, of the oil feeding a hydraulic tensioner
  double crankAcceleration = 0.0;  // [rad/s^2] (used by the acceleration-level contact methods)
  std::vector<double> loadTorque;  // [N m] per rotor: a free sprocket's load, against its running
                                   // direction; a pivoting guide's applied torque, in its output sense
                                   // (model.h: rotorOutputSign; a study's pulse on the guide)
  double ratio = 0.0;              // a CVT's transmission ratio (its sheaves follow it; 0: the assembled one)
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
  explicit HeldInputs(const Model& m) {
    values.loadTorque.assign(m.rotors.size(), 0.0);
    values.supplyPressure = m.tensioner.hydraulic.supplyPressure;
  }
  void evaluate(double, InputValues& v) const override {
    v.crankSpeed = values.crankSpeed;
    v.supplyPressure = values.supplyPressure;
    v.crankAcceleration = 0.0;
    for (std::size_t i = 0; i < v.loadTorque.size() && i < values.loadTorque.size(); ++i) v.loadTorque[i] = values.loadTorque[i];
    v.ratio = values.ratio;
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

/// The kinematics of all links, one array per quantity (structure of arrays): the per-link loops
/// of the dynamics run over contiguous memory, several links per vector instruction. Every array
/// has kPadding entries beyond the links: room for a loop's last, partly filled vector and for
/// the first link's rear pin copied behind the last link (the joints' neighbour, shifted by one).
struct LinkArrays {
  static constexpr int kPadding = 8;
  explicit LinkArrays(int links);
  int size() const { return links; }
  /// One link's kinematics gathered from the arrays (for the paths that take one link at a time).
  LinkKin operator[](int i) const {
    LinkKin k;
    k.c = Vec2{cx[i], cy[i]};
    k.v = Vec2{vx[i], vy[i]};
    k.w = w[i];
    k.e = Vec2{ex[i], ey[i]};
    k.rear = Vec2{rearX[i], rearY[i]};
    k.front = Vec2{frontX[i], frontY[i]};
    k.vRear = Vec2{vRearX[i], vRearY[i]};
    k.vFront = Vec2{vFrontX[i], vFrontY[i]};
    return k;
  }

  int links = 0;
  std::vector<double> cx, cy, vx, vy, w;  // centre, its velocity, angular velocity
  std::vector<double> ex, ey;             // unit axis (rear pin -> front pin)
  std::vector<double> rearX, rearY, frontX, frontY, vRearX, vRearY, vFrontX, vFrontY;  // pins
};

/// The joints' forces and measures, one array per quantity. Joint j joins link j's front pin and
/// link j+1's rear pin (the last one link 0's). The forces are stored with the last joint's force
/// also in front of the first (forceX()[-1]): a link's two joints, j - 1 and j, are neighbours in
/// memory for every link, also for link 0 (the per-link loops read them as two shifted vectors).
struct JointArrays {
  explicit JointArrays(int joints);
  Vec2 force(int j) const { return Vec2{fx_[j + 1], fy_[j + 1]}; }  // on link j's front pin
  void setForce(int j, Vec2 f);
  double* forceX() { return fx_.data() + 1; }
  double* forceY() { return fy_.data() + 1; }
  const double* forceX() const { return fx_.data() + 1; }
  const double* forceY() const { return fy_.data() + 1; }

  std::vector<double> tension;      // [N] positive in tension (measureJoints)
  std::vector<double> deformation;  // [m] radial displacement beyond the clearance (measureJoints)

 private:
  int joints_ = 0;
  std::vector<double> fx_, fy_;
};

/// What the last query of each roller against each sprocket found, to make the next one cheap
/// (contact_lanes.cpp); the results never depend on it. One array per quantity, sprocket by
/// sprocket over the pins (padded as the link arrays).
struct RollerHints {
  RollerHints(int sprockets, int pins);
  int index(int sprocket, int pin) const { return sprocket * stride + pin; }
  /// Hint h's tooth gap (-1: none) and, with it, that gap's axis and its sector's tooth axes.
  void setGap(int h, const SprocketModel& s, int gapIndex);
  int stride = 0;
  std::vector<int> gap;              // the tooth gap of its sector (the search's first guess; -1: none)
  std::vector<double> gapX, gapY;    // that gap's axis (sprocket frame; NaN: none) ...
  std::vector<double> fromX, fromY, toX, toY;  // ... and the tooth axes before and after it
  std::vector<double> bodyX, bodyY;  // its centre in the sprocket's frame ...
  std::vector<double> clearance;     // ... where its gap was this [m] and it touched nothing (< 0: none)
};

/// The contact search's windows, carried from one evaluation to the next: at the last full scan,
/// which blocks of kBlock rollers (pins) lay within a sprocket's reach grown by kBand, which blocks
/// of links had their centre within a guide's bounding circle grown by kBand, and where every
/// link (centre and axis) and guide circle was. While nothing has moved by more than kBand since
/// (a pin, or a link centre and its guide's circle together), no roller or link outside its
/// element's window can be within the element's reach: the search visits the windows only, and
/// scans again when something has moved further (contact_lanes.cpp). Its results do not depend
/// on the windows.
struct SearchWindows {
  static constexpr int kBlock = 4;         // rollers or links per block
  static constexpr double kBand = 2e-3;    // [m]
  SearchWindows(int links, int sprockets, int guides);
  int blocks = 0, words = 0;               // blocks over the links, 64-bit words of a window
  std::vector<double> centerX, centerY, axisX, axisY;  // (links + padding) at the last scan
  std::vector<double> boundX, boundY;      // (guides) the guides' circles at the last scan
  std::vector<std::uint64_t> windows;      // (sprockets, then guides) x words: bit b set: block b in it
  double margin = 0.0;                     // the search's margin at the last scan
  bool valid = false;                      // (false: no scan yet)
  const std::uint64_t* sprocketWindow(int s) const { return &windows[static_cast<std::size_t>(s) * words]; }
  const std::uint64_t* guideWindow(int sprockets, int g) const {
    return &windows[static_cast<std::size_t>(sprockets + g) * words];
  }
};

/// One closed (or nearly closed) contact with its kinematics: gap, normal and tangent, lever
/// arms, relative velocities. Its W-matrix columns follow from these (contact_kinematics.h).
struct ContactPoint {
  enum class Kind { RollerSprocket, PlateGuide, PinSheave } kind = Kind::RollerSprocket;
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
  double fNFriction = 0.0;    // pin-sheave: the friction along the normal (radial; fN is the wedge's
                              // normal force, fT the circumferential friction)
};

/// The force of a contact on the chain (a pin-sheave contact's radial friction included).
inline Vec2 contactForce(const ContactPoint& c) { return (c.fN + c.fNFriction) * c.normal + c.fT * c.tangent; }

/// A range of links [first, last).
struct LinkRange {
  int first = 0, last = 0;
};

/// The largest squared distances by which a link's centre and its axis moved since the search
/// windows' last scan, and whether one was NaN.
struct LinkMoves {
  double center2 = 0.0, axis2 = 0.0;
  bool nan = false;
};

/// A plate-guide contact's share of its guide's rotor: what addContactGen subtracts from the
/// rotor's generalized force, and the contact's dissipated power (added in the serial order).
struct PlateShare {
  int link = 0;
  double moment = 0.0, power = 0.0;
};

/// One thread's share of an evaluation on several threads (solver.threads; dynamics/threaded.h):
/// its links (a contiguous part of the chain, the parts as equal as whole vectors of 4 allow), and
/// what it found for the calling thread to combine. Aligned to a cache line: threads write their
/// own only.
struct alignas(64) ThreadPart {
  std::vector<LinkRange> ranges;    // its links, in increasing order (one range, or none)
  std::vector<std::uint64_t> blocks;  // (window words) bit b: block b of the search's windows is its
  LinkMoves moves;                            // of its links
  double jointOpening2 = 0.0;                 // the largest squared joint opening (NaN: some was)
  double deepestGap = 0.0;
  long long rollerQueries = 0, rollerQueriesSkipped = 0;
  std::vector<PlateShare> plates;  // (guide faces x links) by face: its plate contacts, in link order
  std::vector<int> plateCount;     // (guide faces)
};

/// The work of an evaluation on several threads: the pool, each thread's part, and the per-joint
/// and per-roller values the threads store and the calling thread sums in the serial order (so
/// that every number of threads gives the bits of one).
struct ThreadedWork {
  StagePool* pool = nullptr;        // (null: one thread, the serial code)
  std::vector<ThreadPart> parts;    // (threads)
  std::vector<double> jointPower;   // (links + padding)
  std::vector<double> pinTorque, pinPower;  // (sprockets x pins, as RollerHints) this evaluation's
};

struct Data {
  explicit Data(const Model& m);
  /// Evaluations from now on on the pool's threads (null or one thread: the serial code).
  void useThreads(const Model& m, StagePool* pool);

  // what generalizedForces evaluates: the rigid-contact methods switch off the compliant contacts
  // (and, for ideal joints, the journal bearings) and treat them as constraints instead
  bool compliantContacts = true;
  bool jointForces = true;
  // a CVT's pins: their friction as a force law; off, only the normal force of the pins' axial
  // compliance (the time-stepping method makes the friction a constraint)
  bool pinFriction = true;
  // whether an evaluation with the compliant contacts lists them (contacts, nContacts); off, it
  // only sums their forces and keeps the deepest penetration (deepestGap): the evaluations of
  // schemes that read nothing but the derivatives (OdeSystem::setDerivativesOnly)
  bool listContacts = true;
  bool listsContacts(bool forces) const { return !forces || listContacts; }  // (forces: compliant)

  InputValues inputs;
  LinkArrays links;                           // (links)
  std::vector<double> rotorAngle, rotorRate;  // (rotors) math sense
  std::vector<double> rotorCos, rotorSin;     // (rotors)
  JointArrays joints;                         // (links) joint j: link j front pin - link j+1 rear pin
  double jointOpening2 = 0.0;                 // [m^2] the largest squared pin separation of the joints'
                                              // last evaluation (the health check's blow-up test)
  int vectorLanes = 2;                        // lanes of the per-link loops: 4 (AVX2) where the CPU
                                              // has them, else 2 (SSE2); the same bits either way
  std::vector<ContactPoint> contacts;         // capacity fixed at construction
  std::vector<PlacedFace> placedFaces;        // (guide faces, guide by guide) placed at their guide's angle
  std::vector<double> guideBoundX, guideBoundY, guideReach2;  // (guides) the bounding circles of the
                                              // contact search: centre at the guide's angle, (radius + reach)^2
  SearchWindows windows;                      // the contact search's (results never depend on them)
  std::vector<double> dampingWork;            // work area of jointDampingLoop (link_loops.h)
  std::vector<double> contactDamping;         // (3 links) work area: the compliant contacts' damping rates
                                              // per link coordinate [1/s] (iteration_matrix.h: linkDampedKicks)
  RollerHints rollerHints;                    // what the last queries found: search guesses and bounds
                                              // only (results never depend on them)
  long long rollerQueries = 0, rollerQueriesSkipped = 0;  // near rollers, and those the bound cleared
  int nContacts = 0;                          // listed in contacts
  double deepestGap = 0.0;                    // [m] of the last evaluation's contacts, listed or not
                                              // (>= 0 without a penetration)
  std::vector<double> gen;                    // (nGen) generalized forces, laid out as the
                                              // generalized coordinates (model.h)
  std::vector<double> rotorChainTorque;       // (rotors) [N m] the contacts' part of their generalized
                                              // forces, math sense: the step means' integrand
  // a CVT's sheaves at the ratio input (dynamics/pin_sheave.h): each pulley's free and running radius
  std::vector<double> pulleyFreeRadius, pulleyRunningRadius;  // (pulleys) [m]
  // tensioner; a hydraulic one's chamber: its state and viscosity in, its rate and flows out
  double tensionerForce = 0.0, tensionerStroke = 0.0, tensionerRate = 0.0;
  ChamberState chamber;
  double chamberOilRate = 0.0;        // [m3/s] of the chamber's state, its oil content
  double chamberPressure = 0.0;       // [Pa] gauge, the chamber's (at least the vapour's)
  HydraulicFlows tensionerFlows;      // [m3/s]
  // power terms
  double powerInput = 0.0, powerDissipated = 0.0;
  long long rhsEvaluations = 0;
  ThreadedWork threads;
};

}  // namespace chaindrive
