// Polygon, capsule and circle manifolds: hand cases, agreement with the oriented-box and
// circle-box colliders on random placements, and with the GJK distance.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "geometry/gjk.h"
#include "geometry/manifold.h"
#include "geometry_test_util.h"
#include "narrow_phase/collide.h"

using engine::Manifold;
using engine::Rot;
using engine::Vec2;
using namespace engine::geometry;

namespace {

const Transform kIdentity{};

void CheckVec(Vec2 v, Vec2 expected, double eps = 1e-12) {
  CHECK(v.x == Approx(expected.x).margin(eps));
  CHECK(v.y == Approx(expected.y).margin(eps));
}

// The point of `m` nearest to `p` (manifolds list their points in no promised order).
const engine::ContactPoint& Nearest(const Manifold& m, Vec2 p) {
  return engine::LengthSquared(m.points[0].point - p) <= engine::LengthSquared(m.points[m.point_count - 1].point - p)
             ? m.points[0]
             : m.points[m.point_count - 1];
}

double Deepest(const Manifold& m) {
  double d = -INFINITY;
  for (int i = 0; i < m.point_count; ++i) d = std::max(d, m.points[i].depth);
  return d;
}

}  // namespace

TEST_CASE("polygons: a box resting on a box gives two points at the right depth", "[geometry]") {
  // Ground [−1, 1] × [−0.5, 0.5]; a unit box centred at (0.2, 0.99) sinks 0.01 into it.
  Manifold m;
  REQUIRE(CollidePolygons(MakeBox(1, 0.5), kIdentity, MakeBox(0.5, 0.5), {{0.2, 0.99}, Rot{}}, &m));
  CheckVec(m.normal, {0, 1});
  REQUIRE(m.point_count == 2);
  // Surfaces at y = 0.5 (ground) and 0.49 (box): the points sit at y = 0.495, at the box's ends.
  const engine::ContactPoint& left = Nearest(m, {-0.3, 0.495});
  const engine::ContactPoint& right = Nearest(m, {0.7, 0.495});
  CheckVec(left.point, {-0.3, 0.495});
  CheckVec(right.point, {0.7, 0.495});
  CHECK(left.depth == Approx(0.01).epsilon(1e-10));
  CHECK(right.depth == Approx(0.01).epsilon(1e-10));
  CHECK(left.id != right.id);
}

TEST_CASE("polygons: the margin convention of the narrow phase", "[geometry]") {
  const Polygon ground = MakeBox(1, 0.5), box = MakeBox(0.5, 0.5);
  Manifold m;
  m.point_count = 7;
  CHECK_FALSE(CollidePolygons(ground, kIdentity, box, {{0, 1.03}, Rot{}}, &m, 0.02));
  CHECK(m.point_count == 7);  // left alone
  REQUIRE(CollidePolygons(ground, kIdentity, box, {{0, 1.01}, Rot{}}, &m, 0.02));
  CHECK(m.point_count == 2);
  CHECK(m.points[0].depth == Approx(-0.01).epsilon(1e-9));
  REQUIRE(CollidePolygons(ground, kIdentity, box, {{0, 1.0}, Rot{}}, &m));
  CHECK(m.points[0].depth == Approx(0.0).margin(1e-15));  // touching: depth 0
}

TEST_CASE("polygons: ids stay the same while the box slides a little", "[geometry]") {
  const Polygon ground = MakeBox(3, 0.5), box = MakeBox(0.5, 0.5);
  Manifold first, later;
  REQUIRE(CollidePolygons(ground, kIdentity, box, {{0.0, 0.995}, engine::MakeRot(0.001)}, &first));
  REQUIRE(CollidePolygons(ground, kIdentity, box, {{0.05, 0.996}, engine::MakeRot(-0.002)}, &later));
  REQUIRE(first.point_count == 2);
  REQUIRE(later.point_count == 2);
  CHECK(Nearest(first, {-0.5, 0.5}).id == Nearest(later, {-0.45, 0.5}).id);
  CHECK(Nearest(first, {0.5, 0.5}).id == Nearest(later, {0.55, 0.5}).id);
}

