// Contact detection and kinematics, in one place for every contact method: gaps, normal and
// tangential relative velocities, and the columns of the contact Jacobians W_N, W_T of the
// paper's eq. (1) (generalized coordinates: link x, y, gamma and the rotor angle).
#pragma once

#include <string>

#include "dynamics/data.h"
#include "failure.h"
#include "simd.h"
#include "assembly/model.h"

namespace chaindrive {

/// The kinematics of link `link` in state y.
LinkKin linkKinematics(const Model& m, const double* y, int link);

/// Fills d.links, d.rotorAngle/Rate/Cos/Sin from the state and the inputs (driven rotor rate).
void evaluateKinematics(const Model& m, Data& d, const double* y);
/// Its rotors' part (angles, their sines and cosines, rates).
void rotorKinematics(const Model& m, Data& d, const double* y);

/// Roller of link `link` at end (0 rear, 1 front) against a sprocket turned to `angle` (with
/// cos/sin given) at angular velocity `rate`. True (and cp filled) when the gap is below margin.
bool rollerSprocketKinematics(const Model& m, int sprocket, int link, int end, const LinkKin& lk, double angle,
                              double cosA, double sinA, double rate, double margin, ContactPoint& cp);

/// Plate edge of link `link` against face `face` of a guide turned by `angle` about its pivot.
bool plateGuideKinematics(const Model& m, int guide, int face, int link, const LinkKin& lk, double cosA, double sinA,
                          double rate, double margin, ContactPoint& cp);
/// The same with the face already placed (placeFace) at the guide's angle.
bool plateGuideKinematics(const Model& m, int guide, int face, const PlacedFace& pf, int link, const LinkKin& lk,
                          double rate, double margin, ContactPoint& cp);

/// The steps of a roller's query against a sprocket, shared by the query of one roller
/// (rollerSprocketKinematics) and the contact search's queries of several rollers at a time
/// (contact_lanes.h): formulas of T = double or a vector of doubles (simd.h), the same operations
/// in both, so the same bits.
namespace roller {

/// A roller centre relative to the sprocket's centre (relX, relY), in the frame of the sprocket
/// turned by (cosA, sinA).
template <class T>
CHAINDRIVE_ALWAYS_INLINE void toSprocketFrame(T relX, T relY, double cosA, double sinA, T& bodyX, T& bodyY) {
  const double s = -sinA;
  bodyX = cosA * relX - s * relY;
  bodyY = s * relX + cosA * relY;
}

/// That centre in the frame of its tooth gap, whose axis is (gapX, gapY) in the sprocket's frame.
template <class T>
CHAINDRIVE_ALWAYS_INLINE void toGapFrame(T bodyX, T bodyY, T gapX, T gapY, T& localX, T& localY) {
  const T s = -gapY;
  localX = gapX * bodyX - s * bodyY;
  localY = s * bodyX + gapX * bodyY;
}

/// A roller contact's kinematics in the world frame (the ContactPoint fields of the same names).
template <class T>
struct World {
  T normalX, normalY, tangentX, tangentY, rLinkX, rLinkY, rRotorX, rRotorY, vN, vT;
};

/// The profile's closest point and normal (gap frame) back in the world frame, with the lever arms
/// and the relative velocity: the roller at (px, py) moving at (vx, vy) on its link centred at
/// (linkX, linkY), the sprocket turned by (cosA, sinA) at `rate`, the gap's axis (gapX, gapY).
template <class T>
CHAINDRIVE_ALWAYS_INLINE World<T> toWorld(Vec2 center, double cosA, double sinA, double rate, T gapX, T gapY,
                                          T pointX, T pointY, T normalX, T normalY, T px, T py, T vx, T vy, T linkX,
                                          T linkY) {
  World<T> w;
  // the rotation by (rotor angle + the gap's angle)
  const T c = cosA * gapX - sinA * gapY, s = sinA * gapX + cosA * gapY;
  w.normalX = c * normalX - s * normalY;
  w.normalY = s * normalX + c * normalY;
  w.tangentX = -w.normalY;
  w.tangentY = w.normalX;
  const T qx = center.x + (c * pointX - s * pointY), qy = center.y + (s * pointX + c * pointY);
  w.rLinkX = px - linkX;  // the roller turns on its bushing: the force acts at its centre
  w.rLinkY = py - linkY;
  w.rRotorX = qx - center.x;
  w.rRotorY = qy - center.y;
  const T vRelX = vx - (-rate * w.rRotorY), vRelY = vy - rate * w.rRotorX;
  w.vN = vRelX * w.normalX + vRelY * w.normalY;
  w.vT = vRelX * w.tangentX + vRelY * w.tangentY;
  return w;
}

/// The tooth gap whose sector holds the direction `body` (sprocket frame), walked to from
/// `guess` (-1: none); the result does not depend on the guess. The sectors (from the tooth axis
/// before a gap to the one after it) partition the plane exactly (one cross product decides
/// between two neighbours), so a guess only saves the search. Inline: the guess right, two cross
/// products (the roller stays in its gap for many steps); a walk otherwise (searchGap).
int searchGap(const SprocketModel& s, Vec2 body, int guess);
inline int gapOf(const SprocketModel& s, Vec2 body, int guess) {
  const int z = s.gap.teeth;
  if (guess < 0 || guess >= z) return searchGap(s, body, guess);
  const int next = guess + 1 == z ? 0 : guess + 1;
  if (cross(s.toothDirs[guess], body) < 0.0 || cross(body, s.toothDirs[next]) <= 0.0) return searchGap(s, body, guess);
  return guess;
}

// A roller's gap, the distance of its centre from the sprocket's outline less its radius, changes
// by no more than its centre moves (in the sprocket's frame): a roller that was clear of the
// outline by c cannot touch it within a distance c - margin of where it was. The bound keeps a
// nanometre in reserve, ten million times the rounding of the gap (about 1e-17 m), so that where
// it skips a query the query would have found no contact either.
constexpr double kClearanceReserve = 1e-9;  // [m]

/// Fills cp with a roller contact: gap and the kinematics of lane l of w (arrays of lanes).
template <int W>
CHAINDRIVE_ALWAYS_INLINE void setContact(ContactPoint& cp, int link, int end, int sprocket, int rotor, double gap,
                                         const World<double[W]>& w, int l) {
  cp.kind = ContactPoint::Kind::RollerSprocket;
  cp.link = link;
  cp.end = end;
  cp.element = sprocket;
  cp.face = -1;
  cp.rotor = rotor;
  cp.gap = gap;
  cp.normal = Vec2{w.normalX[l], w.normalY[l]};
  cp.tangent = Vec2{w.tangentX[l], w.tangentY[l]};
  cp.rLink = Vec2{w.rLinkX[l], w.rLinkY[l]};
  cp.rRotor = Vec2{w.rRotorX[l], w.rRotorY[l]};
  cp.vN = w.vN[l];
  cp.vT = w.vT[l];
  cp.fN = cp.fT = 0.0;
}

}  // namespace roller

/// The plate-guide query's piece shared with the contact search's links several at a time
/// (contact_lanes.h): fills cp with the contact `hit` of link `link`'s plate edge (the link centred
/// at `center`, moving at `velocity` and turning at `omega`) with face `face` of guide `guide`, the
/// guide turning at `rate`.
void setPlateContact(const Model& m, int guide, int face, int link, Vec2 center, Vec2 velocity, double omega,
                     const FaceHit& hit, double rate, ContactPoint& cp);

/// Tunnelling check: true if some contact of `contacts[0..n)` penetrates deeper than `limit`
/// [m] (a roller through a tooth, a link through a guide face); `why` then names the contact,
/// its depth, the limit and the time.
bool deepPenetration(const ContactPoint* contacts, int n, double limit, double t, Failure& why);

/// Finds every contact with gap below margin into d.contacts[0 .. d.nContacts). Fixed order:
/// rollers by sprocket, link and end; then plates by guide, face and link. With `forces` (the
/// compliant contacts, margin 0), also their forces by the compliant law (c.fN, c.fT; one pass,
/// contact_compliant.h), added to d.gen in that order; returns their dissipated power (0 without).
/// d.deepestGap: the deepest gap found (0 without a penetration); with forces and
/// !d.listContacts, that and the forces only (nothing listed, d.nContacts 0).
double detectContacts(const Model& m, Data& d, double margin, bool forces = false);

/// detectContacts' first stage: the guides' bounding circles of the search (grown by the reach of
/// `margin`) and their faces placed at their angles, into d; returns a plate edge's reach.
double placeGuides(const Model& m, Data& d, double margin);

/// detectContacts with the forces and no list, on several threads (dynamics/threaded.h), after
/// placeGuides and the search windows: each thread's share over its links (the forces on them,
/// the rest into its part) ...
void shareContacts(const Model& m, Data& d, double reachLink, ThreadPart& part);
/// ... then, on one thread, the rotors' shares and the power summed in detectContacts' order, the
/// parts' deepest gap and counts combined; returns the power.
double sumSharedContacts(const Model& m, Data& d);

/// Column of W for direction `dir` (normal or tangent) of contact c: the link entries
/// (d/dq of the relative velocity along dir for x, y, gamma) and the rotor entry.
inline void wColumn(const ContactPoint& c, Vec2 dir, double link[3], double& rotor) {
  link[0] = dir.x;
  link[1] = dir.y;
  link[2] = cross(c.rLink, dir);
  rotor = c.rotor >= 0 ? -cross(c.rRotor, dir) : 0.0;
}

}  // namespace chaindrive
