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
CHAINDRIVE_ALWAYS_INLINE void kinematicsLanes(const Model& m, Data& d, const double* y) {
  using V = typename simd::Lanes<W>::V;
  const int n = m.chain.links;
  LinkArrays& L = d.links;
  const double halfPitch = 0.5 * m.chain.pitch;
  const double *x = y, *yy = y + n, *gamma = y + 2 * n, *vx = y + 3 * n, *vy = y + 4 * n, *w = y + 5 * n;
  simd::forEachVector<V>(n, CHAINDRIVE_LANES_BODY {
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
  L.rearX[n] = L.rearX[0];
  L.rearY[n] = L.rearY[0];
  L.vRearX[n] = L.vRearX[0];
  L.vRearY[n] = L.vRearY[0];
  L.ex[n] = L.ex[0];
  L.ey[n] = L.ey[0];
}

template <int W>
CHAINDRIVE_ALWAYS_INLINE double jointLanes(const Model& m, Data& d) {
  using V = typename simd::Lanes<W>::V;
  using Mask = typename simd::Lanes<W>::Mask;
  using simd::load;
  const int n = m.chain.links;
  const LinkArrays& L = d.links;
  double *fx = d.joints.forceX(), *fy = d.joints.forceY();
  // joint i: link i's front pin against link i + 1's rear pin
  V partial[4 / W] = {};  // the power in four partial sums: link i in sum i mod 4
  V widest = {};
  Mask notANumber = {};
  simd::forEachVector<V>(n, CHAINDRIVE_LANES_BODY {
    const V dx = load<V>(&L.frontX[i]) - load<V>(&L.rearX[i + 1]);
    const V dy = load<V>(&L.frontY[i]) - load<V>(&L.rearY[i + 1]);
    const V dvx = load<V>(&L.vFrontX[i]) - load<V>(&L.vRearX[i + 1]);
    const V dvy = load<V>(&L.vFrontY[i]) - load<V>(&L.vRearY[i + 1]);
    V jfx, jfy, power;
    journalBearing(m.chain, dx, dy, dvx, dvy, jfx, jfy, power);
    lanes.store(fx + i, jfx);
    lanes.store(fy + i, jfy);
    partial[(i / W) % (4 / W)] += power;
    const V opening2 = dx * dx + dy * dy;
    widest = simd::select(opening2 > widest, opening2, widest);
    notANumber |= opening2 != opening2;
  });
  fx[-1] = fx[n - 1];  // link 0's rear joint is the last one
  fy[-1] = fy[n - 1];
  // each link: its front joint's force on its front pin, its rear joint's opposite force on its
  // rear pin, and their torques about its centre
  double *gx = d.gen.data(), *gy = gx + n, *gGamma = gx + 2 * n;
  simd::forEachVector<V>(n, CHAINDRIVE_LANES_BODY {
    const V fFrontX = load<V>(fx + i), fFrontY = load<V>(fy + i);
    const V fRearX = load<V>(fx + i - 1), fRearY = load<V>(fy + i - 1);
    const V cx = load<V>(&L.cx[i]), cy = load<V>(&L.cy[i]);
    const V ux = load<V>(&L.frontX[i]) - cx, uy = load<V>(&L.frontY[i]) - cy;
    const V rx = load<V>(&L.rearX[i]) - cx, ry = load<V>(&L.rearY[i]) - cy;
    lanes.store(gx + i, fFrontX - fRearX);
    lanes.store(gy + i, fFrontY - fRearY);
    lanes.store(gGamma + i, (ux * fFrontY - uy * fFrontX) - (rx * fRearY - ry * fRearX));
  });
  double sums[4], largest = 0.0;
  bool nan = false;
  for (int h = 0; h < 4 / W; ++h)
    for (int l = 0; l < W; ++l) sums[h * W + l] = partial[h][l];
  for (int l = 0; l < W; ++l) {
    largest = widest[l] > largest ? widest[l] : largest;
    nan |= notANumber[l] != 0;
  }
  d.jointOpening2 = nan ? std::nan("") : largest;
  return simd::reduce4(sums);
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
  double sums[4];
  for (int h = 0; h < 4 / W; ++h)
    for (int l = 0; l < W; ++l) sums[h * W + l] = partial[h][l];
  return simd::reduce4(sums);
}

// jointDampingOffDiagonalLoop: the pins' velocities under the field w = accel (levers of half a
// pitch along the link axes), each joint's force -c (front pin - rear pin of the next link), then
// per link the forces and torques of its two joints over the masses, F / M = -C w, and
// w += a (F / M + D w).
template <int W>
CHAINDRIVE_ALWAYS_INLINE void jointDampingLanes(const Model& m, Data& d, double a, double* accel) {
  using V = typename simd::Lanes<W>::V;
  using simd::load;
  const int n = m.chain.links, stride = n + 1 + LinkArrays::kPadding;
  const LinkArrays& L = d.links;
  const double c = m.chain.jointDamping, hp = 0.5 * m.chain.pitch;
  const double invM = 1.0 / m.chain.mass, invJ = 1.0 / m.chain.inertia;
  const double diagonalX = 2.0 * c * invM, diagonalGamma = 2.0 * c * hp * hp * invJ;  // (linkDampedKicks')
  // w copied with the first link behind the last, and the forces with the last joint's in front
  double *wx = d.dampingWork.data(), *wy = wx + stride, *ww = wy + stride, *fx = ww + stride + 1, *fy = fx + stride;
  for (int k = 0; k < 3; ++k) {
    double* to = wx + k * stride;
    std::copy(accel + k * n, accel + (k + 1) * n, to);
    to[n] = to[0];
  }
  simd::forEachVector<V>(n, CHAINDRIVE_LANES_BODY {
    const V frontX = hp * load<V>(&L.ex[i]), frontY = hp * load<V>(&L.ey[i]);  // levers: front, then rear
    const V rearX = -hp * load<V>(&L.ex[i + 1]), rearY = -hp * load<V>(&L.ey[i + 1]);
    const V omega = load<V>(ww + i), next = load<V>(ww + i + 1);
    const V dvx = (load<V>(wx + i) - omega * frontY) - (load<V>(wx + i + 1) - next * rearY);
    const V dvy = (load<V>(wy + i) + omega * frontX) - (load<V>(wy + i + 1) + next * rearX);
    lanes.store(fx + i, -c * dvx);
    lanes.store(fy + i, -c * dvy);
  });
  fx[-1] = fx[n - 1];
  fy[-1] = fy[n - 1];
  double *ax = accel, *ay = accel + n, *alpha = accel + 2 * n;
  simd::forEachVector<V>(n, CHAINDRIVE_LANES_BODY {
    const V frontX = hp * load<V>(&L.ex[i]), frontY = hp * load<V>(&L.ey[i]);
    const V fFrontX = load<V>(fx + i), fFrontY = load<V>(fy + i), fRearX = load<V>(fx + i - 1), fRearY = load<V>(fy + i - 1);
    const V torque = (frontX * fFrontY - frontY * fFrontX) + (frontX * fRearY - frontY * fRearX);
    const V x = lanes.load(ax + i), y = lanes.load(ay + i), g = lanes.load(alpha + i);
    lanes.store(ax + i, x + a * ((fFrontX - fRearX) * invM + diagonalX * x));
    lanes.store(ay + i, y + a * ((fFrontY - fRearY) * invM + diagonalX * y));
    lanes.store(alpha + i, g + a * (torque * invJ + diagonalGamma * g));
  });
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

CHAINDRIVE_TARGET_AVX2 void kinematicsAvx2(const Model& m, Data& d, const double* y) {
  kinematicsLanes<4>(m, d, y);
}
void kinematicsSse2(const Model& m, Data& d, const double* y) { kinematicsLanes<2>(m, d, y); }

CHAINDRIVE_TARGET_AVX2 void dampedKickAvx2(double a, double base, const double* extra, int n, double* kick) {
  dampedKickLanes<4>(a, base, extra, n, kick);
}
void dampedKickSse2(double a, double base, const double* extra, int n, double* kick) {
  dampedKickLanes<2>(a, base, extra, n, kick);
}

CHAINDRIVE_TARGET_AVX2 double jointsAvx2(const Model& m, Data& d) { return jointLanes<4>(m, d); }
double jointsSse2(const Model& m, Data& d) { return jointLanes<2>(m, d); }

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

void linkKinematicsLoop(const Model& m, Data& d, const double* y) {
  if (d.vectorLanes == 4) kinematicsAvx2(m, d, y);
  else kinematicsSse2(m, d, y);
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