TEST_CASE("polygons: agree with CollideOrientedBoxes on random oriented boxes", "[geometry]") {
  geometry_test::Random rng(99);
  int compared = 0, corner_cases = 0, farther_than_margin = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const engine::OrientedBox a{rng.InBox(0.5), {rng.Uniform(0.2, 1.0), rng.Uniform(0.2, 1.0)}, rng.AnyRotation()};
    const engine::OrientedBox b{rng.InBox(2.0), {rng.Uniform(0.2, 1.0), rng.Uniform(0.2, 1.0)}, rng.AnyRotation()};
    const double margin = 0.2;
    Manifold expected, got;
    const bool hit_expected = engine::CollideOrientedBoxes(a, b, &expected, margin);
    const bool hit = CollidePolygons(MakeBox(a.half_extents.x, a.half_extents.y), {a.center, a.rotation},
                                     MakeBox(b.half_extents.x, b.half_extents.y), {b.center, b.rotation}, &got, margin);
    const bool same_normal = hit && hit_expected && engine::Length(got.normal - expected.normal) < 1e-9;
    if (same_normal && got.point_count == expected.point_count) {
      ++compared;
      for (int i = 0; i < got.point_count; ++i) {
        const engine::ContactPoint& e = Nearest(expected, got.points[i].point);
        CHECK(engine::Length(e.point - got.points[i].point) < 1e-9);
        CHECK(got.points[i].depth == Approx(e.depth).margin(1e-9));
      }
      continue;
    }
    // Otherwise the boxes are apart and their closest features are two corners: the oriented-box
    // collider gives a face normal (or nothing), this one the corner-to-corner line, or nothing
    // when that is longer than the margin. Either way GJK has the true separation.
    const DistanceOutput d = ShapeDistance(MakeProxy(MakeBox(a.half_extents.x, a.half_extents.y)), {a.center, a.rotation},
                                           MakeProxy(MakeBox(b.half_extents.x, b.half_extents.y)), {b.center, b.rotation});
    REQUIRE(d.distance > kCoreGapTolerance);
    if (!hit) {
      CHECK(d.separation > margin);
      ++farther_than_margin;
      continue;
    }
    ++corner_cases;
    REQUIRE(got.point_count == 1);
    CHECK(got.points[0].depth == Approx(-d.separation).margin(1e-12));
    CheckVec(got.normal, d.normal, 1e-9);
  }
  INFO("compared " << compared << ", corner to corner " << corner_cases << ", beyond the margin " << farther_than_margin);
  CHECK(compared > 2000);
  CHECK(corner_cases > 20);
}

TEST_CASE("capsules: a capsule on a capsule gives two points", "[geometry]") {
  const Capsule capsule{{-1, 0}, {1, 0}, 0.25};
  Manifold m;
  // The upper capsule's core at y = 0.49, shifted right by 0.3: surfaces at 0.25 and 0.24.
  REQUIRE(CollideCapsules(capsule, kIdentity, capsule, {{0.3, 0.49}, Rot{}}, &m));
  CheckVec(m.normal, {0, 1});
  REQUIRE(m.point_count == 2);
  CheckVec(Nearest(m, {-0.7, 0.245}).point, {-0.7, 0.245});
  CheckVec(Nearest(m, {1.0, 0.245}).point, {1.0, 0.245});
  CHECK(m.points[0].depth == Approx(0.01).epsilon(1e-9));
  CHECK(m.points[1].depth == Approx(0.01).epsilon(1e-9));
  // Stacked exactly on top (the closest points of the two cores are then both ends): still two.
  REQUIRE(CollideCapsules(capsule, kIdentity, capsule, {{0.0, 0.5}, Rot{}}, &m, 0.01));
  CHECK(m.point_count == 2);
  CheckVec(m.normal, {0, 1});
  // Resting 0.005 apart within a margin: two speculative points.
  REQUIRE(CollideCapsules(capsule, kIdentity, capsule, {{0.0, 0.505}, engine::MakeRot(0.002)}, &m, 0.02));
  CHECK(m.point_count == 2);
  CHECK(Deepest(m) < 0.0);
}

TEST_CASE("capsules: crossed capsules touch at one point, end caps corner to corner", "[geometry]") {
  const Capsule capsule{{-1, 0}, {1, 0}, 0.25};
  Manifold m;
  REQUIRE(CollideCapsules(capsule, kIdentity, capsule, {{0.0, 0.4}, Rot{0.0, 1.0}}, &m, 0.0));
  // The upper capsule stands upright: its lower cap's centre at (0, −0.6) pokes through; lifted
  // by 1.1 that cap would rest on the lower capsule (0.25 + 0.25 above its core).
  CheckVec(m.normal, {0, 1});
  REQUIRE(m.point_count == 1);
  CHECK(m.points[0].depth == Approx(1.1).epsilon(1e-12));
  CheckVec(m.points[0].point, {0, -0.3});
  // End to end along a diagonal: caps at (1, 0) and (1.3, 0.4), 0.5 apart, radii 0.5 total.
  REQUIRE(CollideCapsules(capsule, kIdentity, capsule, {{2.3, 0.4}, Rot{}}, &m, 0.01));
  REQUIRE(m.point_count == 1);
  CheckVec(m.normal, {0.6, 0.8});
  CHECK(m.points[0].depth == Approx(0.0).margin(1e-12));
  CheckVec(m.points[0].point, {1.15, 0.2});
}

