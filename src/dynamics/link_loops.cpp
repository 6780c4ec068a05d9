// The 4-lane vectors are always inlined into the AVX2 functions: GCC's note that passing them
// between functions compiled without AVX would change the ABI does not apply.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

#include "dynamics/link_loops.h"

#include <algorithm>

#include "dynamics/joint_forces.h"
#include "simd.h"
#include "math/sincos.h"

namespace chaindrive {

namespace {

// The loops for W lanes, over whole vectors of links and a last, partly filled one
// (simd::forEachVector). Past the last link they read zeros or the arrays' zero padding and store
// nothing, so the padding stays zero and a joint past the last one has no force.

#define CHAINDRIVE_LANES_BODY [&](int i, auto lanes) __attribute__((always_inline))

template <int W>
CHAINDRIVE_ALWAYS_INLINE void kinematicsLanes(const Model& m, Data& d, const double* y, LinkRange r) {
  using V = typename simd::Lanes<W>::V;
  const int n = m.chain.links;
  LinkArrays& L = d.links;
  const double halfPitch = 0.5 * m.chain.pitch;
  const double *x = y, *yy = y + n, *gamma = y + 2 * n, *vx = y + 3 * n, *vy = y + 4 * n, *w = y + 5 * n;
  simd::forEachVectorIn<V>(r.first, r.last, CHAINDRIVE_LANES_BODY {
    V sine, cosine;
    sinCosLanes<W>(lanes.load(gamma + i), sine, cosine);
    const V cx = lanes.load(x + i), cy = lanes.load(yy + i);
    const V vcx = lanes.load(vx + i), vcy = lanes.load(vy + i), omega = lanes.load(w + i);
    const V hx = halfPitch * cosine, hy = halfPitch * sine;  // centre -> front pin
    const V vhx = -omega * hy, vhy = omega * hx;             // its velocity relative to the centre
    lanes.store(&L.cx[i], cx);
    lanes.store(&L.cy[i], cy);
    lanes.store(&L.vx[i], vcx);
    lanes.store(&L.vy[i], vcy);
    lanes.store(&L.w[i], omega);
    lanes.store(&L.ex[i], cosine);
    lanes.store(&L.ey[i], sine);
    lanes.store(&L.rearX[i], cx - hx);
    lanes.store(&L.rearY[i], cy - hy);
    lanes.store(&L.frontX[i], cx + hx);
    lanes.store(&L.frontY[i], cy + hy);
    lanes.store(&L.vRearX[i], vcx - vhx);
    lanes.store(&L.vRearY[i], vcy - vhy);
    lanes.store(&L.vFrontX[i], vcx + vhx);
    lanes.store(&L.vFrontY[i], vcy + vhy);
  });
  // the last joint joins the last link's front pin to the first link's rear pin
  if (r.first != 0) return;
  L.rearX[n] = L.rearX[0];
  L.rearY[n] = L.rearY[0];
  L.vRearX[n] = L.vRearX[0];
  L.vRearY[n] = L.vRearY[0];
  L.ex[n] = L.ex[0];
  L.ey[n] = L.ey[0];
}

// What the joints' pass over the links carries from vector to vector: their power in four
// partial sums (link i in sum i mod 4), the largest squared opening and whether one was NaN.
template <int W>
struct JointScan {
  typename simd::Lanes<W>::V partial[4 / W] = {}, widest = {};
  typename simd::Lanes<W>::Mask notANumber = {};
  double largest() const {  // (NaN where one was)
    double largest = 0.0;
    bool nan = false;
    for (int l = 0; l < W; ++l) {
      largest = widest[l] > largest ? widest[l] : largest;
      nan |= notANumber[l] != 0;
    }
    return nan ? std::nan("") : largest;
  }
};

// The joints' forces of range r (joint i: link i's front pin against link i + 1's rear pin), their
// power into the scan's sums, or stored per joint into powerOut where not null.
template <int W>
CHAINDRIVE_ALWAYS_INLINE void jointForceLanes(const Model& m, Data& d, LinkRange r, JointScan<W>& scan,
                                              double* powerOut) {
  using V = typename simd::Lanes<W>::V;
  using simd::load;
  const int n = m.chain.links;
  const LinkArrays& L = d.links;
  double *fx = d.joints.forceX(), *fy = d.joints.forceY();
  simd::forEachVectorIn<V>(r.first, r.last, CHAINDRIVE_LANES_BODY {
    const V dx = load<V>(&L.frontX[i]) - load<V>(&L.rearX[i + 1]);
    const V dy = load<V>(&L.frontY[i]) - load<V>(&L.rearY[i + 1]);
    const V dvx = load<V>(&L.vFrontX[i]) - load<V>(&L.vRearX[i + 1]);
    const V dvy = load<V>(&L.vFrontY[i]) - load<V>(&L.vRearY[i + 1]);
    V jfx, jfy, power;
    journalBearing(m.chain, dx, dy, dvx, dvy, jfx, jfy, power);
    lanes.store(fx + i, jfx);
    lanes.store(fy + i, jfy);
    if (powerOut) lanes.store(powerOut + i, power);
    else scan.partial[(i / W) % (4 / W)] += power;
    const V opening2 = dx * dx + dy * dy;
    scan.widest = simd::select(opening2 > scan.widest, opening2, scan.widest);
    scan.notANumber |= opening2 != opening2;
  });
  if (r.last != n) return;
  fx[-1] = fx[n - 1];  // link 0's rear joint is the last one
  fy[-1] = fy[n - 1];
}

// Each link of range r: its front joint's force on its front pin, its rear joint's opposite force
// on its rear pin, and their torques about its centre.
template <int W>
CHAINDRIVE_ALWAYS_INLINE void jointGenLanes(const Model& m, Data& d, LinkRange r) {
  using V = typename simd::Lanes<W>::V;
  using simd::load;
  const int n = m.chain.links;
  const LinkArrays& L = d.links;
  const double *fx = d.joints.forceX(), *fy = d.joints.forceY();
  double *gx = d.gen.data(), *gy = gx + n, *gGamma = gx + 2 * n;
  simd::forEachVectorIn<V>(r.first, r.last, CHAINDRIVE_LANES_BODY {
    const V fFrontX = load<V>(fx + i), fFrontY = load<V>(fy + i);
    const V fRearX = load<V>(fx + i - 1), fRearY = load<V>(fy + i - 1);
    const V cx = load<V>(&L.cx[i]), cy = load<V>(&L.cy[i]);
    const V ux = load<V>(&L.frontX[i]) - cx, uy = load<V>(&L.frontY[i]) - cy;
    const V rx = load<V>(&L.rearX[i]) - cx, ry = load<V>(&L.rearY[i]) - cy;
    lanes.store(gx + i, fFrontX - fRearX);
    lanes.store(gy + i, fFrontY - fRearY);
    lanes.store(gGamma + i, (ux * fFrontY - uy * fFrontX) - (rx * fRearY - ry * fRearX));
  });
}

template <int W>
CHAINDRIVE_ALWAYS_INLINE double jointLanes(const Model& m, Data& d) {
  const LinkRange all{0, m.chain.links};
  JointScan<W> scan;
  jointForceLanes<W>(m, d, all, scan, nullptr);
  jointGenLanes<W>(m, d, all);
  d.jointOpening2 = scan.largest();
  return simd::reducePartials<W>(scan.partial);
}

// The power stored per joint summed as jointForceLanes sums it.
template <int W>
CHAINDRIVE_ALWAYS_INLINE double jointPowerLanes(const Model& m, const double* power) {
  using V = typename simd::Lanes<W>::V;
  V partial[4 / W] = {};
  for (int i = 0; i < m.chain.links; i += W) partial[(i / W) % (4 / W)] += simd::load<V>(power + i);
  return simd::reducePartials<W>(partial);
}

// Per joint its tension along the links' mean axis and its deformation (into tension and
// deformation where not null) and its elastic energy, summed: jointTension, jointDeformation and
// jointForce's energy lane by lane.
template <int W>
CHAINDRIVE_ALWAYS_INLINE double jointMeasureLanes(const Model& m, const Data& d, double* tension,
                                                  double* deformation) {
  using V = typename simd::Lanes<W>::V;
  using simd::load;
  using simd::select;
  const ChainModel& ch = m.chain;
  const LinkArrays& L = d.links;
  const double *fx = d.joints.forceX(), *fy = d.joints.forceY();
  const double halfK = 0.5 * ch.jointStiffness, clearance = ch.jointClearance;
  V partial[4 / W] = {};  // link i in sum i mod 4
  simd::forEachVector<V>(ch.links, CHAINDRIVE_LANES_BODY {
    const V dx = load<V>(&L.frontX[i]) - load<V>(&L.rearX[i + 1]);
    const V dy = load<V>(&L.frontY[i]) - load<V>(&L.rearY[i + 1]);
    const V d2 = dx * dx + dy * dy, distance = simd::sqrt(d2);
    const V pen = select(0.0 < distance - clearance, distance - clearance, V{});
    partial[(i / W) % (4 / W)] += clearance <= 0.0 ? halfK * d2 : halfK * pen * pen;  // (zero past the last)
    if (!tension) return;
    lanes.store(deformation + i, clearance <= 0.0 ? distance : pen);
    const V ex = load<V>(&L.ex[i]), ey = load<V>(&L.ey[i]);
    const V ax = ex + load<V>(&L.ex[i + 1]), ay = ey + load<V>(&L.ey[i + 1]);
    const V axisNorm = simd::sqrt(ax * ax + ay * ay), inverse = 1.0 / axisNorm;
    const V forceX = lanes.load(fx + i), forceY = lanes.load(fy + i);
    lanes.store(tension + i, select(axisNorm > 0.0, forceX * (inverse * ax) + forceY * (inverse * ay),
                                    forceX * ex + forceY * ey));
  });
  return simd::reducePartials<W>(partial);
}

// jointDampingOffDiagonalLoop: the pins' velocities under the field w = accel (levers of half a
// pitch along the link axes), each joint's force -c (front pin - rear pin of the next link), then
// per link the forces and torques of its two joints over the masses, F / M = -C w, and
// w += a (F / M + D w). In three passes over a range of links, each reading the last one's
// results of its neighbours (on several threads, a barrier between them): w copied, with the
// first link behind the last (the work area: w, then the forces with the last joint's in front);
struct DampingWork {
  double *wx, *wy, *ww, *fx, *fy;
  DampingWork(const Model& m, Data& d) {
    const int stride = m.chain.links + 1 + LinkArrays::kPadding;
    wx = d.dampingWork.data(), wy = wx + stride, ww = wy + stride, fx = ww + stride + 1, fy = fx + stride;
  }
};

}  // namespace

void dampingCopyRange(const Model& m, Data& d, const double* accel, LinkRange r) {
  const int n = m.chain.links;
  const DampingWork dw(m, d);
  for (int k = 0; k < 3; ++k) {
    double* to = (k == 0 ? dw.wx : k == 1 ? dw.wy : dw.ww);
    std::copy(accel + k * n + r.first, accel + k * n + r.last, to + r.first);
    if (r.first == 0) to[n] = to[0];
  }
}

namespace {

// the joints' forces;
template <int W>
CHAINDRIVE_ALWAYS_INLINE void dampingForceLanes(const Model& m, Data& d, LinkRange r) {
  using V = typename simd::Lanes<W>::V;
  using simd::load;
  const int n = m.chain.links;
  const LinkArrays& L = d.links;
  const double c = m.chain.jointDamping, hp = 0.5 * m.chain.pitch;
  const DampingWork dw(m, d);
  simd::forEachVectorIn<V>(r.first, r.last, CHAINDRIVE_LANES_BODY {
    const V frontX = hp * load<V>(&L.ex[i]), frontY = hp * load<V>(&L.ey[i]);  // levers: front, then rear
    const V rearX = -hp * load<V>(&L.ex[i + 1]), rearY = -hp * load<V>(&L.ey[i + 1]);
    const V omega = load<V>(dw.ww + i), next = load<V>(dw.ww + i + 1);
    const V dvx = (load<V>(dw.wx + i) - omega * frontY) - (load<V>(dw.wx + i + 1) - next * rearY);
    const V dvy = (load<V>(dw.wy + i) + omega * frontX) - (load<V>(dw.wy + i + 1) + next * rearX);
    lanes.store(dw.fx + i, -c * dvx);
    lanes.store(dw.fy + i, -c * dvy);
  });
  if (r.last != n) return;
  dw.fx[-1] = dw.fx[n - 1];
  dw.fy[-1] = dw.fy[n - 1];
}

// the links' accelerations swept.
template <int W>
CHAINDRIVE_ALWAYS_INLINE void dampingSweepLanes(const Model& m, Data& d, double a, double* accel, LinkRange r) {
  using V = typename simd::Lanes<W>::V;
  using simd::load;
  const int n = m.chain.links;
  const LinkArrays& L = d.links;
  const double c = m.chain.jointDamping, hp = 0.5 * m.chain.pitch;
  const double invM = 1.0 / m.chain.mass, invJ = 1.0 / m.chain.inertia;
  const double diagonalX = 2.0 * c * invM, diagonalGamma = 2.0 * c * hp * hp * invJ;  // (linkDampedKicks')
  const DampingWork dw(m, d);
  double *ax = accel, *ay = accel + n, *alpha = accel + 2 * n;
  simd::forEachVectorIn<V>(r.first, r.last, CHAINDRIVE_LANES_BODY {
    const V frontX = hp * load<V>(&L.ex[i]), frontY = hp * load<V>(&L.ey[i]);
    const V fFrontX = load<V>(dw.fx + i), fFrontY = load<V>(dw.fy + i);
    const V fRearX = load<V>(dw.fx + i - 1), fRearY = load<V>(dw.fy + i - 1);
    const V torque = (frontX * fFrontY - frontY * fFrontX) + (frontX * fRearY - frontY * fRearX);
    const V x = lanes.load(ax + i), y = lanes.load(ay + i), g = lanes.load(alpha + i);
    lanes.store(ax + i, x + a * ((fFrontX - fRearX) * invM + diagonalX * x));
    lanes.store(ay + i, y + a * ((fFrontY - fRearY) * invM + diagonalX * y));
    lanes.store(alpha + i, g + a * (torque * invJ + diagonalGamma * g));
  });
}

template <int W>
CHAINDRIVE_ALWAYS_INLINE void jointDampingLanes(const Model& m, Data& d, double a, double* accel) {
  const LinkRange all{0, m.chain.links};
  dampingCopyRange(m, d, accel, all);
  dampingForceLanes<W>(m, d, all);
  dampingSweepLanes<W>(m, d, a, accel, all);
}

template <int W>
CHAINDRIVE_ALWAYS_INLINE void dampedKickLanes(double a, double base, const double* extra, int n, double* kick) {
  using V = typename simd::Lanes<W>::V;
  const double undamped = a / (1.0 + a * base);
  simd::forEachVector<V>(n, CHAINDRIVE_LANES_BODY {
    const V more = extra ? lanes.load(extra + i) : V{};
    lanes.store(kick + i, simd::anySet(more != 0.0) ? a / (1.0 + a * (base + more)) : V{} + undamped);
  });
}

CHAINDRIVE_TARGET_AVX2 void kinematicsAvx2(const Model& m, Data& d, const double* y, LinkRange r) {
  kinematicsLanes<4>(m, d, y, r);
}
void kinematicsSse2(const Model& m, Data& d, const double* y, LinkRange r) { kinematicsLanes<2>(m, d, y, r); }

CHAINDRIVE_TARGET_AVX2 void dampedKickAvx2(double a, double base, const double* extra, int n, double* kick) {
  dampedKickLanes<4>(a, base, extra, n, kick);
}
void dampedKickSse2(double a, double base, const double* extra, int n, double* kick) {
  dampedKickLanes<2>(a, base, extra, n, kick);
}

CHAINDRIVE_TARGET_AVX2 double jointsAvx2(const Model& m, Data& d) { return jointLanes<4>(m, d); }
double jointsSse2(const Model& m, Data& d) { return jointLanes<2>(m, d); }

template <int W>
CHAINDRIVE_ALWAYS_INLINE double jointForcesStoring(const Model& m, Data& d, LinkRange r) {
  JointScan<W> scan;
  jointForceLanes<W>(m, d, r, scan, d.threads.jointPower.data());
  return scan.largest();
}
CHAINDRIVE_TARGET_AVX2 double jointForcesAvx2(const Model& m, Data& d, LinkRange r) {
  return jointForcesStoring<4>(m, d, r);
}
double jointForcesSse2(const Model& m, Data& d, LinkRange r) { return jointForcesStoring<2>(m, d, r); }
CHAINDRIVE_TARGET_AVX2 void jointGenAvx2(const Model& m, Data& d, LinkRange r) { jointGenLanes<4>(m, d, r); }
void jointGenSse2(const Model& m, Data& d, LinkRange r) { jointGenLanes<2>(m, d, r); }
CHAINDRIVE_TARGET_AVX2 double jointPowerAvx2(const Model& m, const double* power) {
  return jointPowerLanes<4>(m, power);
}
double jointPowerSse2(const Model& m, const double* power) { return jointPowerLanes<2>(m, power); }

CHAINDRIVE_TARGET_AVX2 void dampingForceAvx2(const Model& m, Data& d, LinkRange r) { dampingForceLanes<4>(m, d, r); }
void dampingForceSse2(const Model& m, Data& d, LinkRange r) { dampingForceLanes<2>(m, d, r); }
CHAINDRIVE_TARGET_AVX2 void dampingSweepAvx2(const Model& m, Data& d, double a, double* accel, LinkRange r) {
  dampingSweepLanes<4>(m, d, a, accel, r);
}
void dampingSweepSse2(const Model& m, Data& d, double a, double* accel, LinkRange r) {
  dampingSweepLanes<2>(m, d, a, accel, r);
}

CHAINDRIVE_TARGET_AVX2 void dampingAvx2(const Model& m, Data& d, double a, double* accel) {
  jointDampingLanes<4>(m, d, a, accel);
}
void dampingSse2(const Model& m, Data& d, double a, double* accel) { jointDampingLanes<2>(m, d, a, accel); }

CHAINDRIVE_TARGET_AVX2 double measuresAvx2(const Model& m, const Data& d, double* tension,
                                           double* deformation) {
  return jointMeasureLanes<4>(m, d, tension, deformation);
}
double measuresSse2(const Model& m, const Data& d, double* tension, double* deformation) {
  return jointMeasureLanes<2>(m, d, tension, deformation);
}

}  // namespace

int supportedVectorLanes() { return simd::hasAvx2() ? 4 : 2; }

void linkKinematicsLoop(const Model& m, Data& d, const double* y) { linkKinematicsRange(m, d, y, {0, m.chain.links}); }

void linkKinematicsRange(const Model& m, Data& d, const double* y, LinkRange r) {
  if (d.vectorLanes == 4) kinematicsAvx2(m, d, y, r);
  else kinematicsSse2(m, d, y, r);
}

double jointForcesRange(const Model& m, Data& d, LinkRange r) {
  return d.vectorLanes == 4 ? jointForcesAvx2(m, d, r) : jointForcesSse2(m, d, r);
}

void jointGenRange(const Model& m, Data& d, LinkRange r) {
  if (d.vectorLanes == 4) jointGenAvx2(m, d, r);
  else jointGenSse2(m, d, r);
}

double jointPowerSum(const Model& m, const Data& d) {
  const double* power = d.threads.jointPower.data();
  return d.vectorLanes == 4 ? jointPowerAvx2(m, power) : jointPowerSse2(m, power);
}

void dampingForceRange(const Model& m, Data& d, LinkRange r) {
  if (d.vectorLanes == 4) dampingForceAvx2(m, d, r);
  else dampingForceSse2(m, d, r);
}

void dampingSweepRange(const Model& m, Data& d, double a, double* accel, LinkRange r) {
  if (d.vectorLanes == 4) dampingSweepAvx2(m, d, a, accel, r);
  else dampingSweepSse2(m, d, a, accel, r);
}

double jointForcesLoop(const Model& m, Data& d) {
  return d.vectorLanes == 4 ? jointsAvx2(m, d) : jointsSse2(m, d);
}

void jointDampingOffDiagonalLoop(const Model& m, Data& d, double a, double* accel) {
  if (d.vectorLanes == 4) dampingAvx2(m, d, a, accel);
  else dampingSse2(m, d, a, accel);
}

double jointMeasuresLoop(const Model& m, const Data& d, double* tension, double* deformation) {
  return d.vectorLanes == 4 ? measuresAvx2(m, d, tension, deformation) : measuresSse2(m, d, tension, deformation);
}

void dampedKickLoop(double a, double base, const double* extra, int n, double* kick, int lanes) {
  if (lanes == 4) dampedKickAvx2(a, base, extra, n, kick);
  else dampedKickSse2(a, base, extra, n, kick);
}

}  // namespace chaindrive
