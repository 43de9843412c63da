// Soft bodies: a box as a lattice, a circle as a ring under pressure, solved by XPBD.
#include "particles/soft_bodies.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>

namespace engine::detail {

namespace {

// A box: (nx + 1) × (ny + 1) particles, inset by a particle radius so the lattice's discs fill
// the box; rows from the lower left corner in the box's frame.
void MakeLattice(const SoftBodyDef& def, SoftBody* body) {
  const double s = def.spacing;
  const Vec2 half = def.shape.half_extents;
  const Rot turn = MakeRot(def.angle);
  const double width = 2.0 * half.x - s, height = 2.0 * half.y - s;
  const int nx = std::max(1, static_cast<int>(std::ceil(width / s - 1e-9)));
  const int ny = std::max(1, static_cast<int>(std::ceil(height / s - 1e-9)));
  const double dx = width / nx, dy = height / ny;
  body->radius = 0.5 * s;
  const auto at = [nx](int i, int j) { return static_cast<std::uint32_t>(j * (nx + 1) + i); };
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      const Vec2 local{-0.5 * width + i * dx, -0.5 * height + j * dy};
      body->rest_positions.push_back(def.position + Rotate(turn, local));
    }
  }
  const auto edge = [&](std::uint32_t a, std::uint32_t b, double compliance) {
    const double rest = Length(body->rest_positions[b] - body->rest_positions[a]);
    body->edges.push_back({a, b, rest, compliance * rest / s});  // a longer edge is softer, in proportion
  };
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      if (i < nx) edge(at(i, j), at(i + 1, j), def.stretch_compliance);
      if (j < ny) edge(at(i, j), at(i, j + 1), def.stretch_compliance);
    }
  }
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      edge(at(i, j), at(i + 1, j + 1), def.shear_compliance);
      edge(at(i + 1, j), at(i, j + 1), def.shear_compliance);
    }
  }
  const double cell_area = dx * dy;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const auto first = static_cast<std::uint32_t>(body->area_vertices.size());
      for (const std::uint32_t v : {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)}) {
        body->area_vertices.push_back(v);
      }
      body->areas.push_back({first, 4, cell_area, cell_area, def.area_compliance / cell_area});
    }
  }
  for (int i = 0; i < nx; ++i) body->outline.push_back(at(i, 0));
  for (int j = 0; j < ny; ++j) body->outline.push_back(at(nx, j));
  for (int i = nx; i > 0; --i) body->outline.push_back(at(i, ny));
  for (int j = ny; j > 0; --j) body->outline.push_back(at(0, j));
}

double PolygonArea(std::span<const std::uint32_t> vertices, std::uint32_t offset, std::span<const Vec2> x) {
  double twice = 0.0;
  for (std::size_t k = 0; k < vertices.size(); ++k) {
    const Vec2 a = x[offset + vertices[k]], b = x[offset + vertices[(k + 1) % vertices.size()]];
    twice += Cross(a, b);
  }
  return 0.5 * twice;
}

// A circle: a ring of particles half a spacing in from the rim, anticlockwise, holding an area.
void MakeRing(const SoftBodyDef& def, SoftBody* body) {
  const double s = def.spacing;
  const double ring = def.shape.radius - 0.5 * s;
  const int n = std::max(6, static_cast<int>(std::ceil(2.0 * std::numbers::pi * ring / s - 1e-9)));
  body->radius = 0.5 * s;
  for (int k = 0; k < n; ++k) {
    const double a = def.angle + 2.0 * std::numbers::pi * k / n;
    body->rest_positions.push_back(def.position + ring * Vec2{std::cos(a), std::sin(a)});
    body->outline.push_back(static_cast<std::uint32_t>(k));
    body->area_vertices.push_back(static_cast<std::uint32_t>(k));
  }
  for (int k = 0; k < n; ++k) {
    const auto a = static_cast<std::uint32_t>(k), b = static_cast<std::uint32_t>((k + 1) % n);
    const double rest = Length(body->rest_positions[b] - body->rest_positions[a]);
    body->edges.push_back({a, b, rest, def.stretch_compliance * rest / s});
  }
  const double area = PolygonArea(body->area_vertices, 0, body->rest_positions);
  body->areas.push_back({0, static_cast<std::uint32_t>(n), area, def.pressure * area, def.area_compliance / area});
}

// Greedy colouring: each constraint gets the lowest colour no earlier constraint on any of its
// particles has. Constraints of one colour share no particle.
template <class Particles>
std::vector<int> Colours(std::size_t count, std::uint32_t particles, Particles&& particles_of) {
  std::vector<std::uint64_t> used(particles, 0);
  std::vector<int> colours(count);
  for (std::size_t k = 0; k < count; ++k) {
    std::uint64_t taken = 0;
    particles_of(k, [&](std::uint32_t p) { taken |= used[p]; });
    const int colour = std::countr_one(taken);  // a vertex is in at most 8 edges or 4 cells: < 64
    colours[k] = colour;
    particles_of(k, [&](std::uint32_t p) { used[p] |= std::uint64_t{1} << colour; });
  }
  return colours;
}

