// Small 2D vector and box types used throughout the engine, in double precision.
#pragma once

#include <cmath>

#include "engine/portable_math.h"

namespace engine {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
};

constexpr Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
constexpr Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
constexpr Vec2 operator-(Vec2 a) { return {-a.x, -a.y}; }
constexpr Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
constexpr Vec2 operator*(Vec2 a, double s) { return {a.x * s, a.y * s}; }
constexpr Vec2 operator/(Vec2 a, double s) { return {a.x / s, a.y / s}; }
constexpr Vec2& operator+=(Vec2& a, Vec2 b) { a.x += b.x; a.y += b.y; return a; }
constexpr Vec2& operator-=(Vec2& a, Vec2 b) { a.x -= b.x; a.y -= b.y; return a; }
constexpr bool operator==(Vec2 a, Vec2 b) { return a.x == b.x && a.y == b.y; }

constexpr double Dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
/// The z component of the 3D cross product (a.x, a.y, 0) × (b.x, b.y, 0).
constexpr double Cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
/// ω × r for an angular velocity ω about the z axis.
constexpr Vec2 Cross(double w, Vec2 r) { return {-w * r.y, w * r.x}; }
/// The vector turned a quarter turn counter-clockwise.
constexpr Vec2 LeftPerp(Vec2 a) { return {-a.y, a.x}; }
constexpr double LengthSquared(Vec2 a) { return Dot(a, a); }
inline double Length(Vec2 a) { return std::sqrt(Dot(a, a)); }
constexpr double Clamp(double v, double lo, double hi) { return v < lo ? lo : (v > hi ? hi : v); }
inline bool IsFinite(Vec2 a) { return std::isfinite(a.x) && std::isfinite(a.y); }

/// A rotation by an angle, kept as its cosine and sine.
struct Rot {
  double c = 1.0;
  double s = 0.0;
};

/// The same bits on every machine (engine/portable_math.h), unlike std::cos and std::sin.
inline Rot MakeRot(double angle) {
  const CosSin q = ComputeCosSin(angle);
  return {q.c, q.s};
}
/// The vector turned by the rotation (local to world).
constexpr Vec2 Rotate(Rot q, Vec2 v) { return {q.c * v.x - q.s * v.y, q.s * v.x + q.c * v.y}; }
/// The vector turned back by the rotation (world to local).
constexpr Vec2 InvRotate(Rot q, Vec2 v) { return {q.c * v.x + q.s * v.y, -q.s * v.x + q.c * v.y}; }

/// Axis-aligned bounding box; touching boxes (shared edge) count as overlapping.
struct AABB {
  Vec2 lower;
  Vec2 upper;
};

constexpr bool Overlaps(const AABB& a, const AABB& b) {
  return a.lower.x <= b.upper.x && b.lower.x <= a.upper.x && a.lower.y <= b.upper.y &&
         b.lower.y <= a.upper.y;
}

}  // namespace engine