TEST_CASE("capsules: a capsule lying on a box gives two points", "[geometry]") {
  Manifold m;
  const Capsule capsule{{-0.5, 0}, {0.5, 0}, 0.2};
  REQUIRE(CollideCapsulePolygon(capsule, {{0.1, 0.695}, Rot{}}, MakeBox(1, 0.5), kIdentity, &m));
  CheckVec(m.normal, {0, -1});  // from the capsule (A) down to the box (B)
  REQUIRE(m.point_count == 2);
  CHECK(m.points[0].depth == Approx(0.005).epsilon(1e-9));
  CHECK(m.points[1].depth == Approx(0.005).epsilon(1e-9));
  CheckVec(Nearest(m, {-0.4, 0.4975}).point, {-0.4, 0.4975});
  CheckVec(Nearest(m, {0.6, 0.4975}).point, {0.6, 0.4975});
}

TEST_CASE("polygons: rounded corners meet along the line between them", "[geometry]") {
  Polygon rounded = MakeBox(1, 1);
  rounded.radius = 0.1;
  // Core corners (1, 1) and (1.3, 1.3): 0.3·√2 apart, surfaces 0.3·√2 − 0.2 apart.
  Manifold m;
  REQUIRE(CollidePolygons(rounded, kIdentity, rounded, {{2.3, 2.3}, Rot{}}, &m, 0.3));
  REQUIRE(m.point_count == 1);
  CheckVec(m.normal, {std::sqrt(0.5), std::sqrt(0.5)});
  CHECK(m.points[0].depth == Approx(0.2 - 0.3 * std::sqrt(2.0)).epsilon(1e-12));
  CheckVec(m.points[0].point, {1.15, 1.15});
  CHECK_FALSE(CollidePolygons(rounded, kIdentity, rounded, {{2.3, 2.3}, Rot{}}, &m, 0.2));
  // Face to face they give two points at the surfaces' midway.
  REQUIRE(CollidePolygons(rounded, kIdentity, rounded, {{0.5, 2.19}, Rot{}}, &m));
  REQUIRE(m.point_count == 2);
  CHECK(m.points[0].depth == Approx(0.01).epsilon(1e-9));
  CheckVec(Nearest(m, {1, 1.095}).point, {1, 1.095});
}

TEST_CASE("polygons: the deepest point matches GJK's separation on random pairs", "[geometry]") {
  geometry_test::Random rng(5);
  int checked = 0, beyond = 0, exact = 0;
  double worst = 0.0;
  for (int trial = 0; trial < 6000; ++trial) {
    const Polygon a = MakePolygon(geometry_test::RandomConvexPoints(rng, 3 + trial % 8, rng.Uniform(0.3, 1.2), rng.Uniform(0.3, 1.2)),
                                  trial % 3 == 0 ? 0.0 : rng.Uniform(0.0, 0.3));
    const Polygon b = MakePolygon(geometry_test::RandomConvexPoints(rng, 3 + trial % 5, rng.Uniform(0.3, 1.2), rng.Uniform(0.3, 1.2)),
                                  trial % 2 == 0 ? 0.0 : rng.Uniform(0.0, 0.3));
    const Transform xa{rng.InBox(0.2), rng.AnyRotation()}, xb{rng.InBox(2.5), rng.AnyRotation()};
    const double margin = 0.1;
    const DistanceOutput d = ShapeDistance(MakeProxy(a), xa, MakeProxy(b), xb);
    if (d.distance <= kCoreGapTolerance) continue;  // overlapping cores: no distance to compare
    Manifold m;
    const bool hit = CollidePolygons(a, xa, b, xb, &m, margin);
    if (!hit) {
      CHECK(d.separation > margin);
      ++beyond;
      continue;
    }
    ++checked;
    // Exact, but for the reference face's hysteresis: A's face stays the reference unless B's
    // separates by kFaceTolerance more, so A's may be chosen when B's is up to that much better.
    const double error = std::abs(-Deepest(m) - d.separation);
    worst = std::max(worst, error);
    exact += error <= 1e-12 ? 1 : 0;
    CHECK(error <= kFaceTolerance);
    CHECK(engine::Dot(m.normal, d.normal) > 0.999);
  }
  INFO("checked " << checked << " (exact " << exact << "), beyond the margin " << beyond << ", worst error " << worst);
  CHECK(checked > 300);
  CHECK(exact >= checked - checked / 50);
}