template <class T>
void SortByColour(std::vector<T>& items, const std::vector<int>& colours) {
  std::vector<std::size_t> order(items.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return colours[a] < colours[b]; });
  std::vector<T> sorted;
  sorted.reserve(items.size());
  for (const std::size_t k : order) sorted.push_back(items[k]);
  items = std::move(sorted);
}

// Gauss-Seidel in the order the constraints were made sweeps one way through the body, and its
// corrections lean the way it sweeps: a pressurised ring resting on the floor turned a little
// every substep and rolled off, faster and faster. By colour, no constraint of a colour moves
// a particle another of the colour reads, so each colour's result does not depend on its order
// (Fratarcangeli, Tibaldo and Pellacini 2016, "Vivace"), and the sweep has no direction.
void OrderByColour(SoftBody* body) {
  const auto edge_colours = Colours(body->edges.size(), body->count, [&](std::size_t k, auto&& visit) {
    visit(body->edges[k].a);
    visit(body->edges[k].b);
  });
  SortByColour(body->edges, edge_colours);
  const auto area_colours = Colours(body->areas.size(), body->count, [&](std::size_t k, auto&& visit) {
    const SoftArea& a = body->areas[k];
    for (std::uint32_t i = 0; i < a.count; ++i) visit(body->area_vertices[a.first + i]);
  });
  SortByColour(body->areas, area_colours);
}

double AreaOfShape(const Shape& shape) {
  return shape.type == ShapeType::kCircle ? std::numbers::pi * shape.radius * shape.radius
                                          : 4.0 * shape.half_extents.x * shape.half_extents.y;
}

// XPBD on one edge: lambda is its multiplier this substep.
void SolveEdge(const SoftEdge& e, std::uint32_t o, double inv_h2, std::span<Vec2> x, std::span<const double> w,
               double& lambda) {
  Vec2& xa = x[o + e.a];
  Vec2& xb = x[o + e.b];
  const double wa = w[o + e.a], wb = w[o + e.b];
  const Vec2 d = xb - xa;
  const double length = Length(d);
  if (length == 0.0 || wa + wb == 0.0) return;
  const Vec2 n = d / length;
  const double alpha = e.compliance * inv_h2;
  const double dl = (-(length - e.rest) - alpha * lambda) / (wa + wb + alpha);
  lambda += dl;
  xa -= (wa * dl) * n;
  xb += (wb * dl) * n;
}

void SolveArea(const SoftBody& body, const SoftArea& a, double inv_h2, std::span<Vec2> x, std::span<const double> w,
               double& lambda, std::vector<Vec2>& step) {
  const std::uint32_t o = body.first;
  const std::span<const std::uint32_t> v(body.area_vertices.data() + a.first, a.count);
  const double area = PolygonArea(v, o, x);
  const double c = (area - a.target) / a.rest;
  // dA/dx_i = ½ perp(x_{i+1} − x_{i−1}), with perp(v) = (v.y, −v.x) for an anticlockwise polygon.
  double denominator = 0.0;
  for (std::size_t i = 0; i < a.count; ++i) {
    const Vec2 g = 0.5 / a.rest * (x[o + v[(i + 1) % a.count]] - x[o + v[(i + a.count - 1) % a.count]]);
    denominator += w[o + v[i]] * LengthSquared(g);
  }
  const double alpha = a.compliance * inv_h2;
  if (denominator + alpha == 0.0) return;
  const double dl = (-c - alpha * lambda) / (denominator + alpha);
  lambda += dl;
  // Gradients from the positions before this pass moved any vertex: the constraint's step.
  step.resize(a.count);
  for (std::size_t i = 0; i < a.count; ++i) {
    const Vec2 d = 0.5 / a.rest * (x[o + v[(i + 1) % a.count]] - x[o + v[(i + a.count - 1) % a.count]]);
    step[i] = (w[o + v[i]] * dl) * Vec2{d.y, -d.x};
  }
  for (std::size_t i = 0; i < a.count; ++i) x[o + v[i]] += step[i];
}

