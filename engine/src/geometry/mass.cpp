// Mass properties by integrating area moments: each shape is a sum of triangles and disc sectors
// whose zeroth, first and second area moments have closed forms. The sums run about a reference
// point near the shape (its first vertex), so a shape far from its frame's origin keeps its
// precision, and shift to the centroid at the end.
#include "geometry/mass.h"

#include "geometry/turn_angle.h"

namespace engine::geometry {

namespace {

// Area moments about the reference point: ∫dA, ∫x dA and ∫|x|² dA.
struct AreaMoments {
  double area = 0.0;
  Vec2 first;
  double second = 0.0;
};

// Triangle (a, b, c), counter-clockwise: ∫|x|² dA = A/6·(a·a + b·b + c·c + a·b + b·c + c·a).
void AddTriangle(AreaMoments* m, Vec2 a, Vec2 b, Vec2 c) {
  const double area = 0.5 * Cross(b - a, c - a);
  m->area += area;
  m->first += (area / 3.0) * (a + b + c);
  m->second += (area / 6.0) *
               (Dot(a, a) + Dot(b, b) + Dot(c, c) + Dot(a, b) + Dot(b, c) + Dot(c, a));
}

// The disc sector of radius r at apex v between outward unit normals n1 and n2 (angle θ,
// counter-clockwise). In polar coordinates about the apex: area θr²/2, ∫x dA = r³/3·∫(cos φ,
// sin φ) dφ = r³/3·(n2.y − n1.y, n1.x − n2.x), and ∫|x|² dA = θr⁴/4; then moved to the
// reference point: ∫|v + x|² = ∫|x|² + 2v·∫x + |v|²·area.
void AddSector(AreaMoments* m, Vec2 v, double r, Vec2 n1, Vec2 n2) {
  const double theta = TurnAngle(n1, n2);
  const double area = 0.5 * theta * r * r;
  const Vec2 first_about_apex = (r * r * r / 3.0) * Vec2{n2.y - n1.y, n1.x - n2.x};
  m->area += area;
  m->first += area * v + first_about_apex;
  m->second += 0.25 * theta * r * r * r * r + 2.0 * Dot(v, first_about_apex) + Dot(v, v) * area;
}

MassProperties FromMoments(const AreaMoments& m, Vec2 reference, double density) {
  const Vec2 centroid = m.first / m.area;
  // Parallel axis theorem, from the reference point back to the centroid.
  const double second_about_centroid = m.second - m.area * Dot(centroid, centroid);
  return {density * m.area, reference + centroid, density * second_about_centroid};
}

}  // namespace

MassProperties CircleMass(Vec2 center, double radius, double density) {
  const double mass = density * kPi * radius * radius;
  return {mass, center, 0.5 * mass * radius * radius};
}

MassProperties CapsuleMass(const Capsule& capsule, double density) {
  const double r = capsule.radius, length = Length(capsule.center2 - capsule.center1);
  const double rectangle_mass = density * length * 2.0 * r;
  const double disc_mass = density * kPi * r * r;
  // Each half disc's centroid sits 4r/(3π) beyond its flat side, which is at length/2 from the
  // middle: about the middle a half disc has m_h·(r²/2 − d² + (length/2 + d)²), and the two
  // together disc_mass·(r²/2 + length²/4 + length·d).
  const double d = 4.0 * r / (3.0 * kPi);
  const double rectangle_inertia = rectangle_mass * (length * length + 4.0 * r * r) / 12.0;
  const double caps_inertia = disc_mass * (0.5 * r * r + 0.25 * length * length + length * d);
  return {rectangle_mass + disc_mass, 0.5 * (capsule.center1 + capsule.center2),
          rectangle_inertia + caps_inertia};
}

MassProperties PolygonMass(const Polygon& polygon, double density) {
  const int n = polygon.count;
  const Vec2 reference = polygon.vertices[0];
  Vec2 v[kMaxPolygonVertices];
  for (int i = 0; i < n; ++i) v[i] = polygon.vertices[i] - reference;
  AreaMoments m;
  // The core as a fan from the reference vertex (no area for a capsule's two vertices).
  for (int i = 1; i + 1 < n; ++i) AddTriangle(&m, v[0], v[i], v[i + 1]);
  const double r = polygon.radius;
  if (r > 0.0) {
    for (int i = 0; i < n; ++i) {
      const int next = (i + 1) % n, before = (i + n - 1) % n;
      const Vec2 offset = r * polygon.normals[i];
      // The edge's rectangle as two triangles, counter-clockwise: the normal points outward,
      // which is to the right of the edge.
      AddTriangle(&m, v[i], v[i] + offset, v[next] + offset);
      AddTriangle(&m, v[i], v[next] + offset, v[next]);
      AddSector(&m, v[i], r, polygon.normals[before], polygon.normals[i]);
    }
  }
  return FromMoments(m, reference, density);
}

MassProperties PlaceMass(const MassProperties& local, const Transform& placement) {
  return {local.mass, TransformPoint(placement, local.center), local.inertia};
}

MassProperties CombineMasses(std::span<const MassProperties> parts) {
  MassProperties total;
  if (parts.empty()) return total;
  // Sums about the first part's centre, for precision (as the area moments above).
  const Vec2 reference = parts[0].center;
  Vec2 moment;
  double inertia_about_reference = 0.0;
  for (const MassProperties& part : parts) {
    const Vec2 offset = part.center - reference;
    total.mass += part.mass;
    moment += part.mass * offset;
    inertia_about_reference += part.inertia + part.mass * Dot(offset, offset);
  }
  if (total.mass <= 0.0) return {};
  const Vec2 center = moment / total.mass;
  total.center = reference + center;
  total.inertia = inertia_about_reference - total.mass * Dot(center, center);
  return total;
}

}  // namespace engine::geometry
