#include "dynamics/iteration_matrix.h"

#include <algorithm>
#include <cmath>

#include "dynamics/contact_compliant.h"
#include "dynamics/link_loops.h"

namespace chaindrive {

namespace {

using Block = CyclicBlockTridiagonal3::Block;
using PointJacobian = Eigen::Matrix<double, 2, 3>;

// d(point)/d(x, y, gamma) of a point at r from a link's centre: [I, perp(r)]
PointJacobian pointJacobian(Vec2 r) {
  PointJacobian j;
  j << 1.0, 0.0, -r.y, 0.0, 1.0, r.x;
  return j;
}

Eigen::Matrix2d outer(Vec2 u, double s) {
  Eigen::Matrix2d o;
  o << s * u.x * u.x, s * u.x * u.y, s * u.x * u.y, s * u.y * u.y;
  return o;
}

// a * (damping) + b * (stiffness) of the joint between pins, as a 2 x 2 matrix on their
// separation: isotropic without clearance, along the pins' normal when the bearing is closed
Eigen::Matrix2d jointPinMatrix(const ChainModel& ch, const LinkKin& la, const LinkKin& lb, Vec2 force, double a,
                               double b) {
  const double s = a * ch.jointDamping + b * ch.jointStiffness;
  if (ch.jointClearance <= 0.0) return s * Eigen::Matrix2d::Identity();
  const Vec2 dpos = la.front - lb.rear;
  const double dist = norm(dpos);
  if (dist <= ch.jointClearance || norm2(force) == 0.0) return Eigen::Matrix2d::Zero();
  return outer((1.0 / dist) * dpos, s);
}

void addJoints(const Model& m, const Data& d, double a, double b, CyclicBlockTridiagonal3& w) {
  const int n = m.chain.links;
  for (int j = 0; j < n; ++j) {
    const int k = j + 1 == n ? 0 : j + 1;
    const LinkKin &la = d.links[j], &lb = d.links[k];
    const Vec2 force = d.joints.force(j);  // on link j's front pin; link k gets the opposite
    const Vec2 u = la.front - la.c, v = lb.rear - lb.c;
    const PointJacobian ja = pointJacobian(u), jb = pointJacobian(v);
    const Eigen::Matrix2d s = jointPinMatrix(m.chain, la, lb, force, a, b);
    const Eigen::Matrix<double, 3, 2> jas = ja.transpose() * s, jbs = jb.transpose() * s;
    w.diagonal(j).noalias() += jas * ja;
    w.diagonal(k).noalias() += jbs * jb;
    w.upper(j).noalias() -= jas * jb;
    w.lower(k).noalias() -= jbs * ja;
    // the lever arms turn with their links under the joint force
    w.diagonal(j)(2, 2) += b * dot(u, force);
    w.diagonal(k)(2, 2) -= b * dot(v, force);
  }
}

void addContacts(const Model& m, const Data& d, double a, double b, CyclicBlockTridiagonal3& w) {
  for (int i = 0; i < d.nContacts; ++i) {
    const ContactPoint& c = d.contacts[i];
    const ContactLaw& law = c.kind == ContactPoint::Kind::RollerSprocket ? m.rollerSprocket : m.plateGuide;
    const CompliantSlopes k = compliantContactSlopes(law, m.frictionRegularization, c);
    if (c.gap >= 0.0 || c.fN <= 0.0) continue;  // open, or the normal force clamped at zero
    const Eigen::Matrix2d s =
        outer(c.normal, a * k.byPenetrationRate + b * k.byPenetration) + outer(c.tangent, a * k.bySliding);
    const PointJacobian jc = pointJacobian(c.rLink);
    Block& diag = w.diagonal(c.link);
    diag.noalias() += jc.transpose() * s * jc;
    diag(2, 2) += b * dot(c.rLink, c.fN * c.normal + c.fT * c.tangent);
  }
}

}  // namespace

void linkIterationMatrix(const Model& m, const Data& d, double a, double b, CyclicBlockTridiagonal3& w) {
  w.setZero();
  const Block mass = Eigen::Vector3d(m.chain.mass, m.chain.mass, m.chain.inertia).asDiagonal();
  for (int i = 0; i < m.chain.links; ++i) w.diagonal(i) = mass;
  if (d.jointForces) addJoints(m, d, a, b, w);
  if (d.compliantContacts) addContacts(m, d, a, b, w);
}

void linkDampedKicks(const Model& m, Data& d, double a, bool constantPart, double* kick) {
  const int n = m.chain.links;
  const double c = m.chain.jointDamping, arm2 = 0.25 * m.chain.pitch * m.chain.pitch;
  const double invM = 1.0 / m.chain.mass, invJ = 1.0 / m.chain.inertia;
  double *x = kick + m.linkState(0, Model::kVx), *gamma = kick + m.linkState(0, Model::kOmega);  // (x, then y)
  // the compliant contacts: normal damping and regularised friction at the contact point, and the
  // joints: two per link, isotropic without clearance (the same for every link)
  const double* contact = nullptr;
  if (!constantPart && d.compliantContacts) {
    double* rates = d.contactDamping.data();
    std::fill(rates, rates + 3 * n, 0.0);
    for (int i = 0; i < d.nContacts; ++i) {
      const ContactPoint& cp = d.contacts[i];
      if (cp.gap < 0.0 && cp.fN > 0.0)
        addContactDamping(m, cp.kind == ContactPoint::Kind::RollerSprocket ? m.rollerSprocket : m.plateGuide, cp, rates);
    }
    contact = rates;
  }
  if (d.jointForces && m.chain.jointClearance <= 0.0) {
    dampedKickLoop(a, 2.0 * c * invM, contact, 2 * n, x, d.vectorLanes);
    dampedKickLoop(a, 2.0 * c * arm2 * invJ, contact ? contact + 2 * n : nullptr, n, gamma, d.vectorLanes);
    return;
  }
  if (constantPart) {  // (with clearance the joints' damping changes with the state: none is constant)
    std::fill(x, x + 3 * n, a);
    return;
  }
  // with clearance, along the pins' normal while a bearing is closed: the rates, then the kicks
  for (int i = 0; i < 2 * n; ++i) x[i] = contact ? contact[i] : 0.0;
  for (int i = 0; i < n; ++i) gamma[i] = contact ? contact[2 * n + i] : 0.0;
  for (int j = 0; d.jointForces && j < n; ++j) {
    const int k = j + 1 == n ? 0 : j + 1;
    const Vec2 dpos = d.links[j].front - d.links[k].rear;
    const double dist = norm(dpos);
    if (!(dist > m.chain.jointClearance && norm2(d.joints.force(j)) > 0.0)) continue;  // open
    const Vec2 u = (1.0 / dist) * dpos;
    for (const int link : {j, k}) {
      const double along = dot(u, Vec2{d.links.ex[link], d.links.ey[link]});  // (the pin's arm lies along the axis)
      x[link] += c * u.x * u.x * invM;
      x[n + link] += c * u.y * u.y * invM;
      gamma[link] += c * arm2 * (1.0 - along * along) * invJ;
    }
  }
  for (int i = 0; i < 3 * n; ++i) x[i] = a / (1.0 + a * x[i]);
}

}  // namespace chaindrive
