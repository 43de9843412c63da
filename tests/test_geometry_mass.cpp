// Mass properties against hand computations, closed forms and a brute-force grid integration;
// the portable arctangent they rest on against the standard library's.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "geometry/mass.h"
#include "geometry/turn_angle.h"
#include "geometry_test_util.h"

using engine::Vec2;
using namespace engine::geometry;

namespace {

constexpr double kPiTest = 3.14159265358979323846;

void CheckMass(const MassProperties& m, double mass, Vec2 center, double inertia, double eps = 1e-12) {
  CHECK(m.mass == Approx(mass).epsilon(eps));
  CHECK(m.center.x == Approx(center.x).margin(eps));
  CHECK(m.center.y == Approx(center.y).margin(eps));
  CHECK(m.inertia == Approx(inertia).epsilon(eps));
}

// Area, centroid and polar moment by summing a fine grid of cells whose centres lie in the shape.
MassProperties GridIntegrate(const Polygon& p, double half, int cells) {
  const std::vector<Vec2> core = geometry_test::CorePoints(p);
  const double h = 2.0 * half / cells;
  double area = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0;
  for (int i = 0; i < cells; ++i) {
    for (int j = 0; j < cells; ++j) {
      const Vec2 q{-half + (i + 0.5) * h, -half + (j + 0.5) * h};
      bool inside = geometry_test::InsideConvex(core, q);
      for (int k = 0; k < p.count && !inside; ++k) {
        inside = geometry_test::PointSegmentDistance(q, core[k], core[(k + 1) % p.count]) <= p.radius;
      }
      if (!inside) continue;
      area += h * h, sx += h * h * q.x, sy += h * h * q.y, sxx += h * h * engine::Dot(q, q);
    }
  }
  const Vec2 c{sx / area, sy / area};
  return {area, c, sxx - area * engine::Dot(c, c)};
}

}  // namespace

TEST_CASE("turn angle: the portable arctangent matches std::atan2", "[geometry]") {
  geometry_test::Random rng(7);
  double worst = 0.0;
  for (int i = 0; i < 100000; ++i) {
    const double y = rng.Uniform(-10, 10), x = rng.Uniform(-10, 10);
    worst = std::max(worst, std::abs(PortableAtan2(y, x) - std::atan2(y, x)));
  }
  INFO("worst |error| " << worst);
  CHECK(worst < 2e-15);
  CHECK(PortableAtan2(0, 0) == 0.0);
  CHECK(PortableAtan2(0, -1) == Approx(kPiTest).epsilon(1e-16));
  CHECK(PortableAtan2(1, 0) == Approx(kPiTest / 2).epsilon(1e-16));
  CHECK(TurnAngle({1, 0}, {0, -1}) == Approx(1.5 * kPiTest).epsilon(1e-15));
  CHECK(TurnAngle({1, 0}, {-1, 0}) == Approx(kPiTest).epsilon(1e-16));
}

TEST_CASE("mass: a right triangle by hand", "[geometry]") {
  // Legs 3 and 6 on the axes: area 9, centroid (1, 2); about the origin Ix = ∫y² = b·h³/12 = 54,
  // Iy = h·b³/12 = 13.5, so J_origin = 67.5 and J_centroid = 67.5 − 9·(1 + 4) = 22.5.
  const std::vector<Vec2> points = {{0, 0}, {3, 0}, {0, 6}};
  CheckMass(PolygonMass(MakePolygon(points), 2.0), 18.0, {1, 2}, 45.0);
}

TEST_CASE("mass: a box polygon gives the box formula", "[geometry]") {
  // m·(w² + h²)/12 with w = 3, h = 1, density 2: m = 6, I = 6·10/12 = 5.
  const MassProperties m = PolygonMass(MakeOffsetBox(1.5, 0.5, {4, -2}, engine::MakeRot(0.3)), 2.0);
  CheckMass(m, 6.0, {4, -2}, 5.0);
}

TEST_CASE("mass: a circle", "[geometry]") {
  CheckMass(CircleMass({1, 2}, 0.5, 4.0), kPiTest, {1, 2}, 0.5 * kPiTest * 0.25);
}

TEST_CASE("mass: a capsule by hand, and as a rounded two-vertex polygon", "[geometry]") {
  // Length 2, radius 1, density 1: rectangle 2×2 (m 4, I = 4·(4 + 4)/12 = 8/3) plus a disc
  // (m π) split in two halves whose centroids sit 4/(3π) beyond x = ±1:
  // I = π·(1/2 + 1 + 2·4/(3π)) = 1.5π + 8/3.
  const Capsule capsule{{-1, 0}, {1, 0}, 1.0};
  const double expected_inertia = 8.0 / 3.0 + 1.5 * kPiTest + 8.0 / 3.0;
  CheckMass(CapsuleMass(capsule, 1.0), 4.0 + kPiTest, {0, 0}, expected_inertia);
  // Turned and moved, as a polygon with a radius: the sectors and strips give the same.
  const Capsule turned{{2, 3}, {2 + 2 * 0.6, 3 + 2 * 0.8}, 1.0};
  const MassProperties as_polygon = PolygonMass(MakeCapsulePolygon(turned), 1.0);
  CheckMass(as_polygon, 4.0 + kPiTest, {2.6, 3.8}, expected_inertia, 1e-12);
}

