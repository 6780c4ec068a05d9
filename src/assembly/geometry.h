// Geometry of the controlling elements: the ISO 606 tooth gap of a sprocket and the faces of
// guides, with the closest-point queries the contact kinematics needs.
#pragma once

#include <vector>

#include "vec2.h"

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
  /// Closest point for a point in the gap frame (any sign of y).
  ProfileHit closest(Vec2 p) const;
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

/// Contact of the plate edge segment e0-e1 (outward normal nOut, towards the guide) with a
/// placed face. Beyond the face's extent the face's end corners are the contact points, so the
/// gap is continuous along the guide.
FaceHit plateEdgeFaceContact(const PlacedFace& face, Vec2 e0, Vec2 e1, Vec2 nOut);
/// Outward direction (not of unit length) of a placed face near a point (world), used to pick
/// the plate edge facing it.
Vec2 faceOutwardNear(const PlacedFace& face, Vec2 p);
/// False when no point within `reach` of p can be closer than `reach` to the placed face (its
/// arc circle or line and its end corners): the cheap test before the contact query.
bool faceNear(const PlacedFace& face, Vec2 p, double reach);

}  // namespace chaindrive
