// Where a shape's frame stands in the world: a rotation then a translation, and the frame
// arithmetic the geometry layer needs (no angles: rotations stay as cosine and sine).
#pragma once

#include <cmath>

#include "engine/math.h"

namespace engine::geometry {

/// A rigid placement: a local point v lands at position + Rotate(rotation, v).
struct Transform {
  Vec2 position;
  Rot rotation;
};

constexpr Vec2 TransformPoint(const Transform& xf, Vec2 local) {
  return xf.position + Rotate(xf.rotation, local);
}

constexpr Vec2 InvTransformPoint(const Transform& xf, Vec2 world) {
  return InvRotate(xf.rotation, world - xf.position);
}

/// The rotation by a's angle plus b's.
constexpr Rot MulRot(Rot a, Rot b) { return {a.c * b.c - a.s * b.s, a.s * b.c + a.c * b.s}; }

/// The rotation by b's angle minus a's.
constexpr Rot InvMulRot(Rot a, Rot b) { return {a.c * b.c + a.s * b.s, a.c * b.s - a.s * b.c}; }

/// Frame b as seen from frame a (both given in the world): a⁻¹·b.
constexpr Transform InvMulTransforms(const Transform& a, const Transform& b) {
  return {InvRotate(a.rotation, b.position - a.position), InvMulRot(a.rotation, b.rotation)};
}

/// Frame b (given relative to frame a) in the world: a·b.
constexpr Transform MulTransforms(const Transform& a, const Transform& b) {
  return {TransformPoint(a, b.position), MulRot(a.rotation, b.rotation)};
}

/// The rotation scaled back to unit length (after interpolating cosine and sine).
inline Rot NormalizeRot(Rot q) {
  const double length = std::sqrt(q.c * q.c + q.s * q.s);
  return {q.c / length, q.s / length};
}

}  // namespace engine::geometry