TEST_CASE("mass: regular polygons tend to the disc", "[geometry]") {
  double previous_gap = INFINITY;
  for (int n : {8, 16, 32, 64}) {
    std::vector<Vec2> points;
    for (int i = 0; i < n; ++i) {
      const double a = 2.0 * kPiTest * i / n;
      points.push_back({2.0 * std::cos(a), 2.0 * std::sin(a)});
    }
    const MassProperties m = PolygonMass(MakePolygon(points), 1.0);
    // The n-gon of circumradius R: A = n·R²·sin(2π/n)/2, I = m·R²·(1 + 2cos²(π/n))/6.
    const double area = 0.5 * n * 4.0 * std::sin(2.0 * kPiTest / n);
    const double c = std::cos(kPiTest / n);
    CHECK(m.mass == Approx(area).epsilon(1e-13));
    CHECK(m.inertia == Approx(area * 4.0 * (1.0 + 2.0 * c * c) / 6.0).epsilon(1e-13));
    CHECK(std::abs(m.center.x) < 1e-14);
    CHECK(std::abs(m.center.y) < 1e-14);
    // The gap to the disc (π·R², πR⁴/2) shrinks as 1/n².
    const double gap = std::abs(m.inertia - 0.5 * kPiTest * 16.0) / (0.5 * kPiTest * 16.0);
    CHECK(gap < previous_gap / 3.5);
    previous_gap = gap;
  }
  // At n = 64 the area falls short by (2π/n)²/6 and the factor (1 + 2cos²(π/n))/3 by
  // (2/3)·(π/n)², about 1.606e-3 each.
  CHECK(previous_gap == Approx(3.21e-3).epsilon(0.01));
}

TEST_CASE("mass: a rounded square by hand", "[geometry]") {
  // Side s, radius r: area s² + 4sr + πr². About the centre: the square s⁴/6, four strips
  // s·r·(s² + r²)/12 + s·r·((s + r)/2)², and four quarter discs at (±s/2, ±s/2):
  // πr⁴/8 + 2·(s/2 + s/2)·r³/3 + (s²/2)·πr²/4 each.
  const double s = 2.0, r = 0.5;
  const double area = s * s + 4 * s * r + kPiTest * r * r;
  const double strips = 4 * (s * r * (s * s + r * r) / 12 + s * r * (s + r) * (s + r) / 4);
  const double corners = 4 * (kPiTest * r * r * r * r / 8 + 2 * s * r * r * r / 3 + s * s / 2 * kPiTest * r * r / 4);
  const double inertia = s * s * s * s / 6 + strips + corners;
  Polygon square = MakeBox(1.0, 1.0);
  square.radius = r;
  CheckMass(PolygonMass(square, 1.0), area, {0, 0}, inertia, 1e-13);
}

TEST_CASE("mass: a rounded irregular pentagon against grid integration", "[geometry]") {
  const std::vector<Vec2> points = {{-1, -0.8}, {1.2, -0.5}, {1.0, 0.7}, {-0.2, 1.1}, {-1.1, 0.3}};
  const Polygon p = MakePolygon(points, 0.3);
  const MassProperties exact = PolygonMass(p, 1.0);
  const MassProperties grid = GridIntegrate(p, 1.6, 1600);
  INFO("exact " << exact.mass << " " << exact.inertia << ", grid " << grid.mass << " " << grid.inertia);
  CHECK(exact.mass == Approx(grid.mass).epsilon(1e-4));
  CHECK(exact.center.x == Approx(grid.center.x).margin(1e-4));
  CHECK(exact.center.y == Approx(grid.center.y).margin(1e-4));
  CHECK(exact.inertia == Approx(grid.inertia).epsilon(2e-4));
}

TEST_CASE("mass: an L of two boxes by hand, placed and turned", "[geometry]") {
  // [0,2]×[0,1] (a 1×2 box turned a quarter turn) and [0,1]×[1,2]: area 3, centroid (5/6, 5/6);
  // I = 2·5/12 + 1·2/12 + 2·(1/36 + 4/36) + 1·(4/36 + 16/36) = 11/6.
  const MassProperties tall = PolygonMass(MakeBox(0.5, 1.0), 1.0);
  const MassProperties square = PolygonMass(MakeBox(0.5, 0.5), 1.0);
  const MassProperties parts[2] = {PlaceMass(tall, {{1.0, 0.5}, engine::Rot{0.0, 1.0}}),
                                   PlaceMass(square, {{0.5, 1.5}, engine::Rot{}})};
  CheckMass(CombineMasses(parts), 3.0, {5.0 / 6.0, 5.0 / 6.0}, 11.0 / 6.0);
  // The upper box twice as dense: mass 4, centroid (2·(1, ½) + 2·(½, 3/2))/4 = (3/4, 1);
  // I = 10/12 + 4/12 + 2·(1/16 + 1/4) + 2·(1/16 + 1/4) = 7/6 + 5/4 = 29/12.
  const MassProperties denser[2] = {parts[0], PlaceMass(PolygonMass(MakeBox(0.5, 0.5), 2.0), {{0.5, 1.5}, {}})};
  CheckMass(CombineMasses(denser), 4.0, {0.75, 1.0}, 29.0 / 12.0);
  CHECK(CombineMasses({}).mass == 0.0);
}
