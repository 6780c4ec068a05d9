// The 4-lane vectors are always inlined into the AVX2 functions: GCC's note that passing them
// between functions compiled without AVX would change the ABI does not apply.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

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

// Calls f(i) for the first index i of every block in a window (and in `mine`, where not null: a
// thread's blocks), in increasing order.
template <class F>
CHAINDRIVE_ALWAYS_INLINE void forEachBlock(const std::uint64_t* window, const std::uint64_t* mine, int words, F f) {
  for (int w = 0; w < words; ++w)
    for (std::uint64_t bits = window[w] & (mine ? mine[w] : ~std::uint64_t{0}); bits != 0; bits &= bits - 1)
      f((64 * w + __builtin_ctzll(bits)) * SearchWindows::kBlock);
}

// The largest squared distances by which the centre and the axis of a link in range r moved since
// the last scan, and whether one was NaN, into `moves` (with what it holds), in one pass.
template <int W>
CHAINDRIVE_ALWAYS_INLINE void largestMoves(const LinkArrays& L, const SearchWindows& sw, LinkRange r, LinkMoves& moves) {
  using V = typename simd::Lanes<W>::V;
  using simd::load;
  V center2 = {}, axis2 = {}, notANumber = {};
  for (int i = r.first; i < r.last; i += W) {  // (the padding: zeros in both)
    const V cx = load<V>(&L.cx[i]) - load<V>(&sw.centerX[i]), cy = load<V>(&L.cy[i]) - load<V>(&sw.centerY[i]);
    const V ax = load<V>(&L.ex[i]) - load<V>(&sw.axisX[i]), ay = load<V>(&L.ey[i]) - load<V>(&sw.axisY[i]);
    const V c2 = cx * cx + cy * cy, a2 = ax * ax + ay * ay;
    center2 = simd::select(c2 > center2, c2, center2);
    axis2 = simd::select(a2 > axis2, a2, axis2);
    notANumber = simd::select(c2 + a2 != c2 + a2, c2 + a2, notANumber);
  }
  for (int l = 0; l < W; ++l) {
    moves.center2 = std::max(moves.center2, center2[l]);
    moves.axis2 = std::max(moves.axis2, axis2[l]);
    moves.nan |= notANumber[l] != 0.0;
  }
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

}  // namespace

// Keeps the windows while nothing moved further than the band since the last scan, else scans.
// A pin half a pitch from its link's centre moves by at most the centre's move and half a pitch
// times its axis' move.

bool windowsKept(const Model& m, const Data& d, double margin, const LinkMoves& moves) {
  const SearchWindows& sw = d.windows;
  const double allowed = SearchWindows::kBand - 1e-9;  // (a nanometre for the rounding of the moves)
  if (!sw.valid || sw.margin != margin || moves.nan) return false;
  const double centers = std::sqrt(moves.center2), axes = std::sqrt(moves.axis2);
  bool keep = centers + 0.5 * m.chain.pitch * axes <= allowed;
  for (std::size_t g = 0; g < m.guides.size() && keep; ++g)
    keep = centers + norm(Vec2{d.guideBoundX[g] - sw.boundX[g], d.guideBoundY[g] - sw.boundY[g]}) <= allowed;
  return keep;
}

