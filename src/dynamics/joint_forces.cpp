#include "dynamics/joint_forces.h"

#include <algorithm>
#include <cmath>

#include "dynamics/link_loops.h"

namespace chaindrive {

JointResult jointForce(const ChainModel& ch, const LinkKin& a, const LinkKin& b) {
  JointResult r;
  const Vec2 dpos = a.front - b.rear;          // separation of the two pin centres
  const Vec2 dvel = a.vFront - b.vRear;
  journalBearing(ch, dpos.x, dpos.y, dvel.x, dvel.y, r.force.x, r.force.y, r.power);
  if (ch.jointClearance <= 0.0) {
    r.energy = 0.5 * ch.jointStiffness * dot(dpos, dpos);
  } else {
    const double pen = std::max(0.0, norm(dpos) - ch.jointClearance);
    r.energy = 0.5 * ch.jointStiffness * pen * pen;
  }
  return r;
}

double jointDeformation(const ChainModel& ch, const LinkKin& a, const LinkKin& b) {
  const double dist = norm(a.front - b.rear);
  return ch.jointClearance <= 0.0 ? dist : std::max(0.0, dist - ch.jointClearance);
}

double jointTension(const LinkKin& a, const LinkKin& b, Vec2 force) {
  const Vec2 axis = a.e + b.e;  // mean chain direction at the joint
  const double axisN = norm(axis);
  return dot(force, axisN > 0.0 ? (1.0 / axisN) * axis : a.e);
}

double evaluateJoints(const Model& m, Data& d) { return jointForcesLoop(m, d); }

void measureJoints(const Model& m, Data& d) {
  jointMeasuresLoop(m, d, d.joints.tension.data(), d.joints.deformation.data());
}

bool jointsWithin(const Model& m, const Data& d, double limit) {
  const double reach = limit + std::max(0.0, m.chain.jointClearance);
  if (d.jointForces) return d.jointOpening2 <= reach * reach;  // (false for NaN)
  const int n = m.chain.links;
  bool within = true;
  for (int j = 0; j < n; ++j) within &= norm2(d.links[j].front - d.links[j + 1 == n ? 0 : j + 1].rear) <= reach * reach;
  return within;
}

double jointEnergy(const Model& m, const Data& d) { return jointMeasuresLoop(m, d, nullptr, nullptr); }

}  // namespace chaindrive
