// The contact search over the rollers and links in vectors of 4 lanes (AVX2) or 2 (SSE2), the
// coarse tests (a sprocket's reach, a guide's bounding circle) as lane masks, the queries with the
// formulas of one roller or link at a time (contact_kinematics.h, namespace roller; geometry.h,
// namespace arcface), so with the same bits.
#pragma once

#include "assembly/model.h"
#include "dynamics/data.h"

namespace chaindrive {

/// The search windows (data.h) for this evaluation: kept while nothing has moved further than their
/// band since the last scan, else scanned again; d.guideBoundX, guideBoundY, guideReach2 hold the
/// guides' circles of this evaluation (grown by the reach of `margin`).
void updateSearchWindows(const Model& m, Data& d, double margin);

/// The rollers within sprocket `sprocket`'s reach against it: their contacts with gap below margin
/// appended to d.contacts from index `count` in the order of their pins (as far as d.contacts
/// holds them); returns the new count. Reads and updates d.rollerHints: a roller still clear of
/// the outline by the last query's clearance is not queried again (roller::kClearanceReserve).
/// With `forces`, their forces by the compliant law too (contact_compliant.h), added to d.gen in
/// that order, their dissipated power to `power`.
int rollerContactsLoop(const Model& m, Data& d, int sprocket, double margin, bool forces, int count, double& power);

/// A guide face to search: face `face` of guide `guide`, placed at the guide's angle (pf), index in
/// d.placedFaces; a thread's part (null: all links).
struct PlateFaceRef {
  int guide, face;
  const PlacedFace& pf;
  int index;
  ThreadPart* part;
};

/// The links within guide `guide`'s bounding circle (d.guideBoundX, guideBoundY, guideReach2) and
/// near its arc face `face` (convex or concave), placed at the guide's angle (pf), against that
/// face: their contacts with gap below margin appended to d.contacts from index `count` in the
/// order of the links; returns the new count. `reach`: a plate edge's farthest point from its
/// link's centre (and the margin), faceNear's reach.
/// `forces`, `power`: as for the rollers; with a thread's part, the forces on its links and each
/// contact's share of the guide's rotor and power into the part (sharePlateForce).
int plateContactsLoop(const Model& m, Data& d, const PlateFaceRef& face, double margin, double reach, bool forces,
                      int count, double& power);

// The search's passes for an evaluation on several threads (dynamics/threaded.h), each thread over
// its own links, with the forces (the evaluations that list no contacts):

/// The largest moves of the links in range r since the last scan, merged into `moves`.
void linkMovesRange(const Data& d, LinkRange r, LinkMoves& moves);
/// Whether the windows hold for the guides' circles of this evaluation and the links' moves
/// (every thread's merged), as updateSearchWindows decides; if not, scanSearchWindows scans them.
bool windowsKept(const Model& m, const Data& d, double margin, const LinkMoves& moves);
void scanSearchWindows(const Model& m, Data& d, double margin);
/// rollerContactsLoop over the thread's blocks of the window: the forces on its links, the
/// torques and powers stored per roller (d.threads), its counts and deepest gap into its part.
void rollerContactsShare(const Model& m, Data& d, int sprocket, ThreadPart& part);
/// Then, on one thread, the sprocket's torque and the power summed from them in rollerContactsLoop's
/// order: the bits of one thread.
void rollerContactsSum(const Model& m, Data& d, int sprocket, double& power);

}  // namespace chaindrive