namespace {

template <int W>
CHAINDRIVE_ALWAYS_INLINE void windowLanes(const Model& m, Data& d, double margin) {
  LinkMoves moves;
  if (d.windows.valid && d.windows.margin == margin) largestMoves<W>(d.links, d.windows, {0, m.chain.links}, moves);
  if (!windowsKept(m, d, margin, moves)) scanWindows<W>(m, d, margin);
}

// What a sprocket's pass sums lane by lane: the rollers near it and those the clearance bound
// skipped; the contacts' torque on it and their dissipated power, in four partial sums (pin j in
// sum j mod 4: the same sums whatever the vector width), combined in one order at the end; the
// deepest gap.
template <int W>
struct Sums {
  typename simd::Lanes<W>::Mask near = {}, skipped = {};
  typename simd::Lanes<W>::V torque[4 / W] = {}, power[4 / W] = {}, deepest = {};
};

// Lanes l and l + 1 (a link's two rollers) added in both: the sums per even link.
template <class V>
CHAINDRIVE_ALWAYS_INLINE V pairSums(V v) {
  return v + simd::swapPairs(v);
}

// The tooth gap of each queried roller, into the hints from h: the gap of its last query while it
// is still in that gap's sector (gapOf's two cross products, in vectors), else walked to lane by
// lane (a roller moves on to the next gap once per tooth).
template <int W, class V, class Mask>
CHAINDRIVE_ALWAYS_INLINE void updateGaps(const SprocketModel& sp, RollerHints& hints, int h, Mask query, V bodyX,
                                         V bodyY) {
  using simd::load;
  const auto stays = (load<V>(&hints.fromX[h]) * bodyY - load<V>(&hints.fromY[h]) * bodyX >= 0.0) &
                     (bodyX * load<V>(&hints.toY[h]) - bodyY * load<V>(&hints.toX[h]) > 0.0);  // (NaN: none)
  const Mask movedOn = query & ~stays;
  if (!simd::anySet(movedOn)) return;
  for (int l = 0; l < W; ++l)
    if (movedOn[l]) hints.setGap(h + l, sp, roller::gapOf(sp, Vec2{bodyX[l], bodyY[l]}, hints.gap[h + l]));
}

// The outline's closest point to each queried roller at (lx, ly) in its gap's frame: the seat in
// vectors, the rest of the outline (flanks, tip: rollers entering or leaving) lane by lane.
template <int W, class V, class Mask>
CHAINDRIVE_ALWAYS_INLINE void closestPoints(const ToothGap& gap, Mask query, V lx, V ly, V& distance, V& pointX,
                                            V& pointY, V& normalX, V& normalY) {
  const Mask offSeat = query & ~gap.seatHit(lx, ly, distance, pointX, pointY, normalX, normalY);
  if (!simd::anySet(offSeat)) return;
  for (int l = 0; l < W; ++l)
    if (offSeat[l]) {
      const ProfileHit hit = gap.closestOffSeat(Vec2{lx[l], ly[l]});
      distance[l] = hit.distance, pointX[l] = hit.point.x, pointY[l] = hit.point.y;
      normalX[l] = hit.normal.x, normalY[l] = hit.normal.y;
    }
}

// The contacts' forces by the compliant law (zero in the lanes not touching): their generalized
// forces on the even links (a link's two rollers summed), their torque on the sprocket and their
// power into the sums (Split: stored per pin at hint h, for rollerSumLanes).
template <int W, bool Split, class V, class Mask>
CHAINDRIVE_ALWAYS_INLINE void rollerForces(const Model& m, Data& d, int j, int h, Mask touching, V gap,
                                           const roller::World<V>& w, V& normal, V& friction, Sums<W>& sums) {
  const V zero{};  // (selected, not multiplied: the lanes not queried hold anything, NaN too)
  V power;
  contactLaw(m.rollerSprocket, gap, w.vN, w.vT, regularisedSliding(m.frictionRegularization, w.vT), normal, friction,
             power);
  const V fx = simd::select(touching, normal * w.normalX + friction * w.tangentX, zero);
  const V fy = simd::select(touching, normal * w.normalY + friction * w.tangentY, zero);
  const V torque = simd::select(touching, w.rRotorX * fy - w.rRotorY * fx, zero);
  if constexpr (Split) {
    simd::store(&d.threads.pinTorque[h], torque);
    simd::store(&d.threads.pinPower[h], simd::select(touching, power, zero));
  } else {
    const int part = (j / W) % (4 / W);
    sums.torque[part] += torque;
    sums.power[part] += simd::select(touching, power, zero);
  }
  sums.deepest = simd::select(touching & (gap < sums.deepest), gap, sums.deepest);
  double per[3][W];
  for (auto [array, v] : {std::pair{per[0], pairSums(fx)}, {per[1], pairSums(fy)},
                          {per[2], pairSums(w.rLinkX * fy - w.rLinkY * fx)}})
    simd::store(array, v);
  for (int l = 0; l < W && j + l < m.chain.links; l += 2)  // (per[.][l]: link j + l's)
    for (int k = 0; k < 3; ++k) d.gen[m.linkGen(j + l, k)] += per[k][l];
}

// The touching lanes' contacts written out from d.contacts[count], in lane order; the new count.
template <int W, class V, class Mask>
CHAINDRIVE_ALWAYS_INLINE int listRollerContacts(Data& d, int s, int rotor, int j, Mask touching, V gap,
                                                const roller::World<V>& w, V normal, V friction, int count) {
  roller::World<double[W]> world;
  double gaps[W], fN[W], fT[W];
  for (auto [array, v] : {std::pair{world.normalX, w.normalX}, {world.normalY, w.normalY},
                          {world.tangentX, w.tangentX}, {world.tangentY, w.tangentY}, {world.rLinkX, w.rLinkX},
                          {world.rLinkY, w.rLinkY}, {world.rRotorX, w.rRotorX}, {world.rRotorY, w.rRotorY},
                          {world.vN, w.vN}, {world.vT, w.vT}, {gaps, gap}, {fN, normal}, {fT, friction}})
    simd::store(array, v);
  const int cap = static_cast<int>(d.contacts.size());
  for (int l = 0; l < W && count < cap; ++l) {
    if (!touching[l]) continue;
    const int pin = j + l;  // (the roller's inner link: the even one)
    ContactPoint& c = d.contacts[count++];
    roller::setContact<W>(c, pin - pin % 2, pin % 2, s, rotor, gaps[l], world, l);
    c.fN = fN[l];
    c.fT = fT[l];
  }
  return count;
}

// Sprocket s against the W rollers (pins) from pin j. (Split: their torque and power stored, zero
// unless touching.)
template <int W, bool Split>
CHAINDRIVE_ALWAYS_INLINE int rollerVector(const Model& m, Data& d, int s, int j, double margin, bool forces, int count,
                                          Sums<W>& sums) {
  using V = typename simd::Lanes<W>::V;
  using Mask = typename simd::Lanes<W>::Mask;
  using simd::load;
  RollerHints& hints = d.rollerHints;
  const int h = hints.index(s, j);
  if constexpr (Split) {
    simd::store(&d.threads.pinTorque[h], V{});
    simd::store(&d.threads.pinPower[h], V{});
  }
  const SprocketModel& sp = m.sprockets[s];
  const LinkArrays& L = d.links;
  const V rollerX = pinLanes<W>(load<V>(&L.rearX[j]), load<V>(&L.frontX[j]));
  const V rollerY = pinLanes<W>(load<V>(&L.rearY[j]), load<V>(&L.frontY[j]));
  const V ax = rollerX - sp.center.x, ay = rollerY - sp.center.y;
  const Mask near = ~(ax * ax + ay * ay > sp.reach2) & lanesBelow<W>(j, m.chain.links);  // (NaN: near)
  if (!simd::anySet(near)) return count;
  // the roller centres in the sprocket's frame; the clearance bound of the last query
  const int r = sp.rotor;
  const double cosA = d.rotorCos[r], sinA = d.rotorSin[r];
  V bodyX, bodyY;
  roller::toSprocketFrame(ax, ay, cosA, sinA, bodyX, bodyY);
  const V free = (load<V>(&hints.clearance[h]) - margin) - roller::kClearanceReserve;
  const V movedX = bodyX - load<V>(&hints.bodyX[h]), movedY = bodyY - load<V>(&hints.bodyY[h]);
  const Mask clear = (free > 0.0) & (movedX * movedX + movedY * movedY < free * free);
  const Mask query = near & ~clear;
  sums.near -= near;  // (a set lane is -1)
  sums.skipped -= near & clear;
  if (!simd::anySet(query)) return count;
  // the queries: each roller's tooth gap, the outline's closest point, the gap, kept as the next hints
  updateGaps<W>(sp, hints, h, query, bodyX, bodyY);
  const V gapX = load<V>(&hints.gapX[h]), gapY = load<V>(&hints.gapY[h]);
  V localX, localY, distance, pointX, pointY, normalX, normalY;
  roller::toGapFrame(bodyX, bodyY, gapX, gapY, localX, localY);
  closestPoints<W>(sp.gap, query, localX, localY, distance, pointX, pointY, normalX, normalY);
  const V gap = distance - m.chain.rollerRadius;
  simd::store(&hints.bodyX[h], simd::select(query, bodyX, load<V>(&hints.bodyX[h])));
  simd::store(&hints.bodyY[h], simd::select(query, bodyY, load<V>(&hints.bodyY[h])));
  simd::store(&hints.clearance[h],
              simd::select(query, simd::select(gap >= margin, gap, V{} - 1.0), load<V>(&hints.clearance[h])));
  const Mask touching = query & (gap < margin);
  if (!simd::anySet(touching)) return count;
  // the contacts in the world frame, their forces, and the list
  const roller::World<V> w = roller::toWorld(
      sp.center, cosA, sinA, d.rotorRate[r], gapX, gapY, pointX, pointY, normalX, normalY, rollerX, rollerY,
      pinLanes<W>(load<V>(&L.vRearX[j]), load<V>(&L.vFrontX[j])),
      pinLanes<W>(load<V>(&L.vRearY[j]), load<V>(&L.vFrontY[j])), pinLanes<W>(load<V>(&L.cx[j]), load<V>(&L.cx[j])),
      pinLanes<W>(load<V>(&L.cy[j]), load<V>(&L.cy[j])));
  V normal{}, friction{};
  if (forces) rollerForces<W, Split>(m, d, j, h, touching, gap, w, normal, friction, sums);
  if (!d.listsContacts(forces)) return count;
  return listRollerContacts<W>(d, s, r, j, touching, gap, w, normal, friction, count);
}

// Sprocket s against the rollers of its window (a thread's share of it: Split, with the forces,
// for the evaluation on several threads; its counts and deepest gap into the thread's part).
template <int W, bool Split>
CHAINDRIVE_ALWAYS_INLINE int rollerLanes(const Model& m, Data& d, int s, double margin, bool forces, int count,
                                         double& power, ThreadPart* part) {
  Sums<W> sums;
  forEachBlock(d.windows.sprocketWindow(s), Split ? part->blocks.data() : nullptr, d.windows.words,
               [&](int first) __attribute__((always_inline)) {
    for (int j = first; j < first + SearchWindows::kBlock && j < m.chain.links; j += W)
      count = rollerVector<W, Split>(m, d, s, j, margin, forces, count, sums);
  });
  long long& queries = Split ? part->rollerQueries : d.rollerQueries;
  long long& skipped = Split ? part->rollerQueriesSkipped : d.rollerQueriesSkipped;
  double& deepest = Split ? part->deepestGap : d.deepestGap;
  for (int l = 0; l < W; ++l) {
    queries += sums.near[l];
    skipped += sums.skipped[l];
  }
  if (!forces) return count;
  if (!Split) {
    d.gen[m.rotorGen(m.sprockets[s].rotor)] -= simd::reducePartials<W>(sums.torque);
    power += simd::reducePartials<W>(sums.power);
  }
  for (int l = 0; l < W; ++l) deepest = std::min(deepest, sums.deepest[l]);
  return count;
}

// The torque and power the threads stored for the W rollers (pins) from pin j (hint h) into the
// sums.
template <int W>
CHAINDRIVE_ALWAYS_INLINE void addStoredRollers(const Data& d, int j, int h, Sums<W>& sums) {
  using V = typename simd::Lanes<W>::V;
  sums.torque[(j / W) % (4 / W)] += simd::load<V>(&d.threads.pinTorque[h]);
  sums.power[(j / W) % (4 / W)] += simd::load<V>(&d.threads.pinPower[h]);
}

// The torques and powers the threads stored per roller, summed over the window as rollerLanes sums
// them (the lanes not touching add zeros, which leave a sum as it is: it starts at +0 and so is
// never -0).
template <int W>
CHAINDRIVE_ALWAYS_INLINE void rollerSumLanes(const Model& m, Data& d, int s, double& power) {
  Sums<W> sums;
  forEachBlock(d.windows.sprocketWindow(s), nullptr, d.windows.words, [&](int first) __attribute__((always_inline)) {
    for (int j = first; j < first + SearchWindows::kBlock && j < m.chain.links; j += W)
      addStoredRollers<W>(d, j, d.rollerHints.index(s, j), sums);
  });
  d.gen[m.rotorGen(m.sprockets[s].rotor)] -= simd::reducePartials<W>(sums.torque);
  power += simd::reducePartials<W>(sums.power);
}

// An arc face's pass over the links, worked out once per face and evaluation: face `face` of guide
// `guide` placed at pf, the guide turning at `rate`.
struct FacePass {
  int guide, face;
  const PlacedFace& pf;
  double margin, reach, rate;
  bool forces, list;
  ThreadPart* part;  // (a thread's share: its blocks, its contacts' shares; null: all, serial)
  int faceIndex;     // in d.placedFaces
};

// The arc face against the W links from link i (those within the guide's bounding circle grown by
// twice `reach`, and near the face).
template <int W>
CHAINDRIVE_ALWAYS_INLINE int plateVector(const Model& m, Data& d, const FacePass& f, int i, int count, double& power) {
  using V = typename simd::Lanes<W>::V;
  using simd::load;
  using simd::store;
  const LinkArrays& L = d.links;
  const PlacedFace& pf = f.pf;
  const V px = load<V>(&L.cx[i]), py = load<V>(&L.cy[i]);
  const V bx = px - d.guideBoundX[f.guide], by = py - d.guideBoundY[f.guide];
  const auto withinBound = ~(bx * bx + by * by > d.guideReach2[f.guide]) & lanesBelow<W>(i, m.chain.links);
  if (!simd::anySet(withinBound)) return count;
  const auto near = withinBound & arcface::near(pf, px, py, f.reach);
  if (!simd::anySet(near)) return count;
  // the plate edge facing the arc (plateEdgeHit) and its contact with it
  const V axisX = load<V>(&L.ex[i]), axisY = load<V>(&L.ey[i]);
  const V side = arcface::side(pf, px, py, axisX, axisY);
  const V normalX = side * -axisY, normalY = side * axisX;
  const double h = m.chain.plateHalfHeight;
  const V e0x = load<V>(&L.rearX[i]) + h * normalX, e0y = load<V>(&L.rearY[i]) + h * normalY;
  const V e1x = load<V>(&L.frontX[i]) + h * normalX, e1y = load<V>(&L.frontY[i]) + h * normalY;
  V qx, qy, g, distance;
  const auto arc = arcface::hit(pf, e0x, e0y, e1x, e1y, qx, qy, g, distance);
  // the lanes touching the arc, or to test against its corners, listed (r <= 0: no contact; beyond
  // the arc's range the corners touch only an edge within reach of its link's centre, unless
  // tunnelled through the plate's height)
  const auto listedMask =
      near & ~(distance <= 0.0) & ((arc & (g < f.margin)) | (~arc & arcface::cornerNear(pf, px, py, f.reach)));
  if (!simd::anySet(listedMask)) return count;
  double edge[4][W], out[2][W], pointX[W], pointY[W], gap[W], r[W];
  for (auto [array, v] : {std::pair{edge[0], e0x}, {edge[1], e0y}, {edge[2], e1x}, {edge[3], e1y}, {out[0], normalX},
                          {out[1], normalY}, {pointX, qx}, {pointY, qy}, {gap, g}, {r, distance}})
    store(array, v);
  ContactPoint unlisted;
  const int cap = static_cast<int>(d.contacts.size());
  for (int l = 0; l < W && (count < cap || !f.list); ++l) {
    if (!listedMask[l]) continue;
    FaceHit hit;
    if (arc[l]) {
      hit = FaceHit{true, gap[l], Vec2{pointX[l], pointY[l]}, arcface::normal(pf, pointX[l], pointY[l], r[l])};
    } else {  // beyond the arc's range: its end corners
      hit = nearerCorner(pf.corner0, pf.corner1, Vec2{edge[0][l], edge[1][l]}, Vec2{edge[2][l], edge[3][l]},
                         Vec2{out[0][l], out[1][l]});
      if (!hit.valid || hit.gap >= f.margin) continue;
    }
    ContactPoint& c = f.list ? d.contacts[count++] : unlisted;
    const int link = i + l;
    setPlateContact(m, f.guide, f.face, link, Vec2{L.cx[link], L.cy[link]}, Vec2{L.vx[link], L.vy[link]}, L.w[link],
                    hit, f.rate, c);
    if (!f.forces) continue;
    if (f.part) sharePlateForce(m, c, d, *f.part, f.faceIndex);
    else power += addCompliantForce(m, m.plateGuide, c, d);
  }
  return count;
}

template <int W>
CHAINDRIVE_ALWAYS_INLINE int plateLanes(const Model& m, Data& d, const PlateFaceRef& face, double margin, double reach,
                                        bool forces, int count, double& power) {
  const int guide = face.guide, rotor = m.guides[guide].rotor;
  const FacePass f{guide,  face.face,  face.pf, margin, reach, rotor >= 0 ? d.rotorRate[rotor] : 0.0, forces,
                   d.listsContacts(forces), face.part, face.index};
  forEachBlock(d.windows.guideWindow(static_cast<int>(m.sprockets.size()), guide),
               face.part ? face.part->blocks.data() : nullptr, d.windows.words,
               [&](int first) __attribute__((always_inline)) {
    for (int i = first; i < first + SearchWindows::kBlock && i < m.chain.links; i += W)
      count = plateVector<W>(m, d, f, i, count, power);
  });
  return count;
}

CHAINDRIVE_TARGET_AVX2 int rollersAvx2(const Model& m, Data& d, int s, double margin, bool forces, int count,
                                       double& power) {
  return rollerLanes<4, false>(m, d, s, margin, forces, count, power, nullptr);
}
int rollersSse2(const Model& m, Data& d, int s, double margin, bool forces, int count, double& power) {
  return rollerLanes<2, false>(m, d, s, margin, forces, count, power, nullptr);
}
CHAINDRIVE_TARGET_AVX2 void rollerShareAvx2(const Model& m, Data& d, int s, ThreadPart& part) {
  double unused = 0.0;
  rollerLanes<4, true>(m, d, s, 0.0, true, 0, unused, &part);
}
void rollerShareSse2(const Model& m, Data& d, int s, ThreadPart& part) {
  double unused = 0.0;
  rollerLanes<2, true>(m, d, s, 0.0, true, 0, unused, &part);
}
CHAINDRIVE_TARGET_AVX2 void rollerSumAvx2(const Model& m, Data& d, int s, double& power) {
  rollerSumLanes<4>(m, d, s, power);
}
void rollerSumSse2(const Model& m, Data& d, int s, double& power) { rollerSumLanes<2>(m, d, s, power); }

CHAINDRIVE_TARGET_AVX2 int platesAvx2(const Model& m, Data& d, const PlateFaceRef& face, double margin, double reach,
                                      bool forces, int count, double& power) {
  return plateLanes<4>(m, d, face, margin, reach, forces, count, power);
}
int platesSse2(const Model& m, Data& d, const PlateFaceRef& face, double margin, double reach, bool forces, int count,
               double& power) {
  return plateLanes<2>(m, d, face, margin, reach, forces, count, power);
}

CHAINDRIVE_TARGET_AVX2 void windowsAvx2(const Model& m, Data& d, double margin) { windowLanes<4>(m, d, margin); }
void windowsSse2(const Model& m, Data& d, double margin) { windowLanes<2>(m, d, margin); }
CHAINDRIVE_TARGET_AVX2 void scanAvx2(const Model& m, Data& d, double margin) { scanWindows<4>(m, d, margin); }
void scanSse2(const Model& m, Data& d, double margin) { scanWindows<2>(m, d, margin); }
CHAINDRIVE_TARGET_AVX2 void movesAvx2(const Data& d, LinkRange r, LinkMoves& moves) {
  largestMoves<4>(d.links, d.windows, r, moves);
}
void movesSse2(const Data& d, LinkRange r, LinkMoves& moves) { largestMoves<2>(d.links, d.windows, r, moves); }

}  // namespace

