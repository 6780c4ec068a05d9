// Geometry of the controlling elements: the ISO 606 tooth gap of a sprocket and the faces of
// guides, with the closest-point queries the contact kinematics needs.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "simd.h"
#include "math/vec2.h"

namespace chaindrive {

/// Arc given by its centre, radius and the unit directions of its ends (counterclockwise from
/// dir0 to dir1, span below pi), so range tests need no trigonometry.
struct ArcRange {
  Vec2 center;
  double radius = 0.0;
  Vec2 dir0, dir1;
  bool contains(Vec2 d) const { return cross(dir0, d) >= 0.0 && cross(d, dir1) >= 0.0; }
};

/// Closest point of a roller centre to the tooth-gap profile, in the gap frame (x radial out
/// through the gap centre, y tangential).
struct ProfileHit {
  double distance = 0.0;  // unsigned distance from the roller centre to the profile [m]
  Vec2 point;             // closest profile point
  Vec2 normal;            // unit, from the profile point towards the roller centre
};

/// One tooth gap of an ISO 606 sprocket (seating arc, two convex flank arcs, tip circle),
/// symmetric about the gap axis. Built once; queried for every roller near the sprocket.
struct ToothGap {
  int teeth = 0;
  double pitchRadius = 0.0, rollerRadius = 0.0;
  double seatRadius = 0.0, seatAngle = 0.0, flankRadius = 0.0, tipRadius = 0.0;
  double gapAngle = 0.0;  // 2 pi / z
  // upper half profile (y >= 0)
  ArcRange seat;    // concave, material outside the circle
  ArcRange flank;   // convex, material inside the circle
  ArcRange tip;     // convex (about the sprocket centre); empty when the tooth is pointed
  bool pointed = false;
  Vec2 junctionSeatFlank, junctionFlankTip;

