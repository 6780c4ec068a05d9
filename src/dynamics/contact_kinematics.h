// Contact detection and kinematics, in one place for every contact method: gaps, normal and
// tangential relative velocities, and the columns of the contact Jacobians W_N, W_T of the
// paper's eq. (1) (generalized coordinates: link x, y, gamma and the rotor angle).
#pragma once

#include <string>

#include "dynamics/data.h"
#include "failure.h"
#include "assembly/model.h"

namespace chaindrive {

/// Link kinematics from the 6 link states (x, y, gamma, vx, vy, omega).
LinkKin linkKinematics(const ChainModel& ch, const double* s);

/// Fills d.links, d.rotorAngle/Rate/Cos/Sin from the state and the inputs (driven rotor rate).
void evaluateKinematics(const Model& m, Data& d, const double* y);

/// Roller of link `link` at end (0 rear, 1 front) against a sprocket turned to `angle` (with
/// cos/sin given) at angular velocity `rate`. True (and cp filled) when the gap is below margin.
/// `gapHint` (optional, in and out): the roller's tooth gap on this sprocket at the last call, a
/// starting guess that makes finding the gap cheap; the result does not depend on it.
bool rollerSprocketKinematics(const Model& m, int sprocket, int link, int end, const LinkKin& lk, double angle,
                              double cosA, double sinA, double rate, double margin, ContactPoint& cp,
                              int* gapHint = nullptr);

/// Plate edge of link `link` against face `face` of a guide turned by `angle` about its pivot.
bool plateGuideKinematics(const Model& m, int guide, int face, int link, const LinkKin& lk, double cosA, double sinA,
                          double rate, double margin, ContactPoint& cp);
/// The same with the face already placed (placeFace) at the guide's angle.
bool plateGuideKinematics(const Model& m, int guide, int face, const PlacedFace& pf, int link, const LinkKin& lk,
                          double rate, double margin, ContactPoint& cp);

/// Tunnelling check: true if some contact of `contacts[0..n)` penetrates deeper than `limit`
/// [m] (a roller through a tooth, a link through a guide face); `why` then names the contact,
/// its depth, the limit and the time.
bool deepPenetration(const ContactPoint* contacts, int n, double limit, double t, Failure& why);

/// Finds every contact with gap below margin into d.contacts[0 .. d.nContacts). Fixed order:
/// rollers by link, end and sprocket; then plates by guide, link and face.
void detectContacts(const Model& m, Data& d, double margin);

/// Column of W for direction `dir` (normal or tangent) of contact c: the link entries
/// (d/dq of the relative velocity along dir for x, y, gamma) and the rotor entry.
inline void wColumn(const ContactPoint& c, Vec2 dir, double link[3], double& rotor) {
  link[0] = dir.x;
  link[1] = dir.y;
  link[2] = cross(c.rLink, dir);
  rotor = c.rotor >= 0 ? -cross(c.rRotor, dir) : 0.0;
}

}  // namespace chaindrive
