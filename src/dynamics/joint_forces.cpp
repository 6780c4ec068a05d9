#include "dynamics/joint_forces.h"

#include <algorithm>
#include <cmath>

namespace chaindrive {

JointResult jointForce(const ChainModel& ch, const LinkKin& a, const LinkKin& b) {
  JointResult r;
  const Vec2 dpos = a.front - b.rear;          // separation of the two pin centres
  const Vec2 dvel = a.vFront - b.vRear;
  if (ch.jointClearance <= 0.0) {
    r.force = -ch.jointStiffness * dpos - ch.jointDamping * dvel;
    r.power = ch.jointDamping * dot(dvel, dvel);
    r.energy = 0.5 * ch.jointStiffness * dot(dpos, dpos);
  } else {
    const double dist = norm(dpos);
    const double pen = dist - ch.jointClearance;
    if (pen > 0.0) {
      const Vec2 nrm = (1.0 / dist) * dpos;
      const double rate = dot(dvel, nrm);
      double f = ch.jointStiffness * pen + ch.jointDamping * rate;
      if (f < 0.0) f = 0.0;
      r.force = -f * nrm;
      r.power = (f - ch.jointStiffness * pen) * rate;
      r.energy = 0.5 * ch.jointStiffness * pen * pen;
    }
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

double evaluateJoints(const Model& m, Data& d) {
  const int n = m.chain.links;
  double power = 0.0;
  for (int j = 0; j < n; ++j) {
    const int k = j + 1 == n ? 0 : j + 1;
    const JointResult r = jointForce(m.chain, d.links[j], d.links[k]);
    d.joints[j].force = r.force;
    addJointGen(d.links[j], d.links[k], r.force, &d.gen[3 * j], &d.gen[3 * k]);
    power += r.power;
  }
  return power;
}

void measureJoints(const Model& m, Data& d) {
  const int n = m.chain.links;
  for (int j = 0; j < n; ++j) {
    const LinkKin &a = d.links[j], &b = d.links[j + 1 == n ? 0 : j + 1];
    d.joints[j].tension = jointTension(a, b, d.joints[j].force);
    d.joints[j].deformation = jointDeformation(m.chain, a, b);
  }
}

bool jointsWithin(const Model& m, const Data& d, double limit) {
  const int n = m.chain.links;
  const double reach = limit + std::max(0.0, m.chain.jointClearance), reach2 = reach * reach;
  bool within = true;
  for (int j = 0; j < n; ++j) within &= norm2(d.links[j].front - d.links[j + 1 == n ? 0 : j + 1].rear) <= reach2;
  return within;
}

double jointEnergy(const Model& m, const Data& d) {
  const int n = m.chain.links;
  double e = 0.0;
  for (int j = 0; j < n; ++j) e += jointForce(m.chain, d.links[j], d.links[j + 1 == n ? 0 : j + 1]).energy;
  return e;
}

}  // namespace chaindrive