  /// Builds the profile; throws std::invalid_argument with the reason if it is impossible.
  static ToothGap build(int teeth, double pitch, double rollerDiameter, double seatRadius, double seatAngle,
                        double flankRadius, double tipDiameter);
  /// The seat's case of closest() for one point (T = double) or a vector of points (simd.h, the
  /// contact search's rollers several at a time, with the same bits): true (the mask set) where
  /// (px, py) lies inside the seat circle within the seat's angle range, with the distance, the
  /// closest point and the normal there. Such a point is closest to the seat: the flanks and the
  /// tip lie outside that circle (the flank circle touches it externally).
  template <class T>
  CHAINDRIVE_ALWAYS_INLINE auto seatHit(T px, T py, T& distance, T& pointX, T& pointY, T& normalX, T& normalY) const {
    const T sy = simd::select(py < 0.0, T{} - 1.0, T{} + 1.0);  // the profile is symmetric about x
    const T dx = px - seat.center.x, dy = sy * py - seat.center.y;
    const T r2 = dx * dx + dy * dy;
    const auto within = (r2 < seatRadius * seatRadius) & (r2 > 0.0) & (seat.dir0.x * dy - seat.dir0.y * dx >= 0.0) &
                        (dx * seat.dir1.y - dy * seat.dir1.x >= 0.0);
    const T r = simd::sqrt(r2);
    distance = seatRadius - r;
    const T inverse = 1.0 / r;
    const T ux = inverse * dx, uy = inverse * dy;
    pointX = seat.center.x + seatRadius * ux;
    pointY = seat.center.y + seatRadius * (sy * uy);
    normalX = -ux;
    normalY = -sy * uy;
    return within;
  }
  /// Closest point for a point in the gap frame (any sign of y). Inline: the seated roller's
  /// case, the one queried most (every seated roller at every evaluation); the rest out of line.
  ProfileHit closest(Vec2 p) const {
    ProfileHit h;
    if (!seatHit(p.x, p.y, h.distance, h.point.x, h.point.y, h.normal.x, h.normal.y)) return closestOffSeat(p);
    return h;
  }
  /// closest() for a point not inside the seat circle within the seat's range.
  ProfileHit closestOffSeat(Vec2 p) const;
  /// Polyline of the whole sprocket outline at body angle 0 (gap 0 on the +x axis), for plots.
  std::vector<Vec2> outline(int pointsPerArc) const;
};

/// A face element of a guide in the guide's body frame at its drawn pose.
struct GuideFace {
  enum class Type { ConvexArc, ConcaveArc, Line } type = Type::ConvexArc;
  ArcRange arc;        // arcs
  Vec2 from, to;       // lines
  Vec2 lineNormal;     // lines: unit normal pointing to the chain side
  double lineLength = 0.0;
};

/// Result of a plate-edge/face query in world coordinates.
struct FaceHit {
  bool valid = false;
  double gap = 0.0;     // signed distance, negative = penetration [m]
  Vec2 point;           // contact point on the plate edge
  Vec2 normal;          // unit face normal towards the chain
};

/// A face placed by the rotation (c, s) about `pivot` (world coordinates), computed once per
/// evaluation for every link that comes near it.
struct PlacedFace {
  const GuideFace* face = nullptr;
  double c = 1.0, s = 0.0;
  Vec2 center;                    // arcs
  Vec2 corner0, corner1;          // end points (lines: from, to)
  Vec2 normal, dir;               // lines: normal to the chain side, unit direction
};
PlacedFace placeFace(const GuideFace& face, Vec2 pivot, double c, double s);

/// The queries of an arc face (convex or concave) for one link (T = double) or a vector of links
/// (simd.h): the arc's parts of faceNear, faceOutwardNear and plateEdgeFaceContact below, which use
/// them, so that the contact search's links several at a time give the bits of one at a time.
namespace arcface {

/// faceNear's test of an arc face for a point (px, py): within 2 reach of a corner or of the arc's
/// circle (its distance from the centre within radius -+ 2 reach: compared squared).
template <class T>
CHAINDRIVE_ALWAYS_INLINE auto near(const PlacedFace& pf, T px, T py, double reach) {
  const double reach2 = 4.0 * reach * reach;  // (2 reach)^2
  const T ax = px - pf.corner0.x, ay = py - pf.corner0.y, bx = px - pf.corner1.x, by = py - pf.corner1.y;
  const T cx = px - pf.center.x, cy = py - pf.center.y, c2 = cx * cx + cy * cy;
  const double inner = std::max(0.0, pf.face->arc.radius - 2.0 * reach), outer = pf.face->arc.radius + 2.0 * reach;
  return (ax * ax + ay * ay <= reach2) | (bx * bx + by * by <= reach2) | ((c2 >= inner * inner) & (c2 <= outer * outer));
}

/// Whether a corner lies within `reach` of (px, py): a link centred there can touch a corner
/// (nearerCorner) only then, with its plate edge within reach of its centre, unless the corner
/// lies beyond the plate's other edge (a link tunnelled through its height).
template <class T>
CHAINDRIVE_ALWAYS_INLINE auto cornerNear(const PlacedFace& pf, T px, T py, double reach) {
  const T ax = px - pf.corner0.x, ay = py - pf.corner0.y, bx = px - pf.corner1.x, by = py - pf.corner1.y;
  return (ax * ax + ay * ay <= reach * reach) | (bx * bx + by * by <= reach * reach);
}

/// The side (-1 or +1 along perp(e)) of the plate edge facing the arc, for a link centred at
/// (px, py) with axis (ex, ey): the outward direction from the arc's centre (convex) or to it.
template <class T>
CHAINDRIVE_ALWAYS_INLINE T side(const PlacedFace& pf, T px, T py, T ex, T ey) {
  const T dx = px - pf.center.x, dy = py - pf.center.y;
  const auto atCenter = (dx == 0.0) & (dy == 0.0);
  const double sign = pf.face->type == GuideFace::Type::ConvexArc ? 1.0 : -1.0;
  const T ox = simd::select(atCenter, T{}, sign == 1.0 ? dx : -1.0 * dx);
  const T oy = simd::select(atCenter, T{} + 1.0, sign == 1.0 ? dy : -1.0 * dy);
  return simd::select(-ey * ox + ex * oy > 0.0, T{} - 1.0, T{} + 1.0);
}

/// The contact of the plate edge e0-e1 with the arc: the edge's point q and the gap where q's
/// direction from the arc's centre lies within the arc (the mask returned; normal() its normal);
/// r, the distance of q from the centre, tells the rest: none where r <= 0, the corners' elsewhere.
template <class T>
CHAINDRIVE_ALWAYS_INLINE auto hit(const PlacedFace& pf, T e0x, T e0y, T e1x, T e1y, T& qx, T& qy, T& gap, T& r) {
  const GuideFace& f = *pf.face;
  const Vec2 center = pf.center;
  if (f.type == GuideFace::Type::ConvexArc) {  // the edge's point nearest the centre
    const T segX = e1x - e0x, segY = e1y - e0y;
    const T l2 = segX * segX + segY * segY;
    const T along = simd::select(l2 > 0.0, ((center.x - e0x) * segX + (center.y - e0y) * segY) / l2, T{});
    const T t = simd::select(along < 0.0, T{}, simd::select(1.0 < along, T{} + 1.0, along));
    qx = e0x + t * segX;
    qy = e0y + t * segY;
  } else {  // the edge's end farther from it
    const T ax = e0x - center.x, ay = e0y - center.y, bx = e1x - center.x, by = e1y - center.y;
    const auto first = simd::sqrt(ax * ax + ay * ay) >= simd::sqrt(bx * bx + by * by);
    qx = simd::select(first, e0x, e1x);
    qy = simd::select(first, e0y, e1y);
  }
  const T dx = qx - center.x, dy = qy - center.y;
  r = simd::sqrt(dx * dx + dy * dy);
  const double s = -pf.s;  // d in the guide's frame, against the arc's range
  const T bodyX = pf.c * dx - s * dy, bodyY = s * dx + pf.c * dy;
  const auto within = (f.arc.dir0.x * bodyY - f.arc.dir0.y * bodyX >= 0.0) &
                      (bodyX * f.arc.dir1.y - bodyY * f.arc.dir1.x >= 0.0);
  gap = f.type == GuideFace::Type::ConvexArc ? r - f.arc.radius : f.arc.radius - r;
  return within;
}

/// The arc's normal (towards the chain) at its contact with the edge point (qx, qy), r from the centre.
inline Vec2 normal(const PlacedFace& pf, double qx, double qy, double r) {
  const double inverse = (pf.face->type == GuideFace::Type::ConvexArc ? 1.0 : -1.0) / r;
  return Vec2{inverse * (qx - pf.center.x), inverse * (qy - pf.center.y)};
}

}  // namespace arcface

/// Contact of a face end (a corner at point c) with the plate edge segment e0-e1 whose outward
/// normal (towards the guide) is nOut. Valid when the corner projects onto the segment.
inline FaceHit cornerContact(Vec2 c, Vec2 e0, Vec2 e1, Vec2 nOut) {
  FaceHit hit;
  const Vec2 seg = e1 - e0;
  const double l2 = norm2(seg);
  if (l2 <= 0.0) return hit;
  const double t = dot(c - e0, seg) / l2;
  if (t < 0.0 || t > 1.0) return hit;
  hit.valid = true;
  hit.point = e0 + t * seg;
  hit.gap = dot(c - hit.point, nOut);
  hit.normal = -1.0 * nOut;
  return hit;
}

/// The nearer of the two corners' contacts.
inline FaceHit nearerCorner(Vec2 c0, Vec2 c1, Vec2 e0, Vec2 e1, Vec2 nOut) {
  const FaceHit h0 = cornerContact(c0, e0, e1, nOut), h1 = cornerContact(c1, e0, e1, nOut);
  if (!h0.valid) return h1;
  if (!h1.valid) return h0;
  return h0.gap <= h1.gap ? h0 : h1;
}

/// Contact of the plate edge segment e0-e1 (outward normal nOut, towards the guide) with a
/// placed face. Beyond the face's extent the face's end corners are the contact points, so the
/// gap is continuous along the guide. (Inline, as the two below: queried for every link near a
/// guide at every evaluation.)
inline FaceHit plateEdgeFaceContact(const PlacedFace& pf, Vec2 e0, Vec2 e1, Vec2 nOut) {
  // Inside a face's extent the gap is measured to the face; beyond it, to the face's end
  // corners, so that the gap and the force stay continuous where a link leaves the guide.
  const GuideFace& f = *pf.face;
  FaceHit hit;
  switch (f.type) {
    case GuideFace::Type::ConvexArc:
    case GuideFace::Type::ConcaveArc: {
      double r;
      const bool within = arcface::hit(pf, e0.x, e0.y, e1.x, e1.y, hit.point.x, hit.point.y, hit.gap, r);
      if (r <= 0.0) return FaceHit{};
      if (!within) return nearerCorner(pf.corner0, pf.corner1, e0, e1, nOut);
      hit.valid = true;
      hit.normal = arcface::normal(pf, hit.point.x, hit.point.y, r);
      return hit;
    }
    case GuideFace::Type::Line: {
      const Vec2 a = pf.corner0, n = pf.normal;
      const double d0 = dot(e0 - a, n), d1 = dot(e1 - a, n);
      const Vec2 q = d0 <= d1 ? e0 : e1;
      const double along = dot(q - a, pf.dir);
      if (along < 0.0 || along > f.lineLength) return nearerCorner(a, pf.corner1, e0, e1, nOut);
      hit.valid = true;
      hit.gap = std::min(d0, d1);
      hit.point = q;
      hit.normal = n;
      return hit;
    }
  }
  return hit;
}

/// Outward direction (not of unit length) of a placed face near a point (world), used to pick
/// the plate edge facing it.
inline Vec2 faceOutwardNear(const PlacedFace& pf, Vec2 p) {
  const GuideFace& f = *pf.face;
  if (f.type == GuideFace::Type::Line) return pf.normal;
  const Vec2 d = p - pf.center;
  if (d.x == 0.0 && d.y == 0.0) return Vec2{0.0, 1.0};
  return f.type == GuideFace::Type::ConvexArc ? d : -1.0 * d;
}

/// False when no point within `reach` of p can be closer than `reach` to the placed face (its
/// arc circle or line and its end corners): the cheap test before the contact query.
inline bool faceNear(const PlacedFace& pf, Vec2 p, double reach) {
  const double reach2 = 4.0 * reach * reach;  // (2 reach)^2
  if (norm2(p - pf.corner0) <= reach2 || norm2(p - pf.corner1) <= reach2) return true;
  const GuideFace& f = *pf.face;
  if (f.type != GuideFace::Type::Line) return arcface::near(pf, p.x, p.y, reach);
  const double along = dot(p - pf.corner0, pf.dir);
  return along >= -2.0 * reach && along <= f.lineLength + 2.0 * reach && std::fabs(dot(p - pf.corner0, pf.normal)) <= 2.0 * reach;
}


}  // namespace chaindrive
