// The nominal chain path: the taut closed curve through the route (pitch circles of sprockets,
// pin circles of guide arcs, joined by common tangents), and the polygon of pins inscribed in it
// with chords of one pitch.
#pragma once

#include <string>
#include <vector>

#include "math/vec2.h"

namespace chaindrive {

/// A wrapped circle of the route. signedRadius > 0: the path runs counterclockwise around it.
struct RouteCircle {
  Vec2 center;
  double signedRadius = 0.0;
};

struct PathSegment {
  bool isArc = false;
  int routeIndex = -1;        // arcs: the route element; spans: the element the span leaves
  Vec2 center;                // arcs
  double signedRadius = 0.0;  // arcs
  double angle0 = 0.0;        // arcs: polar angle of the start point
  double sweep = 0.0;         // arcs: signed swept angle
  Vec2 from, to;              // start and end points
  double start = 0.0;         // arc length at the start of the segment
  double length = 0.0;
};

class ChainPath {
 public:
  /// Builds the path through the circles in order. Throws std::invalid_argument naming the route
  /// index when two consecutive circles have no common tangent of the required kind.
  static ChainPath through(const std::vector<RouteCircle>& circles);

  double length() const { return length_; }
  const std::vector<PathSegment>& segments() const { return segs_; }
  /// Point at arc length s (any real s; wrapped into [0, length)).
  Vec2 point(double s) const;
  /// Unit tangent in running direction at s.
  Vec2 tangent(double s) const;
  /// Index of the segment containing s.
  int segmentAt(double s) const;
  /// Arc-length position of the middle of route element r's arc.
  double arcMiddle(int r) const;
  /// The next pin after the pin at arc length s: smallest s' > s with |point(s') - point(s)| = pitch.
  double nextPin(double s, double pitch) const;

 private:
  double wrap(double s) const;
  std::vector<PathSegment> segs_;  // arc 0, span 0, arc 1, span 1, ...
  double length_ = 0.0;
};

/// Walks n chords of one pitch along the path from arc length s0; returns the arc length of the
/// n-th pin (not wrapped), and the first n pins (s0 included) in `pins` unless null.
double walkChords(const ChainPath& path, double s0, int n, double pitch, std::vector<double>* pins);

/// Tangent directions between two oriented circles: the unit vector m with tangent points
/// c1 + r1 m and c2 + r2 m. Returns false if no such tangent exists.
bool commonTangent(const RouteCircle& a, const RouteCircle& b, Vec2& m);

}  // namespace chaindrive
