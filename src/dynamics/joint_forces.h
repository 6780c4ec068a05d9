// Chain joints: journal bearings between neighbouring links (paper Fig. 2), a radial
// spring-damper with optional clearance.
#pragma once

#include "dynamics/data.h"
#include "assembly/model.h"

namespace chaindrive {

/// Force of joint between link a's front pin and link b's rear pin, acting on a's front pin
/// (b gets the opposite), with its dissipated power and stored energy.
struct JointResult {
  Vec2 force;
  double power = 0.0, energy = 0.0;
};
JointResult jointForce(const ChainModel& ch, const LinkKin& a, const LinkKin& b);
/// Radial displacement of the joint's pins beyond the clearance [m].
double jointDeformation(const ChainModel& ch, const LinkKin& a, const LinkKin& b);
/// The joint force's component along the links' mean axis: the tension [N].
double jointTension(const LinkKin& a, const LinkKin& b, Vec2 force);

/// Adds the generalized forces of joint force f (on a's front pin) to links a and b.
inline void addJointGen(const LinkKin& a, const LinkKin& b, Vec2 f, double* ga, double* gb) {
  ga[0] += f.x;
  ga[1] += f.y;
  ga[2] += cross(a.front - a.c, f);
  gb[0] -= f.x;
  gb[1] -= f.y;
  gb[2] -= cross(b.rear - b.c, f);
}

/// Evaluates all joint forces into d.joints and d.gen; returns the dissipated power. The
/// tensions and deformations (square roots the dynamics do not need) are measureJoints' work.
double evaluateJoints(const Model& m, Data& d);
/// Tension and deformation of every joint (d.joints) from the links and joint forces in d.
void measureJoints(const Model& m, Data& d);
/// True when no joint of d.links is opened by more than `limit` [m] (no square roots: the
/// check of every step; the joint that is, and by how much, is measureJoints' to tell).
bool jointsWithin(const Model& m, const Data& d, double limit);
/// Elastic energy stored in the joints at the current kinematics.
double jointEnergy(const Model& m, const Data& d);

}  // namespace chaindrive
