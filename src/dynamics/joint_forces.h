// Chain joints: journal bearings between neighbouring links (paper Fig. 2), a radial
// spring-damper with optional clearance.
#pragma once

#include "dynamics/data.h"
#include "assembly/model.h"
#include "simd.h"

namespace chaindrive {

/// The journal bearing's law for one joint (T = double) or a vector of joints (simd.h): the force
/// (fx, fy) on link a's front pin (link b's rear pin gets the opposite) from the separation
/// (dx, dy) of a's front pin from b's rear pin and its rate (dvx, dvy), and the power it
/// dissipates. One definition for both, so the per-link loops give the bits of one joint at a time.
template <class T>
CHAINDRIVE_ALWAYS_INLINE void journalBearing(const ChainModel& ch, T dx, T dy, T dvx, T dvy, T& fx, T& fy, T& power) {
  const double k = ch.jointStiffness, c = ch.jointDamping;
  if (ch.jointClearance <= 0.0) {
    fx = -k * dx - c * dvx;
    fy = -k * dy - c * dvy;
    power = c * (dvx * dvx + dvy * dvy);
    return;
  }
  // with clearance: a force only while the pins are pressed together beyond it
  const T zero{};
  const T dist = simd::sqrt(dx * dx + dy * dy);
  const T pen = dist - ch.jointClearance;
  const T inverse = 1.0 / dist;
  const T nx = inverse * dx, ny = inverse * dy;
  const T rate = dvx * nx + dvy * ny;
  T f = k * pen + c * rate;
  f = simd::select(f < 0.0, zero, f);
  const auto closed = pen > 0.0;
  fx = simd::select(closed, -f * nx, zero);
  fy = simd::select(closed, -f * ny, zero);
  power = simd::select(closed, (f - k * pen) * rate, zero);
}

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

/// Evaluates all joint forces into d.joints and the links' generalized forces from them into
/// d.gen (written, not added: the first stage of the link forces), and d.jointOpening2; returns
/// the dissipated power. The tensions and deformations (square roots the dynamics do not need)
/// are measureJoints' work. A loop over the link arrays (link_loops.h).
double evaluateJoints(const Model& m, Data& d);
/// Tension and deformation of every joint (d.joints) from the links and joint forces in d.
void measureJoints(const Model& m, Data& d);
/// True when no joint of d.links is opened by more than `limit` [m] (no square roots: the
/// check of every step, from d.jointOpening2 when the joint forces were evaluated; the joint
/// that is, and by how much, is measureJoints' to tell).
bool jointsWithin(const Model& m, const Data& d, double limit);
/// Elastic energy stored in the joints at the current kinematics.
double jointEnergy(const Model& m, const Data& d);

}  // namespace chaindrive
