// The contact search's queries several at a time (simd.h): the rollers near one sprocket and the
// links near one guide's arc face in vectors of 4 lanes (AVX2) or 2 (SSE2), with the formulas of
// one at a time (contact_kinematics.h, namespace roller; geometry.h, namespace arcface), so with
// the same bits.
#pragma once

#include "assembly/model.h"
#include "dynamics/data.h"

namespace chaindrive {

/// The rollers d.rollerCandidates of sprocket `sprocket` against it: their contacts with gap below
/// margin appended to d.contacts from index `count` in the candidates' order (as far as d.contacts
/// holds them); returns the new count. Reads and updates d.rollerHints as the query of one roller
/// does.
int rollerContactsLoop(const Model& m, Data& d, int sprocket, double margin, int count);

/// The links d.plateCandidates (those near guide `guide`) against its arc face `face` (convex or
/// concave), placed at the guide's angle (pf): their contacts with gap below margin appended to
/// d.contacts from index `count` in the candidates' order; returns the new count. `reach`: a
/// plate edge's farthest point from its link's centre (and the margin), faceNear's reach.
int plateContactsLoop(const Model& m, Data& d, int guide, int face, const PlacedFace& pf, double margin, double reach,
                      int count);

}  // namespace chaindrive
