// Chain joints: journal bearings between neighbouring links (paper Fig. 2), a radial
// spring-damper with optional clearance.
#pragma once

#include "dynamics/data.h"
#include "assembly/model.h"

namespace chaindrive {

/// Force of joint between link a's front pin and link b's rear pin, acting on a's front pin
/// (b gets the opposite). Also returns tension, deformation and dissipated power.
struct JointResult {
  Vec2 force;
  double tension = 0.0, deformation = 0.0, power = 0.0, energy = 0.0;
};
JointResult jointForce(const ChainModel& ch, const LinkKin& a, const LinkKin& b);

/// Adds the generalized forces of joint force f (on a's front pin) to links a and b.
inline void addJointGen(const LinkKin& a, const LinkKin& b, Vec2 f, double* ga, double* gb) {
  ga[0] += f.x;
  ga[1] += f.y;
  ga[2] += cross(a.front - a.c, f);
  gb[0] -= f.x;
  gb[1] -= f.y;
  gb[2] -= cross(b.rear - b.c, f);
}

/// Evaluates all joints into d.joints and d.gen; returns the dissipated power.
double evaluateJoints(const Model& m, Data& d);
/// Elastic energy stored in the joints at the current kinematics.
double jointEnergy(const Model& m, const Data& d);

}  // namespace chaindrive
