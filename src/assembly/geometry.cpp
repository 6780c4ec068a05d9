#include "assembly/geometry.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace chaindrive {

namespace {

// Closest point on an arc (centre, radius, counterclockwise range) to p.
// (Square roots only where a distance is kept: a profile query runs for every roller near a
// sprocket at every evaluation.)
void closestOnArc(const ArcRange& a, Vec2 p, Vec2 end0, Vec2 end1, double& bestDist, Vec2& bestPoint) {
  const Vec2 d = p - a.center;
  if (a.contains(d)) {
    const double r = norm(d);
    if (r > 0.0) {
      const double dist = std::fabs(r - a.radius);
      if (dist < bestDist) {
        bestDist = dist;
        bestPoint = a.center + (a.radius / r) * d;
      }
      return;
    }
  }
  const double q0 = norm2(p - end0), q1 = norm2(p - end1);
  if (q0 < bestDist * bestDist) { bestDist = std::sqrt(q0); bestPoint = end0; }
  if (q1 < bestDist * bestDist) { bestDist = std::sqrt(q1); bestPoint = end1; }
}

}  // namespace

ToothGap ToothGap::build(int teeth, double pitch, double rollerDiameter, double seatRadius, double seatAngle,
                         double flankRadius, double tipDiameter) {
  ToothGap g;
  g.teeth = teeth;
  const double z = static_cast<double>(teeth);
  g.gapAngle = 2.0 * kPi / z;
  g.pitchRadius = pitch / (2.0 * std::sin(kPi / z));
  g.rollerRadius = 0.5 * rollerDiameter;
  g.seatRadius = seatRadius;
  g.seatAngle = seatAngle;
  g.flankRadius = flankRadius;
  g.tipRadius = 0.5 * tipDiameter;
  if (seatRadius < g.rollerRadius)
    throw std::invalid_argument("seat radius " + std::to_string(seatRadius) + " m is smaller than the roller radius " +
                                std::to_string(g.rollerRadius) + " m");
  if (g.tipRadius <= g.pitchRadius)
    throw std::invalid_argument("tip diameter " + std::to_string(tipDiameter) + " m must exceed the pitch diameter " +
                                std::to_string(2.0 * g.pitchRadius) + " m");

  const double R = g.pitchRadius, ri = seatRadius, re = flankRadius, h = 0.5 * seatAngle;
  const Vec2 C{R, 0.0};
  const Vec2 u{-std::cos(h), std::sin(h)};  // from the seat centre to the seat/flank junction
  const Vec2 P1 = C + ri * u;
  const Vec2 F = P1 + re * u;                // flank centre: the flank is convex (tooth material inside)
  g.seat = ArcRange{C, ri, u, Vec2{-1.0, 0.0}};
  // Walk the flank from P1 (direction -u seen from F) towards the tip until it leaves the tip
  // circle or reaches the tooth axis (polar angle pi/z).
  const double psi0 = angleOf(-1.0 * u);
  auto at = [&](double psi) { return F + re * unit(psi); };
  auto outside = [&](double psi) {
    const Vec2 q = at(psi);
    return norm(q) >= g.tipRadius || angleOf(q) >= kPi / z;
  };
  double a = psi0, b = psi0;
  const double step = 1e-3;
  while (!outside(b)) {
    a = b;
    b += step;
    if (b > psi0 + kPi) throw std::invalid_argument("flank arc never reaches the tip circle or the tooth axis");
  }
  for (int i = 0; i < 200 && b - a > 1e-15; ++i) {
    const double m = 0.5 * (a + b);
    (outside(m) ? b : a) = m;
  }
  const Vec2 E = at(b);
  g.flank = ArcRange{F, re, -1.0 * u, unit(b)};
  g.junctionSeatFlank = P1;
  if (angleOf(E) >= kPi / z - 1e-12 && norm(E) < g.tipRadius - 1e-9) {
    g.pointed = true;
    g.junctionFlankTip = E;
    g.tip = ArcRange{Vec2{}, g.tipRadius, unit(angleOf(E)), unit(angleOf(E))};
  } else {
    g.pointed = false;
    g.junctionFlankTip = g.tipRadius * unit(angleOf(E));
    g.tip = ArcRange{Vec2{}, g.tipRadius, unit(angleOf(E)), unit(kPi / z)};
  }
  if (angleOf(P1) <= 0.0 || angleOf(P1) >= kPi / z)
    throw std::invalid_argument("seating angle too large for " + std::to_string(teeth) + " teeth");
  return g;
}

