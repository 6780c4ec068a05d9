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

/// The links within guide `guide`'s bounding circle (d.guideBoundX, guideBoundY, guideReach2) and
/// near its arc face `face` (convex or concave), placed at the guide's angle (pf), against that
/// face: their contacts with gap below margin appended to d.contacts from index `count` in the
/// order of the links; returns the new count. `reach`: a plate edge's farthest point from its
/// link's centre (and the margin), faceNear's reach.
/// `forces`, `power`: as for the rollers.
int plateContactsLoop(const Model& m, Data& d, int guide, int face, const PlacedFace& pf, double margin, double reach,
                      bool forces, int count, double& power);

}  // namespace chaindrive
