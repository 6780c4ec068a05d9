#include "dynamics/joint_forces.h"

#include <cmath>

namespace chaindrive {

JointResult jointForce(const ChainModel& ch, const LinkKin& a, const LinkKin& b) {
  JointResult r;
  const Vec2 dpos = a.front - b.rear;          // separation of the two pin centres
  const Vec2 dvel = a.vFront - b.vRear;
  const Vec2 axis = a.e + b.e;                 // mean chain direction at the joint
  const double axisN = norm(axis);
  const Vec2 u = axisN > 0.0 ? (1.0 / axisN) * axis : a.e;
  if (ch.jointClearance <= 0.0) {
    r.force = -ch.jointStiffness * dpos - ch.jointDamping * dvel;
    r.deformation = norm(dpos);
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
      r.deformation = pen;
      r.power = (f - ch.jointStiffness * pen) * rate;
      r.energy = 0.5 * ch.jointStiffness * pen * pen;
    }
  }
  // tension: the pull of link b on link a's front pin, along the chain
  r.tension = dot(r.force, u);
  return r;
}

double evaluateJoints(const Model& m, Data& d) {
  const int n = m.chain.links;
  double power = 0.0;
  for (int j = 0; j < n; ++j) {
    const int k = j + 1 == n ? 0 : j + 1;
    const JointResult r = jointForce(m.chain, d.links[j], d.links[k]);
    d.joints[j].force = r.force;
    d.joints[j].tension = r.tension;
    d.joints[j].deformation = r.deformation;
    addJointGen(d.links[j], d.links[k], r.force, &d.gen[3 * j], &d.gen[3 * k]);
    power += r.power;
  }
  return power;
}

double jointEnergy(const Model& m, const Data& d) {
  const int n = m.chain.links;
  double e = 0.0;
  for (int j = 0; j < n; ++j) e += jointForce(m.chain, d.links[j], d.links[j + 1 == n ? 0 : j + 1]).energy;
  return e;
}

}  // namespace chaindrive
