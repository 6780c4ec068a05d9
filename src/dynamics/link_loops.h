// The per-link stages of the dynamics as loops over the link arrays (data.h), several links per
// vector instruction (simd.h): 4 lanes (AVX2, without FMA) where the CPU has them, 2 (SSE2, every
// x86-64 CPU) otherwise, chosen per Data (Data::vectorLanes) and giving the same bits either way,
// the bits of the same formulas for one link at a time (tests/cpp/dynamics/link_loops_test.cpp).
#pragma once

#include "assembly/model.h"
#include "dynamics/data.h"

namespace chaindrive {

/// The lanes of this CPU's widest vectors the loops use: 4 with AVX2, else 2.
int supportedVectorLanes();

/// Link kinematics from the state y: centres, axes, pins and their velocities (d.links), and the
/// first link's rear pin copied behind the last one (the joints' loop reads it there).
void linkKinematicsLoop(const Model& m, Data& d, const double* y);

/// The joint forces (d.joints) and from them the links' generalized forces, written (not added)
/// into the link part of d.gen; the largest squared pin separation into d.jointOpening2. Returns
/// the joints' dissipated power (summed in four partial sums: link i in sum i mod 4).
double jointForcesLoop(const Model& m, Data& d);

/// The contact search's first, coarse test over all links (contact_kinematics.h): for every link
/// the sprockets whose reach holds the roller at either of its ends (d.nearSprockets, bit
/// end * kMaxSprockets + s) and the guides whose bounding circle, grown by the search's reach,
/// holds its centre (d.nearGuides, bit g; the circles in d.guideBoundX, guideBoundY,
/// guideReach2).
void nearElementsLoop(const Model& m, Data& d);

}  // namespace chaindrive