ProfileHit ToothGap::closest(Vec2 p) const {
  const double sy = p.y < 0.0 ? -1.0 : 1.0;
  const Vec2 q{p.x, sy * p.y};
  double best = 1e300;
  Vec2 bestPoint;
  // A point inside the seat circle and within the seat's angle range is closest to the seat:
  // the flanks and the tip lie outside that circle (the flank circle touches it externally).
  {
    const Vec2 d = q - seat.center;
    const double r2 = norm2(d);
    if (r2 < seatRadius * seatRadius && r2 > 0.0 && seat.contains(d)) {
      const double r = std::sqrt(r2);
      ProfileHit h;
      h.distance = seatRadius - r;
      const Vec2 u = (1.0 / r) * d;
      h.point = seat.center + seatRadius * Vec2{u.x, sy * u.y};
      h.normal = Vec2{-u.x, -sy * u.y};
      return h;
    }
  }
  const Vec2 seatBottom = seat.center + Vec2{-seatRadius, 0.0};
  closestOnArc(seat, q, junctionSeatFlank, seatBottom, best, bestPoint);
  closestOnArc(flank, q, junctionSeatFlank, junctionFlankTip, best, bestPoint);
  if (!pointed) closestOnArc(tip, q, junctionFlankTip, tipRadius * tip.dir1, best, bestPoint);
  ProfileHit h;
  h.distance = best;
  h.point = Vec2{bestPoint.x, sy * bestPoint.y};
  const Vec2 d = p - h.point;
  const double n = norm(d);
  h.normal = n > 1e-15 ? (1.0 / n) * d : Vec2{-1.0, 0.0};
  return h;
}

std::vector<Vec2> ToothGap::outline(int m) const {
  std::vector<Vec2> half;  // upper half of gap 0, from the gap bottom to the tooth axis
  auto arcPts = [&](const ArcRange& a, Vec2 from, Vec2 to, bool reverse) {
    double a0 = angleOf(from - a.center), a1 = angleOf(to - a.center);
    if (!reverse) { while (a1 < a0) a1 += 2.0 * kPi; }
    else { while (a1 > a0) a1 -= 2.0 * kPi; }
    for (int i = 0; i <= m; ++i) half.push_back(a.center + a.radius * unit(a0 + (a1 - a0) * i / m));
  };
  const Vec2 seatBottom = seat.center + Vec2{-seatRadius, 0.0};
  arcPts(seat, seatBottom, junctionSeatFlank, true);
  arcPts(flank, junctionSeatFlank, junctionFlankTip, false);
  if (!pointed) arcPts(tip, junctionFlankTip, tipRadius * tip.dir1, false);
  std::vector<Vec2> out;
  for (int k = 0; k < teeth; ++k) {
    const double th = k * gapAngle;
    for (auto it = half.rbegin(); it != half.rend(); ++it) out.push_back(rotate(Vec2{it->x, -it->y}, th));
    for (const auto& v : half) out.push_back(rotate(v, th));
  }
  // reorder so that each gap's lower half (mirrored) precedes its upper half: already done above
  return out;
}