// A ring has no constraint against bending: its shape can change with no edge stretched and,
// to first order, its area kept, so edge damping never reaches those motions, and a ball
// rolling in a V traded energy with them for tens of seconds. Its velocities relative to its
// rigid motion (the particles' mean velocity and mean spin) lose `share` instead (Müller et
// al. 2007, "Position based dynamics", §3.5): momentum and angular momentum kept.
void DampShape(const SoftBody& body, double share, std::span<const Vec2> x, std::span<Vec2> v) {
  const std::uint32_t o = body.first;
  const double n = static_cast<double>(body.count);  // the particles' masses are all equal
  Vec2 centre, velocity;
  for (std::uint32_t i = 0; i < body.count; ++i) {
    centre += x[o + i];
    velocity += v[o + i];
  }
  centre = centre / n;
  velocity = velocity / n;
  double spin = 0.0, inertia = 0.0;
  for (std::uint32_t i = 0; i < body.count; ++i) {
    const Vec2 r = x[o + i] - centre;
    spin += Cross(r, v[o + i] - velocity);
    inertia += LengthSquared(r);
  }
  if (inertia == 0.0) return;
  const double omega = spin / inertia;
  for (std::uint32_t i = 0; i < body.count; ++i) {
    const Vec2 r = x[o + i] - centre;
    const Vec2 rigid = velocity + omega * Vec2{-r.y, r.x};
    v[o + i] += share * (rigid - v[o + i]);
  }
}

}  // namespace

bool IsValidSoftBodyDef(const SoftBodyDef& def) {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  const auto non_negative = [](double v) { return std::isfinite(v) && v >= 0.0; };
  if (!IsFinite(def.position) || !std::isfinite(def.angle) || !IsFinite(def.velocity)) return false;
  if (!positive(def.spacing) || !positive(def.density) || !positive(def.pressure)) return false;
  for (const double v : {def.stretch_compliance, def.shear_compliance, def.area_compliance, def.damping, def.friction}) {
    if (!non_negative(v)) return false;
  }
  constexpr double kMaxParticles = 100000.0;
  if (def.shape.type == ShapeType::kCircle) {
    return positive(def.shape.radius) && def.shape.radius > def.spacing &&
           2.0 * std::numbers::pi * def.shape.radius / def.spacing <= kMaxParticles;
  }
  const Vec2 half = def.shape.half_extents;
  return def.shape.type == ShapeType::kBox && positive(half.x) && positive(half.y) &&
         2.0 * std::min(half.x, half.y) > def.spacing &&
         (2.0 * half.x / def.spacing + 1.0) * (2.0 * half.y / def.spacing + 1.0) <= kMaxParticles;
}

SoftBody MakeSoftBody(const SoftBodyDef& def) {
  SoftBody body;
  body.def = def;
  if (def.shape.type == ShapeType::kCircle) {
    MakeRing(def, &body);
  } else {
    MakeLattice(def, &body);
  }
  body.count = static_cast<std::uint32_t>(body.rest_positions.size());
  OrderByColour(&body);
  body.particle_mass = def.density * AreaOfShape(def.shape) / body.count;
  return body;
}

void SolveSoftBody(const SoftBody& body, double h, std::span<Vec2> x, std::span<const double> w,
                   std::span<double> lambda, std::vector<Vec2>& scratch) {
  const double inv_h2 = 1.0 / (h * h);
  std::size_t k = 0;
  for (const SoftEdge& e : body.edges) SolveEdge(e, body.first, inv_h2, x, w, lambda[k++]);
  for (const SoftArea& a : body.areas) SolveArea(body, a, inv_h2, x, w, lambda[k++], scratch);
}

void DampSoftBody(const SoftBody& body, double h, std::span<const Vec2> x, std::span<Vec2> v,
                  std::span<const double> w) {
  if (body.def.damping == 0.0) return;
  const double share = std::min(1.0, body.def.damping * h);
  const std::uint32_t o = body.first;
  for (const SoftEdge& e : body.edges) {
    const double wa = w[o + e.a], wb = w[o + e.b];
    const Vec2 d = x[o + e.b] - x[o + e.a];
    const double length = Length(d);
    if (wa + wb == 0.0 || length == 0.0) continue;
    const Vec2 n = d / length;
    // Takes `share` of the stretching speed away, momentum kept: never adds energy.
    const double impulse = share * Dot(v[o + e.b] - v[o + e.a], n) / (wa + wb);
    v[o + e.a] += (wa * impulse) * n;
    v[o + e.b] -= (wb * impulse) * n;
  }
  if (body.def.shape.type == ShapeType::kCircle) DampShape(body, share, x, v);
}

double SoftBodyElasticEnergy(const SoftBody& body, std::span<const Vec2> x) {
  const std::uint32_t o = body.first;
  double energy = 0.0;
  for (const SoftEdge& e : body.edges) {
    if (e.compliance == 0.0) continue;
    const double c = Length(x[o + e.b] - x[o + e.a]) - e.rest;
    energy += 0.5 * c * c / e.compliance;
  }
  for (const SoftArea& a : body.areas) {
    if (a.compliance == 0.0) continue;
    const std::span<const std::uint32_t> v(body.area_vertices.data() + a.first, a.count);
    const double c = (PolygonArea(v, o, x) - a.target) / a.rest;
    energy += 0.5 * c * c / a.compliance;
  }
  return energy;
}

}  // namespace engine::detail
