// GJK on the Minkowski difference B − A: the simplex (a point, a segment or a triangle of
// difference vertices w = b − a) is reduced each step to the smallest sub-simplex whose Voronoi
// region holds the origin, and grown by the support point in the direction of the origin, until
// a support point repeats (no progress, the minimum is found) or the triangle holds the origin.
#include "geometry/gjk.h"

#include <algorithm>

namespace engine::geometry {

namespace {

struct Vertex {
  Vec2 a, b, w;  // w = b − a
  double weight = 0.0;
  int index_a = 0, index_b = 0;
};

struct Simplex {
  Vertex v[3];
  int count = 0;
};

// The point of the proxy farthest along `direction` (in the proxy's frame); ties keep the lower
// index, so the result never depends on anything but the numbers.
int Support(const ShapeProxy& proxy, Vec2 direction) {
  int best = 0;
  double best_dot = Dot(proxy.points[0], direction);
  for (int i = 1; i < proxy.count; ++i) {
    const double dot = Dot(proxy.points[i], direction);
    if (dot > best_dot) best = i, best_dot = dot;
  }
  return best;
}

Vertex MakeVertex(const ShapeProxy& a, const Transform& xa, int ia, const ShapeProxy& b,
                  const Transform& xb, int ib) {
  Vertex v;
  v.a = TransformPoint(xa, a.points[ia]);
  v.b = TransformPoint(xb, b.points[ib]);
  v.w = v.b - v.a;
  v.index_a = ia, v.index_b = ib;
  return v;
}

// The segment w1 w2: the origin's region is vertex 1, vertex 2 or the edge, told by the
// unnormalised barycentric coordinates of its projection.
void SolveSegment(Simplex* s) {
  const Vec2 w1 = s->v[0].w, w2 = s->v[1].w, e = w2 - w1;
  const double u = Dot(w2, e), v = -Dot(w1, e);  // weights of w1 and w2, times |e|²
  if (v <= 0.0) {
    s->v[0].weight = 1.0, s->count = 1;
  } else if (u <= 0.0) {
    s->v[0] = s->v[1], s->v[0].weight = 1.0, s->count = 1;
  } else {
    s->v[0].weight = u / (u + v), s->v[1].weight = v / (u + v);
  }
}

void KeepEdge(Simplex* s, int i, int j, double ui, double uj) {
  const Vertex vi = s->v[i], vj = s->v[j];
  s->v[0] = vi, s->v[1] = vj;
  s->v[0].weight = ui / (ui + uj), s->v[1].weight = uj / (ui + uj);
  s->count = 2;
}

void KeepVertex(Simplex* s, int i) {
  s->v[0] = s->v[i];
  s->v[0].weight = 1.0;
  s->count = 1;
}

// The triangle w1 w2 w3: the edge coordinates (u, v) per edge and the triangle's signed-area
// coordinates decide among the seven regions (Ericson 5.1.5 in 2D).
void SolveTriangle(Simplex* s) {
  const Vec2 w1 = s->v[0].w, w2 = s->v[1].w, w3 = s->v[2].w;
  const Vec2 e12 = w2 - w1, e13 = w3 - w1, e23 = w3 - w2;
  const double u12 = Dot(w2, e12), v12 = -Dot(w1, e12);
  const double u13 = Dot(w3, e13), v13 = -Dot(w1, e13);
  const double u23 = Dot(w3, e23), v23 = -Dot(w2, e23);
  const double area = Cross(e12, e13);
  const double t1 = area * Cross(w2, w3), t2 = area * Cross(w3, w1), t3 = area * Cross(w1, w2);
  if (v12 <= 0.0 && v13 <= 0.0) return KeepVertex(s, 0);
  if (u12 > 0.0 && v12 > 0.0 && t3 <= 0.0) return KeepEdge(s, 0, 1, u12, v12);
  if (u13 > 0.0 && v13 > 0.0 && t2 <= 0.0) return KeepEdge(s, 0, 2, u13, v13);
  if (u12 <= 0.0 && v23 <= 0.0) return KeepVertex(s, 1);
  if (u13 <= 0.0 && u23 <= 0.0) return KeepVertex(s, 2);
  if (u23 > 0.0 && v23 > 0.0 && t1 <= 0.0) return KeepEdge(s, 1, 2, u23, v23);
  const double sum = t1 + t2 + t3;  // the origin is inside
  s->v[0].weight = t1 / sum, s->v[1].weight = t2 / sum, s->v[2].weight = t3 / sum;
}

// Towards the origin: from the point, or perpendicular to the segment on the origin's side.
Vec2 SearchDirection(const Simplex& s) {
  if (s.count == 1) return -s.v[0].w;
  const Vec2 e = s.v[1].w - s.v[0].w;
  return Cross(e, -s.v[0].w) > 0.0 ? LeftPerp(e) : Vec2{e.y, -e.x};
}

bool AlreadyIn(const Simplex& s, int ia, int ib) {
  return std::any_of(s.v, s.v + s.count,
                     [&](const Vertex& v) { return v.index_a == ia && v.index_b == ib; });
}

DistanceOutput Output(const Simplex& s, const ShapeProxy& a, const ShapeProxy& b, int iterations) {
  DistanceOutput out;
  for (int i = 0; i < s.count; ++i) {
    out.point_a += s.v[i].weight * s.v[i].a;
    out.point_b += s.v[i].weight * s.v[i].b;
    out.simplex[i] = {s.v[i].a, s.v[i].b, s.v[i].weight, s.v[i].index_a, s.v[i].index_b};
  }
  out.simplex_count = s.count;
  out.iterations = iterations;
  if (s.count == 3) {
    out.point_b = out.point_a;  // the cores overlap: one point of both
  } else {
    out.distance = Length(out.point_b - out.point_a);
    if (out.distance > 0.0) out.normal = (out.point_b - out.point_a) / out.distance;
  }
  out.separation = out.distance - a.radius - b.radius;
  return out;
}

}  // namespace

ShapeProxy MakeProxy(std::span<const Vec2> points, double radius) {
  ShapeProxy proxy;
  proxy.count = static_cast<int>(std::min<std::size_t>(points.size(), kMaxPolygonVertices));
  std::copy(points.begin(), points.begin() + proxy.count, proxy.points);
  proxy.radius = radius;
  return proxy;
}

ShapeProxy MakeProxy(const Polygon& polygon) {
  return MakeProxy({polygon.vertices, static_cast<std::size_t>(polygon.count)}, polygon.radius);
}

ShapeProxy MakeProxy(const Capsule& capsule) {
  const Vec2 centers[2] = {capsule.center1, capsule.center2};
  return MakeProxy(centers, capsule.radius);
}

DistanceOutput ShapeDistance(const ShapeProxy& a, const Transform& xa, const ShapeProxy& b,
                             const Transform& xb) {
  Simplex s;
  s.v[0] = MakeVertex(a, xa, 0, b, xb, 0);
  s.v[0].weight = 1.0;
  s.count = 1;
  int iterations = 0;
  for (;;) {
    if (s.count == 2) SolveSegment(&s);
    if (s.count == 3) SolveTriangle(&s);
    if (s.count == 3 || iterations == kMaxGjkIterations) break;
    const Vec2 d = SearchDirection(s);
    if (LengthSquared(d) == 0.0) break;  // the origin is a vertex of the difference: touching
    // B's point farthest along d and A's farthest against it make the difference's support.
    const int ia = Support(a, InvRotate(xa.rotation, -d));
    const int ib = Support(b, InvRotate(xb.rotation, d));
    ++iterations;
    if (AlreadyIn(s, ia, ib)) break;  // no progress: the closest point is found
    s.v[s.count++] = MakeVertex(a, xa, ia, b, xb, ib);
  }
  return Output(s, a, b, iterations);
}

}  // namespace engine::geometry