namespace {

// Contact of a face end (a corner at point c) with the plate edge segment e0-e1 whose outward
// normal (towards the guide) is nOut. Valid when the corner projects onto the segment.
FaceHit cornerContact(Vec2 c, Vec2 e0, Vec2 e1, Vec2 nOut) {
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

FaceHit nearerCorner(Vec2 c0, Vec2 c1, Vec2 e0, Vec2 e1, Vec2 nOut) {
  const FaceHit h0 = cornerContact(c0, e0, e1, nOut), h1 = cornerContact(c1, e0, e1, nOut);
  if (!h0.valid) return h1;
  if (!h1.valid) return h0;
  return h0.gap <= h1.gap ? h0 : h1;
}

}  // namespace

PlacedFace placeFace(const GuideFace& f, Vec2 pivot, double c, double s) {
  PlacedFace p;
  p.face = &f;
  p.c = c;
  p.s = s;
  if (f.type == GuideFace::Type::Line) {
    p.corner0 = pivot + rotate(f.from - pivot, c, s);
    p.corner1 = pivot + rotate(f.to - pivot, c, s);
    p.normal = rotate(f.lineNormal, c, s);
    p.dir = rotate((1.0 / f.lineLength) * (f.to - f.from), c, s);
  } else {
    p.center = pivot + rotate(f.arc.center - pivot, c, s);
    p.corner0 = p.center + f.arc.radius * rotate(f.arc.dir0, c, s);
    p.corner1 = p.center + f.arc.radius * rotate(f.arc.dir1, c, s);
  }
  return p;
}

FaceHit plateEdgeFaceContact(const PlacedFace& pf, Vec2 e0, Vec2 e1, Vec2 nOut) {
  // Inside a face's extent the gap is measured to the face; beyond it, to the face's end
  // corners, so that the gap and the force stay continuous where a link leaves the guide.
  const GuideFace& f = *pf.face;
  FaceHit hit;
  switch (f.type) {
    case GuideFace::Type::ConvexArc:
    case GuideFace::Type::ConcaveArc: {
      const Vec2 center = pf.center;
      Vec2 q;
      if (f.type == GuideFace::Type::ConvexArc) {
        const Vec2 seg = e1 - e0;
        const double l2 = norm2(seg);
        const double t = std::clamp(l2 > 0.0 ? dot(center - e0, seg) / l2 : 0.0, 0.0, 1.0);
        q = e0 + t * seg;
      } else {
        q = norm(e0 - center) >= norm(e1 - center) ? e0 : e1;
      }
      const Vec2 d = q - center;
      const double r = norm(d);
      if (r <= 0.0) return hit;
      if (!f.arc.contains(rotate(d, pf.c, -pf.s))) return nearerCorner(pf.corner0, pf.corner1, e0, e1, nOut);
      hit.valid = true;
      hit.point = q;
      if (f.type == GuideFace::Type::ConvexArc) {
        hit.gap = r - f.arc.radius;
        hit.normal = (1.0 / r) * d;
      } else {
        hit.gap = f.arc.radius - r;
        hit.normal = (-1.0 / r) * d;
      }
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

Vec2 faceOutwardNear(const PlacedFace& pf, Vec2 p) {
  const GuideFace& f = *pf.face;
  if (f.type == GuideFace::Type::Line) return pf.normal;
  const Vec2 d = p - pf.center;
  if (d.x == 0.0 && d.y == 0.0) return Vec2{0.0, 1.0};
  return f.type == GuideFace::Type::ConvexArc ? d : -1.0 * d;
}

bool faceNear(const PlacedFace& pf, Vec2 p, double reach) {
  const double reach2 = 4.0 * reach * reach;  // (2 reach)^2
  if (norm2(p - pf.corner0) <= reach2 || norm2(p - pf.corner1) <= reach2) return true;
  const GuideFace& f = *pf.face;
  if (f.type == GuideFace::Type::Line) {
    const double along = dot(p - pf.corner0, pf.dir);
    return along >= -2.0 * reach && along <= f.lineLength + 2.0 * reach && std::fabs(dot(p - pf.corner0, pf.normal)) <= 2.0 * reach;
  }
  return std::fabs(norm(p - pf.center) - f.arc.radius) <= 2.0 * reach;
}

}  // namespace chaindrive
