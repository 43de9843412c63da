// Concave decomposition: the pieces are convex, cover the outline exactly once (areas add up,
// sampled points fall in exactly one piece) and are few (known optima; Hertel–Mehlhorn's 2r + 1).
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "geometry/decompose.h"
#include "geometry_test_util.h"

using engine::Vec2;
using namespace engine::geometry;

namespace {

bool StrictlyConvex(const Outline& piece) {
  for (int i = 0; i < piece.count; ++i) {
    const Vec2 a = piece.points[i], b = piece.points[(i + 1) % piece.count], c = piece.points[(i + 2) % piece.count];
    if (engine::Cross(b - a, c - b) <= 0.0) return false;
  }
  return piece.count >= 3;
}

int ReflexCount(const Outline& outline) {
  int reflex = 0;
  for (int i = 0; i < outline.count; ++i) {
    const Vec2 a = outline.points[i], b = outline.points[(i + 1) % outline.count];
    const Vec2 c = outline.points[(i + 2) % outline.count];
    if (engine::Cross(b - a, c - b) < 0.0) ++reflex;
  }
  return reflex;
}

// Crossing-number point-in-polygon test for a simple outline.
bool InsideSimple(const Outline& outline, Vec2 p) {
  bool inside = false;
  for (int i = 0, j = outline.count - 1; i < outline.count; j = i++) {
    const Vec2 a = outline.points[i], b = outline.points[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y)) inside = !inside;
  }
  return inside;
}

double DistanceToBoundary(const Outline& o, Vec2 p) {
  double d = INFINITY;
  for (int i = 0; i < o.count; ++i) {
    d = std::min(d, geometry_test::PointSegmentDistance(p, o.points[i], o.points[(i + 1) % o.count]));
  }
  return d;
}

// Checks everything a decomposition promises; returns the piece count.
int CheckDecomposition(const std::vector<Vec2>& points, geometry_test::Random& rng) {
  REQUIRE(CheckOutline(points).problem == OutlineProblem::kNone);
  const Outline outline = NormaliseOutline(points);
  const std::vector<Outline> pieces = DecomposeConvex(outline);
  REQUIRE(!pieces.empty());
  double area = 0.0;
  for (const Outline& piece : pieces) {
    CHECK(StrictlyConvex(piece));
    CHECK(piece.count <= outline.count);
    area += 0.5 * TwiceSignedArea(piece.View());
  }
  CHECK(area == Approx(0.5 * TwiceSignedArea(outline.View())).epsilon(1e-12));
  CHECK(static_cast<int>(pieces.size()) <= 2 * ReflexCount(outline) + 1);
  // Points away from every boundary: inside the outline exactly when inside one piece.
  Vec2 lower = outline.points[0], upper = outline.points[0];
  for (const Vec2& p : outline.View()) {
    lower = {std::min(lower.x, p.x), std::min(lower.y, p.y)};
    upper = {std::max(upper.x, p.x), std::max(upper.y, p.y)};
  }
  int sampled = 0;
  for (int k = 0; k < 4000; ++k) {
    const Vec2 p{rng.Uniform(lower.x, upper.x), rng.Uniform(lower.y, upper.y)};
    bool near_boundary = DistanceToBoundary(outline, p) < 1e-9;
    int holders = 0;
    for (const Outline& piece : pieces) {
      near_boundary = near_boundary || DistanceToBoundary(piece, p) < 1e-9;
      holders += geometry_test::InsideConvex({piece.points, piece.points + piece.count}, p) ? 1 : 0;
    }
    if (near_boundary) continue;
    ++sampled;
    CHECK(holders == (InsideSimple(outline, p) ? 1 : 0));
  }
  CHECK(sampled > 3900);
  return static_cast<int>(pieces.size());
}

}  // namespace

TEST_CASE("decompose: a convex outline is one piece", "[geometry]") {
  geometry_test::Random rng(1);
  const std::vector<Vec2> hexagon = {{2, 0}, {1, 1.7}, {-1, 1.7}, {-2, 0}, {-1, -1.7}, {1, -1.7}};
  CHECK(CheckDecomposition(hexagon, rng) == 1);
  const std::vector<Outline> pieces = DecomposeConvex(NormaliseOutline(hexagon));
  REQUIRE(pieces[0].count == 6);
}

TEST_CASE("decompose: an L gives two pieces, a U three (both optimal)", "[geometry]") {
  geometry_test::Random rng(2);
  const std::vector<Vec2> l = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  CHECK(CheckDecomposition(l, rng) == 2);
  const std::vector<Vec2> cup = {{0, 0}, {3, 0}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};
  CHECK(CheckDecomposition(cup, rng) == 3);
  // Given clockwise, the same.
  const std::vector<Vec2> cup_cw(cup.rbegin(), cup.rend());
  CHECK(CheckDecomposition(cup_cw, rng) == 3);
}

TEST_CASE("decompose: a comb of 64 points", "[geometry]") {
  // Sixteen teeth [2k, 2k + 1] × [1, 3] on a base [0, 31] × [0, 1]: 4·16 = 64 points, 30 reflex
  // corners (the gaps' feet). No convex piece holds two teeth's tops, so at least 16 pieces.
  constexpr int kTeeth = 16;
  std::vector<Vec2> comb = {{0, 0}, {2 * kTeeth - 1, 0}};
  for (int k = kTeeth - 1; k >= 0; --k) {
    comb.insert(comb.end(), {{2.0 * k + 1, 3}, {2.0 * k, 3}});
    if (k > 0) comb.insert(comb.end(), {{2.0 * k, 1}, {2.0 * k - 1, 1}});
  }
  REQUIRE(comb.size() == 64);
  geometry_test::Random rng(3);
  const int pieces = CheckDecomposition(comb, rng);
  INFO("comb pieces: " << pieces);
  CHECK(pieces >= kTeeth);
  CHECK(pieces <= 4 * kTeeth);
}

TEST_CASE("decompose: random star-shaped outlines", "[geometry]") {
  geometry_test::Random rng(4);
  for (int trial = 0; trial < 60; ++trial) {
    const int n = 5 + trial % 60;
    std::vector<Vec2> star;
    for (int i = 0; i < n; ++i) {
      const double a = 2.0 * 3.14159265358979 * (i + rng.Uniform(0.1, 0.9)) / n;
      const double r = rng.Uniform(0.3, 2.0);
      star.push_back({r * std::cos(a), r * std::sin(a)});
    }
    CheckDecomposition(star, rng);
  }
}
