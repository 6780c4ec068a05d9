#include "dynamics/contact_lanes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>

#include "dynamics/contact_compliant.h"
#include "dynamics/contact_kinematics.h"
#include "dynamics/link_loops.h"
#include "simd.h"

namespace chaindrive {

namespace {

// The passes run over the rollers (pins) and the links in whole vectors, their coarse tests as lane
// masks; what is left of a vector after them goes on in vectors where every lane does the same
// work, and lane by lane (from arrays the vectors are stored to whole) where lanes differ: the tooth
// gap of each roller, the outline beyond the seat, the contacts written out.

// Lanes of the vector at index i that hold one of n elements (all but in a last, partly filled one).
template <int W>
CHAINDRIVE_ALWAYS_INLINE auto lanesBelow(int i, int n) {
  typename simd::Lanes<W>::V past = {};
  if (i + W > n)
    for (int l = 0; l < W; ++l) past[l] = i + l < n ? 0.0 : 1.0;
  return past == 0.0;
}

// Calls f(i) for the first index i of every block in a window, in increasing order.
template <class F>
CHAINDRIVE_ALWAYS_INLINE void forEachBlock(const std::uint64_t* window, int words, F f) {
  for (int w = 0; w < words; ++w)
    for (std::uint64_t bits = window[w]; bits != 0; bits &= bits - 1)
      f((64 * w + __builtin_ctzll(bits)) * SearchWindows::kBlock);
}

// The largest distance by which an element of a (now) moved from b (at the last scan).
template <int W>
CHAINDRIVE_ALWAYS_INLINE double largestMove(const double* ax, const double* ay, const double* bx, const double* by,
                                            int n) {
  using V = typename simd::Lanes<W>::V;
  V largest = {}, notANumber = {};
  for (int i = 0; i < n; i += W) {  // (the padding: zeros in both)
    const V dx = simd::load<V>(ax + i) - simd::load<V>(bx + i), dy = simd::load<V>(ay + i) - simd::load<V>(by + i);
    const V d2 = dx * dx + dy * dy;
    largest = simd::select(d2 > largest, d2, largest);
    notANumber = simd::select(d2 != d2, d2, notANumber);
  }
  double out = 0.0;
  for (int l = 0; l < W; ++l) out = std::max(out, largest[l]) + notANumber[l] * 0.0;  // (NaN carried)
  return std::sqrt(out);
}

// Scans every block against every element: the windows of the elements, the positions now.
template <int W>
CHAINDRIVE_ALWAYS_INLINE void scanWindows(const Model& m, Data& d, double margin) {
  using V = typename simd::Lanes<W>::V;
  using simd::load;
  SearchWindows& sw = d.windows;
  const LinkArrays& L = d.links;
  const int n = m.chain.links, nSprockets = static_cast<int>(m.sprockets.size());
  std::fill(sw.windows.begin(), sw.windows.end(), 0);
  for (int e = 0; e < nSprockets + static_cast<int>(m.guides.size()); ++e) {
    const bool sprocket = e < nSprockets;
    const double cx = sprocket ? m.sprockets[e].center.x : d.guideBoundX[e - nSprockets];
    const double cy = sprocket ? m.sprockets[e].center.y : d.guideBoundY[e - nSprockets];
    const double radius = std::sqrt(sprocket ? m.sprockets[e].reach2 : d.guideReach2[e - nSprockets]) +
                          SearchWindows::kBand;
    std::uint64_t* window = &sw.windows[static_cast<std::size_t>(e) * sw.words];
    for (int i = 0; i < n; i += W) {
      // the rollers (pins) for a sprocket, the link centres for a guide
      const V px = sprocket ? pinLanes<W>(load<V>(&L.rearX[i]), load<V>(&L.frontX[i])) : load<V>(&L.cx[i]);
      const V py = sprocket ? pinLanes<W>(load<V>(&L.rearY[i]), load<V>(&L.frontY[i])) : load<V>(&L.cy[i]);
      const V dx = px - cx, dy = py - cy;
      const auto within = ~(dx * dx + dy * dy > radius * radius) & lanesBelow<W>(i, n);  // (NaN: within)
      if (!simd::anySet(within)) continue;
      const int block = i / SearchWindows::kBlock;
      window[block / 64] |= std::uint64_t{1} << (block % 64);
    }
  }
  std::copy(L.cx.begin(), L.cx.end(), sw.centerX.begin());
  std::copy(L.cy.begin(), L.cy.end(), sw.centerY.begin());
  std::copy(L.ex.begin(), L.ex.end(), sw.axisX.begin());
  std::copy(L.ey.begin(), L.ey.end(), sw.axisY.begin());
  std::copy(d.guideBoundX.begin(), d.guideBoundX.end(), sw.boundX.begin());
  std::copy(d.guideBoundY.begin(), d.guideBoundY.end(), sw.boundY.begin());
  sw.margin = margin;
  sw.valid = true;
}

// Keeps the windows while nothing moved further than the band since the last scan, else scans.
// A pin half a pitch from its link's centre moves by at most the centre's move and half a pitch
// times its axis' move.
template <int W>
CHAINDRIVE_ALWAYS_INLINE void windowLanes(const Model& m, Data& d, double margin) {
  SearchWindows& sw = d.windows;
  const LinkArrays& L = d.links;
  const int n = m.chain.links;
  const double allowed = SearchWindows::kBand - 1e-9;  // (a nanometre for the rounding of the moves)
  bool keep = sw.valid && sw.margin == margin;
  if (keep) {
    const double centers = largestMove<W>(L.cx.data(), L.cy.data(), sw.centerX.data(), sw.centerY.data(), n);
    const double axes = largestMove<W>(L.ex.data(), L.ey.data(), sw.axisX.data(), sw.axisY.data(), n);
    keep = centers + 0.5 * m.chain.pitch * axes <= allowed;
    for (std::size_t g = 0; g < m.guides.size() && keep; ++g)
      keep = centers + std::hypot(d.guideBoundX[g] - sw.boundX[g], d.guideBoundY[g] - sw.boundY[g]) <= allowed;
  }
  if (!keep) scanWindows<W>(m, d, margin);
}

// Sprocket s against the W rollers (pins) from pin j.
// Counts of the rollers near a sprocket and of those the clearance bound skipped, lane by lane.
template <int W>
struct Tally {
  typename simd::Lanes<W>::Mask near = {}, skipped = {};
};

template <int W>
CHAINDRIVE_ALWAYS_INLINE int rollerVector(const Model& m, Data& d, int s, int j, double margin, bool forces, int count,
                                          double& power, Tally<W>& tally) {
  using V = typename simd::Lanes<W>::V;
  using simd::load;
  using simd::store;
  const SprocketModel& sp = m.sprockets[s];
  const LinkArrays& L = d.links;
  const V rollerX = pinLanes<W>(load<V>(&L.rearX[j]), load<V>(&L.frontX[j]));
  const V rollerY = pinLanes<W>(load<V>(&L.rearY[j]), load<V>(&L.frontY[j]));
  const V ax = rollerX - sp.center.x, ay = rollerY - sp.center.y;
  const auto near = ~(ax * ax + ay * ay > sp.reach2) & lanesBelow<W>(j, m.chain.links);  // (NaN: near)
  if (!simd::anySet(near)) return count;
  // the roller centres in the sprocket's frame; the clearance bound of the last query
  const int r = sp.rotor;
  const double cosA = d.rotorCos[r], sinA = d.rotorSin[r];
  V bodyX, bodyY;
  roller::toSprocketFrame(ax, ay, cosA, sinA, bodyX, bodyY);
  RollerHints& hints = d.rollerHints;
  const int h = hints.index(s, j);
  const V free = (load<V>(&hints.clearance[h]) - margin) - roller::kClearanceReserve;
  const V movedX = bodyX - load<V>(&hints.bodyX[h]), movedY = bodyY - load<V>(&hints.bodyY[h]);
  const auto clear = (free > 0.0) & (movedX * movedX + movedY * movedY < free * free);
  const auto queryMask = near & ~clear;
  tally.near -= near;  // (a set lane is -1)
  tally.skipped -= near & clear;
  if (!simd::anySet(queryMask)) return count;
  // the lanes queried, listed (no branch per lane), and the tooth gap of each (a walk from the last
  // one where it moved on)
  int query[W], queries = 0;
  {
    long long lane[W];
    std::memcpy(lane, &queryMask, sizeof lane);
    for (int l = 0; l < W; ++l) {
      query[queries] = l;
      queries += lane[l] != 0;
    }
  }
  double body[2][W], gapX[W], gapY[W];
  store(body[0], bodyX);
  store(body[1], bodyY);
  int gap[W] = {};
  for (int l = 0; l < W; ++l) gapX[l] = 1.0, gapY[l] = 0.0;
  for (int q = 0; q < queries; ++q) {
    const int l = query[q];
    gap[l] = roller::gapOf(sp, Vec2{body[0][l], body[1][l]}, hints.gap[h + l]);
    gapX[l] = sp.gapDirs[gap[l]].x;
    gapY[l] = sp.gapDirs[gap[l]].y;
  }
  // the closest point of the outline: the seat in vectors, the rest roller by roller
  double localX[W], localY[W], distance[W], pointX[W], pointY[W], normalX[W], normalY[W];
  long long seated[W];
  {
    V lx, ly, dist, qx, qy, nx, ny;
    roller::toGapFrame(bodyX, bodyY, load<V>(gapX), load<V>(gapY), lx, ly);
    const auto within = sp.gap.seatHit(lx, ly, dist, qx, qy, nx, ny);
    for (auto [array, v] : {std::pair{localX, lx}, {localY, ly}, {distance, dist}, {pointX, qx}, {pointY, qy},
                            {normalX, nx}, {normalY, ny}})
      store(array, v);
    std::memcpy(seated, &within, sizeof seated);
  }
  int contact[W], contacts = 0;
  for (int q = 0; q < queries; ++q) {
    const int l = query[q];
    if (!seated[l]) {
      const ProfileHit hit = sp.gap.closestOffSeat(Vec2{localX[l], localY[l]});
      distance[l] = hit.distance, pointX[l] = hit.point.x, pointY[l] = hit.point.y;
      normalX[l] = hit.normal.x, normalY[l] = hit.normal.y;
    }
    const double g = distance[l] - m.chain.rollerRadius;
    hints.gap[h + l] = gap[l];
    hints.bodyX[h + l] = body[0][l];
    hints.bodyY[h + l] = body[1][l];
    hints.clearance[h + l] = g >= margin ? g : -1.0;
    contact[contacts] = l;
    contacts += g < margin;
  }
  if (contacts == 0) return count;
  // the contacts in the world frame
  const roller::World<V> w = roller::toWorld(
      sp.center, cosA, sinA, d.rotorRate[r], load<V>(gapX), load<V>(gapY), load<V>(pointX), load<V>(pointY),
      load<V>(normalX), load<V>(normalY), rollerX, rollerY,
      pinLanes<W>(load<V>(&L.vRearX[j]), load<V>(&L.vFrontX[j])),
      pinLanes<W>(load<V>(&L.vRearY[j]), load<V>(&L.vFrontY[j])), pinLanes<W>(load<V>(&L.cx[j]), load<V>(&L.cx[j])),
      pinLanes<W>(load<V>(&L.cy[j]), load<V>(&L.cy[j])));
  roller::World<double[W]> world;
  for (auto [array, v] : {std::pair{world.normalX, w.normalX}, {world.normalY, w.normalY},
                          {world.tangentX, w.tangentX}, {world.tangentY, w.tangentY}, {world.rLinkX, w.rLinkX},
                          {world.rLinkY, w.rLinkY}, {world.rRotorX, w.rRotorX}, {world.rRotorY, w.rRotorY},
                          {world.vN, w.vN}, {world.vT, w.vT}})
    store(array, v);
  // their forces by the compliant law, in vectors
  double fN[W], fT[W], dissipated[W], damping[3][W];
  if (forces) {
    const V gapV = load<V>(distance) - m.chain.rollerRadius;
    V normal, friction, p, rateX, rateY, rateGamma;
    contactLaw(m.rollerSprocket, m.frictionRegularization, gapV, w.vN, w.vT, normal, friction, p);
    contactDampingRates(m, m.rollerSprocket, gapV, normal, w.vT, w.normalX, w.normalY, w.tangentX, w.tangentY,
                        w.rLinkX, w.rLinkY, rateX, rateY, rateGamma);
    for (auto [array, v] : {std::pair{fN, normal}, {fT, friction}, {dissipated, p}, {damping[0], rateX},
                            {damping[1], rateY}, {damping[2], rateGamma}})
      store(array, v);
  }
  const int cap = static_cast<int>(d.contacts.size());
  for (int k = 0; k < contacts && count < cap; ++k) {
    const int l = contact[k], pin = j + l, link = pin - pin % 2;  // (the roller's inner link: the even one)
    ContactPoint& c = d.contacts[count++];
    roller::setContact<W>(c, link, pin % 2, s, r, distance[l] - m.chain.rollerRadius, world, l);
    if (!forces) continue;
    c.fN = fN[l];
    c.fT = fT[l];
    addContactGen(m, c, d.gen.data());
    power += dissipated[l];
    for (int c3 = 0; c3 < 3; ++c3) d.contactDamping[m.linkGen(link, c3)] += damping[c3][l];
  }
  return count;
}

template <int W>
CHAINDRIVE_ALWAYS_INLINE int rollerLanes(const Model& m, Data& d, int s, double margin, bool forces, int count,
                                         double& power) {
  Tally<W> tally;
  forEachBlock(d.windows.sprocketWindow(s), d.windows.words, [&](int first) __attribute__((always_inline)) {
    for (int j = first; j < first + SearchWindows::kBlock && j < m.chain.links; j += W)
      count = rollerVector<W>(m, d, s, j, margin, forces, count, power, tally);
  });
  for (int l = 0; l < W; ++l) {
    d.rollerQueries += tally.near[l];
    d.rollerQueriesSkipped += tally.skipped[l];
  }
  return count;
}

// Arc face `face` of guide `guide` (placed: pf) against the W links from link i (those within the
// guide's bounding circle grown by twice `reach`, and near the face).
template <int W>
CHAINDRIVE_ALWAYS_INLINE int plateVector(const Model& m, Data& d, int guide, int face, const PlacedFace& pf, int i,
                                         double margin, double reach, bool forces, int count, double& power) {
  using V = typename simd::Lanes<W>::V;
  using simd::load;
  using simd::store;
  const LinkArrays& L = d.links;
  const V px = load<V>(&L.cx[i]), py = load<V>(&L.cy[i]);
  const V bx = px - d.guideBoundX[guide], by = py - d.guideBoundY[guide];
  const auto withinBound = ~(bx * bx + by * by > d.guideReach2[guide]) & lanesBelow<W>(i, m.chain.links);
  if (!simd::anySet(withinBound)) return count;
  const auto near = withinBound & arcface::near(pf, px, py, reach);
  if (!simd::anySet(near)) return count;
  // the plate edge facing the arc (plateEdgeHit) and its contact with it
  const V axisX = load<V>(&L.ex[i]), axisY = load<V>(&L.ey[i]);
  const V side = arcface::side(pf, px, py, axisX, axisY);
  const V normalX = side * -axisY, normalY = side * axisX;
  const double h = m.chain.plateHalfHeight;
  const V offX = h * normalX, offY = h * normalY;
  double edge[4][W], pointX[W], pointY[W], gap[W], hitNormalX[W], hitNormalY[W], r[W];
  long long nearLane[W], within[W];
  {
    const V e0x = load<V>(&L.rearX[i]) + offX, e0y = load<V>(&L.rearY[i]) + offY;
    const V e1x = load<V>(&L.frontX[i]) + offX, e1y = load<V>(&L.frontY[i]) + offY;
    V qx, qy, g, nx, ny, distance;
    const auto arc = arcface::hit(pf, e0x, e0y, e1x, e1y, qx, qy, g, nx, ny, distance);
    for (auto [array, v] : {std::pair{edge[0], e0x}, {edge[1], e0y}, {edge[2], e1x}, {edge[3], e1y}, {pointX, qx},
                            {pointY, qy}, {gap, g}, {hitNormalX, nx}, {hitNormalY, ny}, {r, distance}})
      store(array, v);
    std::memcpy(within, &arc, sizeof within);
    std::memcpy(nearLane, &near, sizeof nearLane);
  }
  double outX[W], outY[W];
  store(outX, normalX);
  store(outY, normalY);
  const GuideModel& g = m.guides[guide];
  const double rate = g.rotor >= 0 ? d.rotorRate[g.rotor] : 0.0;
  const int cap = static_cast<int>(d.contacts.size());
  for (int l = 0; l < W && count < cap; ++l) {
    if (!nearLane[l] || r[l] <= 0.0) continue;
    FaceHit hit;
    if (within[l]) {
      hit.valid = true;
      hit.point = Vec2{pointX[l], pointY[l]};
      hit.gap = gap[l];
      hit.normal = Vec2{hitNormalX[l], hitNormalY[l]};
    } else {  // beyond the arc's range: its end corners
      hit = nearerCorner(pf.corner0, pf.corner1, Vec2{edge[0][l], edge[1][l]}, Vec2{edge[2][l], edge[3][l]},
                         Vec2{outX[l], outY[l]});
    }
    if (!hit.valid || hit.gap >= margin) continue;
    ContactPoint& c = d.contacts[count++];
    setPlateContact(m, guide, face, i + l, L[i + l], hit, rate, c);
    if (forces) power += addCompliantForce(m, m.plateGuide, c, d);
  }
  return count;
}

template <int W>
CHAINDRIVE_ALWAYS_INLINE int plateLanes(const Model& m, Data& d, int guide, int face, const PlacedFace& pf,
                                        double margin, double reach, bool forces, int count, double& power) {
  forEachBlock(d.windows.guideWindow(static_cast<int>(m.sprockets.size()), guide), d.windows.words,
               [&](int first) __attribute__((always_inline)) {
    for (int i = first; i < first + SearchWindows::kBlock && i < m.chain.links; i += W)
      count = plateVector<W>(m, d, guide, face, pf, i, margin, reach, forces, count, power);
  });
  return count;
}

__attribute__((target("avx2"))) int rollersAvx2(const Model& m, Data& d, int s, double margin, bool forces, int count,
                                                double& power) {
  return rollerLanes<4>(m, d, s, margin, forces, count, power);
}
int rollersSse2(const Model& m, Data& d, int s, double margin, bool forces, int count, double& power) {
  return rollerLanes<2>(m, d, s, margin, forces, count, power);
}

__attribute__((target("avx2"))) int platesAvx2(const Model& m, Data& d, int guide, int face, const PlacedFace& pf,
                                               double margin, double reach, bool forces, int count, double& power) {
  return plateLanes<4>(m, d, guide, face, pf, margin, reach, forces, count, power);
}
int platesSse2(const Model& m, Data& d, int guide, int face, const PlacedFace& pf, double margin, double reach,
               bool forces, int count, double& power) {
  return plateLanes<2>(m, d, guide, face, pf, margin, reach, forces, count, power);
}

__attribute__((target("avx2"))) void windowsAvx2(const Model& m, Data& d, double margin) { windowLanes<4>(m, d, margin); }
void windowsSse2(const Model& m, Data& d, double margin) { windowLanes<2>(m, d, margin); }

}  // namespace

void updateSearchWindows(const Model& m, Data& d, double margin) {
  if (d.vectorLanes == 4) windowsAvx2(m, d, margin);
  else windowsSse2(m, d, margin);
}

int rollerContactsLoop(const Model& m, Data& d, int sprocket, double margin, bool forces, int count, double& power) {
  return d.vectorLanes == 4 ? rollersAvx2(m, d, sprocket, margin, forces, count, power)
                            : rollersSse2(m, d, sprocket, margin, forces, count, power);
}

int plateContactsLoop(const Model& m, Data& d, int guide, int face, const PlacedFace& pf, double margin, double reach,
                      bool forces, int count, double& power) {
  return d.vectorLanes == 4 ? platesAvx2(m, d, guide, face, pf, margin, reach, forces, count, power)
                            : platesSse2(m, d, guide, face, pf, margin, reach, forces, count, power);
}

}  // namespace chaindrive
