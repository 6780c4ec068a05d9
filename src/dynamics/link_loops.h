// The per-link stages of the dynamics as loops over the link arrays (data.h), several links per
// vector instruction (simd.h): 4 lanes (AVX2, without FMA) where the CPU has them, 2 (SSE2, every
// x86-64 CPU) otherwise, chosen per Data (Data::vectorLanes) and giving the same bits either way,
// the bits of the same formulas for one link at a time (tests/cpp/dynamics/link_loops_test.cpp).
#pragma once

#include "assembly/model.h"
#include "dynamics/data.h"
#include "simd.h"

namespace chaindrive {

/// Per pin, from vectors over the links from an even one (as the pins: pin i is link i's rear pin):
/// lane l of `rear` for an even pin l, lane l - 1 of `front` for an odd one. The rollers sit on
/// the even links, one at each end: pinLanes of the rear and front pins are the rollers.
template <int W>
CHAINDRIVE_ALWAYS_INLINE typename simd::Lanes<W>::V pinLanes(typename simd::Lanes<W>::V rear,
                                                             typename simd::Lanes<W>::V front) {
  return simd::evenLanes(rear, front);
}

/// The lanes of this CPU's widest vectors the loops use: 4 with AVX2, else 2.
int supportedVectorLanes();

/// Link kinematics from the state y: centres, axes, pins and their velocities (d.links), and the
/// first link's rear pin and axis copied behind the last one (the joints' loops read them there).
void linkKinematicsLoop(const Model& m, Data& d, const double* y);

// The passes of the per-link loops over a range of links [r.first, r.last), r.first a multiple
// of 4, for an evaluation on several threads (dynamics/threaded.h): each thread its links, a
// barrier between passes that read their neighbours' results. The whole loops above are these
// over all links, so every split gives the same bits.

/// The links' kinematics (link 0's range also copies its rear pin behind the last link).
void linkKinematicsRange(const Model& m, Data& d, const double* y, LinkRange r);
/// The joints' forces (the last joint's range also copies its force in front of the first), their
/// power stored per joint into d.threads.jointPower; returns the largest squared opening (NaN:
/// one was NaN).
double jointForcesRange(const Model& m, Data& d, LinkRange r);
/// The links' generalized forces of their two joints (after every range's jointForcesRange).
void jointGenRange(const Model& m, Data& d, LinkRange r);
/// d.threads.jointPower summed as jointForcesLoop sums the power.
double jointPowerSum(const Model& m, const Data& d);
/// jointDampingOffDiagonalLoop's three passes.
void dampingCopyRange(const Model& m, Data& d, const double* accel, LinkRange r);
void dampingForceRange(const Model& m, Data& d, LinkRange r);
void dampingSweepRange(const Model& m, Data& d, double a, double* accel, LinkRange r);

/// The joint forces (d.joints) and from them the links' generalized forces, written (not added)
/// into the link part of d.gen; the largest squared pin separation into d.jointOpening2. Returns
/// the joints' dissipated power (summed in four partial sums: link i in sum i mod 4).
double jointForcesLoop(const Model& m, Data& d);

/// From the kinematics and joint forces in d: per joint its tension along the links' mean axis
/// and its deformation (into tension and deformation, n each, unless null), and the joints'
/// elastic energy, returned (summed as the power of jointForcesLoop).
double jointMeasuresLoop(const Model& m, const Data& d, double* tension, double* deformation);

/// The joints' damping without clearance, C = M^-1 J^T c J (the links' masses M, the pins' levers
/// half a pitch along the link axes in d), applied off its diagonal D to the link accelerations
/// `accel` (3n: ax, ay, alpha of every link, the state's layout), in place:
/// accel -= a (C - D) accel. (C is linear: applied to accelerations here, not velocities.)
void jointDampingOffDiagonalLoop(const Model& m, Data& d, double a, double* accel);

/// kick[i] = a / (1 + a (base + extra[i])) for i < n (extra null: none): the kicks of components
/// damped at rate base plus extra (>= 0), the division only in the vectors where extra is nonzero
/// (else a / (1 + a base), the same bits). `lanes`: 4 or 2, Data::vectorLanes.
void dampedKickLoop(double a, double base, const double* extra, int n, double* kick, int lanes);

}  // namespace chaindrive
