// GJK distance against hand cases and against a brute-force distance over random convex pairs
// (polygons, segments, points), and the closest points it names.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "geometry/gjk.h"
#include "geometry/segment_distance.h"
#include "geometry_test_util.h"

using engine::Rot;
using engine::Vec2;
using namespace engine::geometry;

namespace {

const Transform kIdentity{};

DistanceOutput Distance(const std::vector<Vec2>& a, const Transform& xa, const std::vector<Vec2>& b,
                        const Transform& xb, double ra = 0.0, double rb = 0.0) {
  return ShapeDistance(MakeProxy(a, ra), xa, MakeProxy(b, rb), xb);
}

}  // namespace

TEST_CASE("gjk: two boxes side by side", "[geometry]") {
  const Polygon box = MakeBox(1, 1);
  const DistanceOutput d = ShapeDistance(MakeProxy(box), kIdentity, MakeProxy(box), {{3.5, 0.5}, Rot{}});
  CHECK(d.distance == Approx(1.5).epsilon(1e-15));
  CHECK(d.normal.x == Approx(1.0));
  CHECK(d.normal.y == Approx(0.0).margin(1e-15));
  CHECK(d.point_a.x == Approx(1.0));
  CHECK(d.point_b.x == Approx(2.5));
  // The witness points lie on the facing sides, within both boxes' height.
  CHECK(d.point_a.y == Approx(d.point_b.y));
  CHECK(d.point_a.y >= -0.5 - 1e-15);
  CHECK(d.point_a.y <= 1.0 + 1e-15);
  CHECK(d.separation == d.distance);
}

TEST_CASE("gjk: corner to corner, turned by 45 degrees", "[geometry]") {
  // A diamond (box turned 45°) whose left corner is at x = 3 − √2 faces the unit box's right side.
  const Polygon box = MakeBox(1, 1);
  const Transform xb{{3.0, 0.0}, engine::MakeRot(0.78539816339744831)};
  const DistanceOutput d = ShapeDistance(MakeProxy(box), kIdentity, MakeProxy(box), xb);
  CHECK(d.distance == Approx(2.0 - std::sqrt(2.0)).epsilon(1e-14));
  CHECK(d.point_b.x == Approx(3.0 - std::sqrt(2.0)).epsilon(1e-14));
  CHECK(d.point_b.y == Approx(0.0).margin(1e-14));
}

TEST_CASE("gjk: circles and capsules use their radii in the separation only", "[geometry]") {
  const std::vector<Vec2> point = {{0, 0}};
  const DistanceOutput circles = Distance(point, kIdentity, point, {{3, 4}, Rot{}}, 1.0, 1.5);
  CHECK(circles.distance == Approx(5.0));
  CHECK(circles.separation == Approx(2.5));
  CHECK(circles.normal.x == Approx(0.6));
  CHECK(circles.normal.y == Approx(0.8));
  // Two parallel capsules 1 apart (cores), radii 0.3 each.
  const DistanceOutput capsules = ShapeDistance(MakeProxy(Capsule{{-1, 0}, {1, 0}, 0.3}), kIdentity,
                                                MakeProxy(Capsule{{-1, 0}, {1, 0}, 0.3}), {{0.5, 1.0}, Rot{}});
  CHECK(capsules.distance == Approx(1.0));
  CHECK(capsules.separation == Approx(0.4));
}

TEST_CASE("gjk: overlapping cores give distance 0", "[geometry]") {
  const Polygon box = MakeBox(1, 1);
  const DistanceOutput d = ShapeDistance(MakeProxy(box), kIdentity, MakeProxy(box), {{0.5, 0.3}, engine::MakeRot(0.4)});
  CHECK(d.distance == 0.0);
  CHECK(d.simplex_count == 3);
  CHECK(d.normal == Vec2{0, 0});
  // Crossing segments overlap too, and a point inside a polygon.
  const DistanceOutput cross = Distance({{-1, 0}, {1, 0}}, kIdentity, {{0, -1}, {0, 1}}, kIdentity);
  CHECK(cross.distance == Approx(0.0).margin(1e-15));
  const DistanceOutput inside = ShapeDistance(MakeProxy(box), kIdentity, MakeProxy(std::vector<Vec2>{{0.2, 0.1}}, 0.0), kIdentity);
  CHECK(inside.distance == 0.0);
}

TEST_CASE("gjk: agrees with brute force on random convex pairs", "[geometry]") {
  geometry_test::Random rng(20240601);
  double worst = 0.0;
  int separated = 0, overlapping = 0, max_iterations = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    // Sizes 1 (a point), 2 (a segment) and polygons of 3 to 12 vertices.
    const int na = 1 + trial % 12, nb = 1 + (trial / 12) % 12;
    const auto shape = [&](int n) {
      if (n == 1) return std::vector<Vec2>{rng.InBox(0.5)};
      if (n == 2) return std::vector<Vec2>{rng.InBox(1.0), rng.InBox(1.0)};
      return geometry_test::RandomConvexPoints(rng, n, rng.Uniform(0.2, 1.5), rng.Uniform(0.2, 1.5));
    };
    const std::vector<Vec2> a = shape(na), b = shape(nb);
    const Transform xa{rng.InBox(1.0), rng.AnyRotation()}, xb{rng.InBox(2.5), rng.AnyRotation()};
    const DistanceOutput d = Distance(a, xa, b, xb);
    const std::vector<Vec2> wa = geometry_test::Placed(a, xa), wb = geometry_test::Placed(b, xb);
    const double brute = geometry_test::BruteDistance(wa, wb);
    worst = std::max(worst, std::abs(d.distance - brute));
    REQUIRE(d.distance == Approx(brute).margin(1e-12));
    max_iterations = std::max(max_iterations, d.iterations);
    if (brute == 0.0) {
      ++overlapping;
      continue;
    }
    ++separated;
    // The witness points lie on the shapes (at distance 0 from each) and span the distance.
    CHECK(geometry_test::BruteDistance(wa, {d.point_a}) < 1e-12);
    CHECK(geometry_test::BruteDistance(wb, {d.point_b}) < 1e-12);
    CHECK(engine::Length(d.point_b - d.point_a) == Approx(d.distance).epsilon(1e-12));
    // The weights make the points from the simplex.
    Vec2 from_simplex;
    for (int i = 0; i < d.simplex_count; ++i) from_simplex += d.simplex[i].weight * d.simplex[i].point_a;
    CHECK(engine::Length(from_simplex - d.point_a) < 1e-12);
  }
  INFO("worst |gjk − brute| " << worst << ", separated " << separated << ", overlapping " << overlapping
                              << ", most iterations " << max_iterations);
  CHECK(separated > 1000);
  CHECK(overlapping > 300);
  CHECK(max_iterations < kMaxGjkIterations);
}

TEST_CASE("segment distance: crossing, parallel and end cases", "[geometry]") {
  const SegmentDistanceResult cross = SegmentDistance({-1, 0}, {1, 0}, {0, -1}, {0, 1});
  CHECK(cross.distance_squared == 0.0);
  CHECK(cross.fraction1 == 0.5);
  const SegmentDistanceResult parallel = SegmentDistance({0, 0}, {2, 0}, {1, 1}, {3, 1});
  CHECK(parallel.distance_squared == Approx(1.0));
  const SegmentDistanceResult ends = SegmentDistance({0, 0}, {1, 0}, {2, 1}, {3, 2});
  CHECK(ends.fraction1 == 1.0);
  CHECK(ends.fraction2 == 0.0);
  CHECK(ends.distance_squared == Approx(2.0));
}