void updateSearchWindows(const Model& m, Data& d, double margin) {
  if (d.vectorLanes == 4) windowsAvx2(m, d, margin);
  else windowsSse2(m, d, margin);
}

int rollerContactsLoop(const Model& m, Data& d, int sprocket, double margin, bool forces, int count, double& power) {
  return d.vectorLanes == 4 ? rollersAvx2(m, d, sprocket, margin, forces, count, power)
                            : rollersSse2(m, d, sprocket, margin, forces, count, power);
}

int plateContactsLoop(const Model& m, Data& d, const PlateFaceRef& face, double margin, double reach, bool forces,
                      int count, double& power) {
  return d.vectorLanes == 4 ? platesAvx2(m, d, face, margin, reach, forces, count, power)
                            : platesSse2(m, d, face, margin, reach, forces, count, power);
}

void linkMovesRange(const Data& d, LinkRange r, LinkMoves& moves) {
  if (d.vectorLanes == 4) movesAvx2(d, r, moves);
  else movesSse2(d, r, moves);
}

void scanSearchWindows(const Model& m, Data& d, double margin) {
  if (d.vectorLanes == 4) scanAvx2(m, d, margin);
  else scanSse2(m, d, margin);
}

void rollerContactsShare(const Model& m, Data& d, int sprocket, ThreadPart& part) {
  if (d.vectorLanes == 4) rollerShareAvx2(m, d, sprocket, part);
  else rollerShareSse2(m, d, sprocket, part);
}

void rollerContactsSum(const Model& m, Data& d, int sprocket, double& power) {
  if (d.vectorLanes == 4) rollerSumAvx2(m, d, sprocket, power);
  else rollerSumSse2(m, d, sprocket, power);
}

}  // namespace chaindrive
