// Mass properties in closed form: circles, capsules, convex polygons (rounded ones exactly), and
// compounds of parts placed in a body's frame (summed, with the parallel axis theorem).
#pragma once

#include <span>

#include "engine/math.h"
#include "geometry/polygon.h"
#include "geometry/transform.h"

namespace engine::geometry {

/// With density 1 the mass is the area (m²) and the inertia the polar second moment (m⁴).
struct MassProperties {
  double mass = 0.0;   ///< kg
  Vec2 center;         ///< the centre of mass, in the frame the shape is given in
  double inertia = 0.0;  ///< kg·m², about `center`
};

/// density in kg/m².
MassProperties CircleMass(Vec2 center, double radius, double density);

/// A rectangle and two half discs.
MassProperties CapsuleMass(const Capsule& capsule, double density);

/// Exact for any radius: the core polygon, a rectangle of depth `radius` on each edge, and a
/// disc sector at each vertex spanning the turn between its two edge normals (the sectors add
/// up to one disc). Box2D v3's b2ComputePolygonMass approximates the rounded skin by pushing
/// the vertices out instead; the sectors need their angles, which TurnAngle gives without libm.
/// A two-vertex polygon is a capsule and agrees with CapsuleMass; it needs a radius > 0 (a bare
/// segment has no area).
MassProperties PolygonMass(const Polygon& polygon, double density);

/// The same mass placed in a parent frame: the centre moves, the inertia about it does not.
MassProperties PlaceMass(const MassProperties& local, const Transform& placement);

/// The parts' total: masses add, the centre is the mass-weighted mean, and each part's inertia
/// moves to the common centre by the parallel axis theorem. No parts (or no mass) gives zeros.
MassProperties CombineMasses(std::span<const MassProperties> parts);

}  // namespace engine::geometry
