#include "assembly/geometry.h"
#include "math/elementary.h"

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
  g.pitchRadius = pitch / (2.0 * math::sin(kPi / z));
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
  const Vec2 u{-math::cos(h), math::sin(h)};  // from the seat centre to the seat/flank junction
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

ProfileHit ToothGap::closestOffSeat(Vec2 p) const {
  const double sy = p.y < 0.0 ? -1.0 : 1.0;
  const Vec2 q{p.x, sy * p.y};
  double best = 1e300;
  Vec2 bestPoint;
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

}  // namespace chaindrive
