// Planar vector algebra used by geometry, contact kinematics and forces.
#pragma once

#include <cmath>

#include "math/elementary.h"

namespace chaindrive {

constexpr double kPi = 3.14159265358979323846;

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
};

inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2 operator-(Vec2 a) { return {-a.x, -a.y}; }
inline Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
inline Vec2 operator*(Vec2 a, double s) { return {s * a.x, s * a.y}; }
inline Vec2& operator+=(Vec2& a, Vec2 b) { a.x += b.x; a.y += b.y; return a; }
inline Vec2& operator-=(Vec2& a, Vec2 b) { a.x -= b.x; a.y -= b.y; return a; }
inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
/// z component of the cross product a x b
inline double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
/// (0, 0, w) x r in the plane
inline Vec2 crossWz(double w, Vec2 r) { return {-w * r.y, w * r.x}; }
inline double norm(Vec2 a) { return std::sqrt(a.x * a.x + a.y * a.y); }
inline double norm2(Vec2 a) { return a.x * a.x + a.y * a.y; }
/// left normal (rotation by +90 degrees)
inline Vec2 perp(Vec2 a) { return {-a.y, a.x}; }
inline Vec2 unit(double angle) { return {math::cos(angle), math::sin(angle)}; }
inline Vec2 rotate(Vec2 a, double c, double s) { return {c * a.x - s * a.y, s * a.x + c * a.y}; }
inline Vec2 rotate(Vec2 a, double angle) { return rotate(a, math::cos(angle), math::sin(angle)); }
inline double angleOf(Vec2 a) { return math::atan2(a.y, a.x); }

/// Wraps an angle into (-pi, pi].
inline double wrapAngle(double a) {
  a = std::fmod(a + kPi, 2.0 * kPi);
  if (a <= 0.0) a += 2.0 * kPi;
  return a - kPi;
}

}  // namespace chaindrive
