#include "assembly/chain_path.h"
#include "math/elementary.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace chaindrive {

bool commonTangent(const RouteCircle& a, const RouteCircle& b, Vec2& m) {
  // Tangent points T1 = c1 + s1 m, T2 = c2 + s2 m with running direction perp(m):
  // (c2 - c1).m = s1 - s2 and (c2 - c1).perp(m) > 0.
  const Vec2 d = b.center - a.center;
  const double dist = norm(d);
  if (dist <= 0.0) return false;
  const double c = (a.signedRadius - b.signedRadius) / dist;
  if (std::fabs(c) > 1.0) return false;
  const double beta = angleOf(d);
  const double psi = -math::acos(c);
  m = unit(beta + psi);
  return true;
}

ChainPath ChainPath::through(const std::vector<RouteCircle>& circles) {
  const std::size_t n = circles.size();
  if (n < 2) throw std::invalid_argument("route needs at least two elements");
  std::vector<Vec2> ms(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!commonTangent(circles[i], circles[(i + 1) % n], ms[i]))
      throw std::invalid_argument("route elements " + std::to_string(i) + " and " + std::to_string((i + 1) % n) +
                                  " have no common tangent (they overlap)");
  }
  ChainPath p;
  double s = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const RouteCircle& c = circles[i];
    const Vec2 tin = c.center + c.signedRadius * ms[(i + n - 1) % n];
    const Vec2 tout = c.center + c.signedRadius * ms[i];
    PathSegment arc;
    arc.isArc = true;
    arc.routeIndex = static_cast<int>(i);
    arc.center = c.center;
    arc.signedRadius = c.signedRadius;
    arc.angle0 = angleOf(tin - c.center);
    double sweep = angleOf(tout - c.center) - arc.angle0;
    if (c.signedRadius > 0.0) {
      while (sweep < 0.0) sweep += 2.0 * kPi;
      while (sweep >= 2.0 * kPi) sweep -= 2.0 * kPi;
    } else {
      while (sweep > 0.0) sweep -= 2.0 * kPi;
      while (sweep <= -2.0 * kPi) sweep += 2.0 * kPi;
    }
    arc.sweep = sweep;
    arc.from = tin;
    arc.to = tout;
    arc.start = s;
    arc.length = std::fabs(c.signedRadius * sweep);
    s += arc.length;
    p.segs_.push_back(arc);

    const RouteCircle& nx = circles[(i + 1) % n];
    PathSegment span;
    span.isArc = false;
    span.routeIndex = static_cast<int>(i);
    span.from = tout;
    span.to = nx.center + nx.signedRadius * ms[i];
    span.start = s;
    span.length = norm(span.to - span.from);
    s += span.length;
    p.segs_.push_back(span);
  }
  p.length_ = s;
  return p;
}

double ChainPath::wrap(double s) const {
  double w = std::fmod(s, length_);
  if (w < 0.0) w += length_;
  return w;
}

int ChainPath::segmentAt(double s) const {
  const double w = wrap(s);
  // segments are few; a linear scan from the back is fine and deterministic
  int k = static_cast<int>(segs_.size()) - 1;
  while (k > 0 && segs_[k].start > w) --k;
  return k;
}

Vec2 ChainPath::point(double s) const {
  const double w = wrap(s);
  const PathSegment& g = segs_[segmentAt(w)];
  const double u = std::min(std::max(w - g.start, 0.0), g.length);
  if (g.isArc) {
    const double r = std::fabs(g.signedRadius);
    const double a = g.angle0 + (g.signedRadius > 0.0 ? 1.0 : -1.0) * u / r;
    return g.center + r * unit(a);
  }
  if (g.length <= 0.0) return g.from;
  return g.from + (u / g.length) * (g.to - g.from);
}

Vec2 ChainPath::tangent(double s) const {
  const double w = wrap(s);
  const PathSegment& g = segs_[segmentAt(w)];
  if (g.isArc) {
    const double r = std::fabs(g.signedRadius);
    const double sg = g.signedRadius > 0.0 ? 1.0 : -1.0;
    const double a = g.angle0 + sg * (w - g.start) / r;
    return sg * perp(unit(a));
  }
  if (g.length <= 0.0) return Vec2{1.0, 0.0};
  return (1.0 / g.length) * (g.to - g.from);
}

double ChainPath::arcMiddle(int r) const {
  const PathSegment& g = segs_[static_cast<std::size_t>(2 * r)];
  return g.start + 0.5 * g.length;
}

double ChainPath::nextPin(double s, double pitch) const {
  const Vec2 p0 = point(s);
  // fast path: the next pin lies on the same segment
  const double w = wrap(s);
  const PathSegment& g = segs_[segmentAt(w)];
  const double remaining = g.start + g.length - w;
  if (g.isArc) {
    const double r = std::fabs(g.signedRadius);
    if (pitch < 2.0 * r) {
      const double ds = 2.0 * r * math::asin(pitch / (2.0 * r));
      if (ds <= remaining) return s + ds;
    }
  } else if (pitch <= remaining) {
    return s + pitch;
  }
  // general case: the chord is shorter than the arc, so the root lies in [s + pitch, s + 1.6 pitch]
  double lo = s + pitch, hi = s + 1.6 * pitch;
  auto f = [&](double x) { return norm(point(x) - p0) - pitch; };
  double flo = f(lo);
  if (flo >= 0.0) return lo;
  double fhi = f(hi);
  while (fhi < 0.0) {
    hi += pitch;
    fhi = f(hi);
    if (hi > s + 10.0 * pitch) throw std::invalid_argument("no pin position found along the path");
  }
  for (int i = 0; i < 200 && hi - lo > 1e-15 * (1.0 + std::fabs(s)); ++i) {
    const double mid = 0.5 * (lo + hi);
    const double fm = f(mid);
    if (fm < 0.0) lo = mid;
    else hi = mid;
  }
  return 0.5 * (lo + hi);
}

double walkChords(const ChainPath& path, double s0, int n, double pitch, std::vector<double>* pins) {
  double s = s0;
  if (pins) pins->assign(1, s0);
  for (int k = 0; k < n; ++k) {
    s = path.nextPin(s, pitch);
    if (pins && k + 1 < n) pins->push_back(s);
  }
  return s;
}

}  // namespace chaindrive
