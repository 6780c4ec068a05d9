#include "dynamics/contact_lanes.h"

#include <algorithm>
#include <cstring>
#include <utility>

#include "dynamics/contact_kinematics.h"
#include "simd.h"

namespace chaindrive {

namespace {

// One vector of W candidates of sprocket s from index `first` (`lanes` of them real; the others
// repeat the last, and their results are dropped): the clearance bound and the tooth gap one roller
// at a time (their work is branches and a table), the frames, the seat and the world frame in
// vectors, the outline beyond the seat one roller at a time.
template <int W>
CHAINDRIVE_ALWAYS_INLINE int rollerVector(const Model& m, Data& d, int s, int first, int lanes, double margin,
                                          int count) {
  using V = typename simd::Lanes<W>::V;
  using simd::load;
  using simd::store;
  const SprocketModel& sp = m.sprockets[s];
  const int r = sp.rotor, n = m.chain.links;
  const double cosA = d.rotorCos[r], sinA = d.rotorSin[r];
  const LinkArrays& L = d.links;
  // (lane values move between vectors and arrays whole: no lane is read or written alone in a vector)
  int link[W], end[W];
  double px[W], py[W];
  for (int l = 0; l < W; ++l) {
    const int candidate = d.rollerCandidates[s * n + first + std::min(l, lanes - 1)];
    link[l] = candidate / 2;
    end[l] = candidate % 2;
    px[l] = end[l] == 0 ? L.rearX[link[l]] : L.frontX[link[l]];
    py[l] = end[l] == 0 ? L.rearY[link[l]] : L.frontY[link[l]];
  }
  double bodyX[W], bodyY[W];
  {
    V bx, by;
    roller::toSprocketFrame(load<V>(px) - sp.center.x, load<V>(py) - sp.center.y, cosA, sinA, bx, by);
    store(bodyX, bx);
    store(bodyY, by);
  }
  // the clearance bound and the tooth gap, roller by roller
  bool query[W] = {};
  int gap[W] = {};
  double gapX[W], gapY[W];
  for (int l = 0; l < W; ++l) {
    gapX[l] = 1.0;
    gapY[l] = 0.0;
    if (l >= lanes) continue;
    const Vec2 body{bodyX[l], bodyY[l]};
    const RollerHint& hint = d.rollerHints[(link[l] + end[l]) * m.sprockets.size() + s];
    ++d.rollerQueries;
    if (roller::stillClear(hint, body, margin)) {
      ++d.rollerQueriesSkipped;
      continue;
    }
    query[l] = true;
    gap[l] = roller::gapOf(sp, body, hint.gap);
    gapX[l] = sp.gapDirs[gap[l]].x;
    gapY[l] = sp.gapDirs[gap[l]].y;
  }
  if (std::none_of(query, query + W, [](bool q) { return q; })) return count;
  // the closest point of the outline: the seat in vectors, the rest roller by roller
  double localX[W], localY[W], distance[W], pointX[W], pointY[W], normalX[W], normalY[W];
  long long seated[W];
  {
    V lx, ly, dist, qx, qy, nx, ny;
    roller::toGapFrame(load<V>(bodyX), load<V>(bodyY), load<V>(gapX), load<V>(gapY), lx, ly);
    const auto within = sp.gap.seatHit(lx, ly, dist, qx, qy, nx, ny);
    for (auto [array, v] : {std::pair{localX, lx}, {localY, ly}, {distance, dist}, {pointX, qx}, {pointY, qy},
                            {normalX, nx}, {normalY, ny}})
      store(array, v);
    std::memcpy(seated, &within, sizeof seated);
  }
  bool contact[W] = {};
  for (int l = 0; l < W; ++l) {
    if (!query[l]) continue;
    if (!seated[l]) {
      const ProfileHit hit = sp.gap.closestOffSeat(Vec2{localX[l], localY[l]});
      distance[l] = hit.distance;
      pointX[l] = hit.point.x;
      pointY[l] = hit.point.y;
      normalX[l] = hit.normal.x;
      normalY[l] = hit.normal.y;
    }
    const double g = distance[l] - m.chain.rollerRadius;
    d.rollerHints[(link[l] + end[l]) * m.sprockets.size() + s] =
        RollerHint{gap[l], Vec2{bodyX[l], bodyY[l]}, g >= margin ? g : -1.0};
    contact[l] = g < margin;
  }
  if (std::none_of(contact, contact + W, [](bool c) { return c; })) return count;
  // the contacts in the world frame
  double velocityX[W], velocityY[W], linkX[W], linkY[W];
  for (int l = 0; l < W; ++l) {
    velocityX[l] = end[l] == 0 ? L.vRearX[link[l]] : L.vFrontX[link[l]];
    velocityY[l] = end[l] == 0 ? L.vRearY[link[l]] : L.vFrontY[link[l]];
    linkX[l] = L.cx[link[l]];
    linkY[l] = L.cy[link[l]];
  }
  const roller::World<V> w = roller::toWorld(
      sp.center, cosA, sinA, d.rotorRate[r], load<V>(gapX), load<V>(gapY), load<V>(pointX), load<V>(pointY),
      load<V>(normalX), load<V>(normalY), load<V>(px), load<V>(py), load<V>(velocityX), load<V>(velocityY),
      load<V>(linkX), load<V>(linkY));
  roller::World<double[W]> world;
  for (auto [array, v] : {std::pair{world.normalX, w.normalX}, {world.normalY, w.normalY},
                          {world.tangentX, w.tangentX}, {world.tangentY, w.tangentY}, {world.rLinkX, w.rLinkX},
                          {world.rLinkY, w.rLinkY}, {world.rRotorX, w.rRotorX}, {world.rRotorY, w.rRotorY},
                          {world.vN, w.vN}, {world.vT, w.vT}})
    store(array, v);
  const int cap = static_cast<int>(d.contacts.size());
  for (int l = 0; l < W && count < cap; ++l)
    if (contact[l])
      roller::setContact<W>(d.contacts[count++], link[l], end[l], s, r, distance[l] - m.chain.rollerRadius, world, l);
  return count;
}

template <int W>
CHAINDRIVE_ALWAYS_INLINE int rollerLanes(const Model& m, Data& d, int s, double margin, int count) {
  const int candidates = d.rollerCandidateCount[s];
  for (int first = 0; first < candidates; first += W)
    count = rollerVector<W>(m, d, s, first, std::min(W, candidates - first), margin, count);
  return count;
}

// One vector of W links near a guide from candidate `first` (`lanes` of them real, the others
// repeating the last) against its arc face: the tests, the facing edge and its contact with the
// arc in vectors; beyond the arc's range the corners, and the contacts, link by link.
template <int W>
CHAINDRIVE_ALWAYS_INLINE int plateVector(const Model& m, Data& d, int guide, int face, const PlacedFace& pf, int first,
                                         int lanes, double margin, double reach, int count) {
  using V = typename simd::Lanes<W>::V;
  using simd::load;
  using simd::store;
  const LinkArrays& L = d.links;
  int link[W];
  double cx[W], cy[W], ex[W], ey[W], rearX[W], rearY[W], frontX[W], frontY[W];
  for (int l = 0; l < W; ++l) {
    const int i = link[l] = d.plateCandidates[first + std::min(l, lanes - 1)];
    cx[l] = L.cx[i], cy[l] = L.cy[i], ex[l] = L.ex[i], ey[l] = L.ey[i];
    rearX[l] = L.rearX[i], rearY[l] = L.rearY[i], frontX[l] = L.frontX[i], frontY[l] = L.frontY[i];
  }
  const V px = load<V>(cx), py = load<V>(cy), axisX = load<V>(ex), axisY = load<V>(ey);
  long long near[W], within[W];
  const auto nearMask = arcface::near(pf, px, py, reach);
  std::memcpy(near, &nearMask, sizeof near);
  // the plate edge facing the arc (plateEdgeHit) and its contact with it
  const V side = arcface::side(pf, px, py, axisX, axisY);
  const V normalX = side * -axisY, normalY = side * axisX;
  const double h = m.chain.plateHalfHeight;
  const V offX = h * normalX, offY = h * normalY;
  const V e0x = load<V>(rearX) + offX, e0y = load<V>(rearY) + offY, e1x = load<V>(frontX) + offX,
          e1y = load<V>(frontY) + offY;
  double pointX[W], pointY[W], gap[W], hitNormalX[W], hitNormalY[W], r[W];
  {
    V qx, qy, g, nx, ny, distance;
    const auto arc = arcface::hit(pf, e0x, e0y, e1x, e1y, qx, qy, g, nx, ny, distance);
    for (auto [array, v] : {std::pair{pointX, qx}, {pointY, qy}, {gap, g}, {hitNormalX, nx}, {hitNormalY, ny},
                            {r, distance}})
      store(array, v);
    std::memcpy(within, &arc, sizeof within);
  }
  const GuideModel& g = m.guides[guide];
  const double rate = g.rotor >= 0 ? d.rotorRate[g.rotor] : 0.0;
  const int cap = static_cast<int>(d.contacts.size());
  for (int l = 0; l < lanes && count < cap; ++l) {
    if (!near[l] || r[l] <= 0.0) continue;
    FaceHit hit;
    if (within[l]) {
      hit.valid = true;
      hit.point = Vec2{pointX[l], pointY[l]};
      hit.gap = gap[l];
      hit.normal = Vec2{hitNormalX[l], hitNormalY[l]};
    } else {
      const double sideL = side[l];
      const Vec2 nOut = Vec2{sideL * -ey[l], sideL * ex[l]}, off = h * nOut;
      hit = nearerCorner(pf.corner0, pf.corner1, Vec2{rearX[l], rearY[l]} + off, Vec2{frontX[l], frontY[l]} + off, nOut);
    }
    if (hit.valid && hit.gap < margin) setPlateContact(m, guide, face, link[l], L[link[l]], hit, rate, d.contacts[count++]);
  }
  return count;
}

template <int W>
CHAINDRIVE_ALWAYS_INLINE int plateLanes(const Model& m, Data& d, int guide, int face, const PlacedFace& pf,
                                        double margin, double reach, int count) {
  for (int first = 0; first < d.plateCandidateCount; first += W)
    count = plateVector<W>(m, d, guide, face, pf, first, std::min(W, d.plateCandidateCount - first), margin, reach,
                           count);
  return count;
}

__attribute__((target("avx2"))) int platesAvx2(const Model& m, Data& d, int guide, int face, const PlacedFace& pf,
                                               double margin, double reach, int count) {
  return plateLanes<4>(m, d, guide, face, pf, margin, reach, count);
}
int platesSse2(const Model& m, Data& d, int guide, int face, const PlacedFace& pf, double margin, double reach,
               int count) {
  return plateLanes<2>(m, d, guide, face, pf, margin, reach, count);
}

__attribute__((target("avx2"))) int rollersAvx2(const Model& m, Data& d, int s, double margin, int count) {
  return rollerLanes<4>(m, d, s, margin, count);
}
int rollersSse2(const Model& m, Data& d, int s, double margin, int count) {
  return rollerLanes<2>(m, d, s, margin, count);
}

}  // namespace

int rollerContactsLoop(const Model& m, Data& d, int sprocket, double margin, int count) {
  return d.vectorLanes == 4 ? rollersAvx2(m, d, sprocket, margin, count) : rollersSse2(m, d, sprocket, margin, count);
}

int plateContactsLoop(const Model& m, Data& d, int guide, int face, const PlacedFace& pf, double margin, double reach,
                      int count) {
  return d.vectorLanes == 4 ? platesAvx2(m, d, guide, face, pf, margin, reach, count)
                            : platesSse2(m, d, guide, face, pf, margin, reach, count);
}

}  // namespace chaindrive