TEST_CASE("circle-polygon: agrees with CollideCircleOrientedBox", "[geometry]") {
  geometry_test::Random rng(11);
  int hits = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const engine::OrientedBox box{rng.InBox(0.5), {rng.Uniform(0.2, 1.0), rng.Uniform(0.2, 1.0)}, rng.AnyRotation()};
    const Vec2 center = rng.InBox(2.0);
    const double radius = rng.Uniform(0.1, 0.8);
    Manifold expected, got;
    const bool e = engine::CollideCircleOrientedBox(center, radius, box, &expected, 0.05);
    const bool g = CollideCirclePolygon(center, radius, MakeBox(box.half_extents.x, box.half_extents.y),
                                        {box.center, box.rotation}, &got, 0.05);
    REQUIRE(e == g);
    if (!g) continue;
    ++hits;
    REQUIRE(got.point_count == 1);
    CheckVec(got.normal, expected.normal, 1e-9);
    CheckVec(got.points[0].point, expected.points[0].point, 1e-9);
    CHECK(got.points[0].depth == Approx(expected.points[0].depth).margin(1e-9));
  }
  CHECK(hits > 3000);
}

TEST_CASE("circle-polygon: a rounded polygon's corner and face", "[geometry]") {
  Polygon rounded = MakeBox(1, 1);
  rounded.radius = 0.2;
  Manifold m;
  // Circle of radius 0.3 at (1.3, 1.4): 0.5 from the core corner, touching the skin exactly.
  REQUIRE(CollideCirclePolygon({1.3, 1.4}, 0.3, rounded, kIdentity, &m));
  CheckVec(m.normal, {-0.6, -0.8});
  CHECK(m.points[0].depth == Approx(0.0).margin(1e-12));
  CheckVec(m.points[0].point, {1.0 + 0.2 * 0.6, 1.0 + 0.2 * 0.8});
  // Above the face, 0.05 into the skin.
  REQUIRE(CollideCirclePolygon({0.3, 1.45}, 0.3, rounded, kIdentity, &m));
  CheckVec(m.normal, {0, -1});
  CHECK(m.points[0].depth == Approx(0.05).epsilon(1e-12));
}

TEST_CASE("polygons: 64-vertex polygons agree with brute-force separating axes", "[geometry]") {
  // The face search walks round the other polygon instead of scanning it; the least penetration
  // over every face normal of both, scanned in full here, must come out the same.
  geometry_test::Random rng(64);
  int overlapping = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Polygon a = MakePolygon(geometry_test::RandomConvexPoints(rng, 64, rng.Uniform(0.5, 1.5), rng.Uniform(0.5, 1.5)));
    const Polygon b = MakePolygon(geometry_test::RandomConvexPoints(rng, 3 + trial % 62, rng.Uniform(0.2, 1.2), rng.Uniform(0.2, 1.2)));
    const Transform xa{rng.InBox(0.2), rng.AnyRotation()}, xb{rng.InBox(2.0), rng.AnyRotation()};
    const std::vector<Vec2> wa = geometry_test::Placed(geometry_test::CorePoints(a), xa);
    const std::vector<Vec2> wb = geometry_test::Placed(geometry_test::CorePoints(b), xb);
    const auto max_separation = [](const std::vector<Vec2>& ref, const std::vector<Vec2>& other) {
      double best = -INFINITY;
      for (std::size_t i = 0; i < ref.size(); ++i) {
        const Vec2 n = EdgeNormal(ref[i], ref[(i + 1) % ref.size()]);
        double deepest = INFINITY;
        for (const Vec2& v : other) deepest = std::min(deepest, engine::Dot(n, v - ref[i]));
        best = std::max(best, deepest);
      }
      return best;
    };
    const double separation = std::max(max_separation(wa, wb), max_separation(wb, wa));
    Manifold m;
    const bool hit = CollidePolygons(a, xa, b, xb, &m);
    REQUIRE(hit == (separation <= 0.0));
    if (!hit) continue;
    ++overlapping;
    // The reference face may be A's when B's separates by up to kFaceTolerance more.
    CHECK(Deepest(m) >= -separation - 1e-12);
    CHECK(Deepest(m) <= -separation + kFaceTolerance + 1e-12);
  }
  CHECK(overlapping > 500);
}
