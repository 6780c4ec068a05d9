// The links' iteration matrix of linearly implicit schemes: W = M - a dQ/dv - b dQ/dq over the
// link coordinates (x, y, gamma of every link), from the joints and the compliant contacts at
// the last evaluation of the dynamics. These are the stiff forces (joint modes near 3e5 rad/s,
// roller contacts in parallel, friction regularised over 0.05 m/s); what they exert on rotors and
// guides (large inertias, slow modes) is left to the explicit part of the scheme, so W is a ring
// of 3 x 3 blocks: link j couples to links j - 1 and j + 1 through its joints only.
#pragma once

#include "assembly/model.h"
#include "dynamics/data.h"
#include "linear/cyclic_block_tridiagonal.h"

namespace chaindrive {

/// Fills W (blocks of links 0..n-1) with M - a D - b K at the kinematics, joint forces and
/// contacts held in d (an evaluation of the dynamics, generalizedForces, must precede it).
/// Derivatives at fixed lever arms and contact normals, plus the lever arms' turning under
/// the force (the geometric stiffness of joints and contacts).
void linkIterationMatrix(const Model& m, const Data& d, double a, double b, CyclicBlockTridiagonal3& w);

/// The diagonal of W's damping part over the masses, -diag(dQ/dv) / M: per link coordinate what
/// the joints and the compliant contacts held in d damp it by (its rate r [1/s], >= 0), and from it
/// the kick a / (1 + a r) of the schemes that treat damping implicitly, into the state's velocity
/// components of `kick` (model.h; the other components untouched). The joints' part is that of
/// pins half a pitch from the centre (the lever arm of every pin); without joint clearance it is
/// the same for every link and in every state (constantPart: that part alone, none with
/// clearance), and a link without damping contacts gets its kick without a division.
/// (d.contactDamping: its work area.)
void linkDampedKicks(const Model& m, Data& d, double a, bool constantPart, double* kick);

}  // namespace chaindrive
