// Ray casts against polygons (rounded or not), capsules and segments: hand cases, and random rays
// against rounded polygons checked by root-finding on the GJK distance along the ray.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "geometry/gjk.h"
#include "geometry/ray_cast.h"
#include "geometry_test_util.h"

using engine::Rot;
using engine::Vec2;
using namespace engine::geometry;

namespace {

const Transform kIdentity{};

void CheckHit(const CastOutput& out, double fraction, Vec2 normal) {
  REQUIRE(out.hit);
  CHECK(out.fraction == Approx(fraction).epsilon(1e-12));
  CHECK(out.normal.x == Approx(normal.x).margin(1e-12));
  CHECK(out.normal.y == Approx(normal.y).margin(1e-12));
}

}  // namespace

TEST_CASE("ray cast: a box polygon, square on and turned", "[geometry]") {
  const Polygon box = MakeBox(1, 1);
  CheckHit(RayCastPolygon(box, kIdentity, {{-3, 0.5}, {6, 0}}), 2.0 / 6.0, {-1, 0});
  CHECK(RayCastPolygon(box, kIdentity, {{-3, 0.5}, {6, 0}}).point.x == Approx(-1.0));
  // Placed at (5, 5) and turned a quarter turn: the ray from below meets the face at y = 4.
  CheckHit(RayCastPolygon(box, {{5, 5}, Rot{0, 1}}, {{5.3, 0}, {0, 10}}), 0.4, {0, -1});
  // Misses, stops short, or starts inside: no hit.
  CHECK_FALSE(RayCastPolygon(box, kIdentity, {{-3, 1.5}, {6, 0}}).hit);
  CHECK_FALSE(RayCastPolygon(box, kIdentity, {{-3, 0.5}, {6, 0}, 0.3}).hit);
  CHECK_FALSE(RayCastPolygon(box, kIdentity, {{0, 0}, {6, 0}}).hit);
}

TEST_CASE("ray cast: a rounded box's pushed-out face and corner disc", "[geometry]") {
  Polygon rounded = MakeBox(1, 1);
  rounded.radius = 0.5;
  CheckHit(RayCastPolygon(rounded, kIdentity, {{-3, 0.5}, {6, 0}}), 0.25, {-1, 0});
  // Along the diagonal through the corner (−1, 1): it enters the corner's disc 0.5 before it.
  const double s = std::sqrt(0.5);
  CheckHit(RayCastPolygon(rounded, kIdentity, {{-3, 3}, {6, -6}}), (2 * std::sqrt(2.0) - 0.5) / (6 * std::sqrt(2.0)), {-s, s});
}

TEST_CASE("ray cast: a capsule's side and cap", "[geometry]") {
  const Capsule capsule{{-1, 0}, {1, 0}, 0.5};
  CheckHit(RayCastCapsule(capsule, kIdentity, {{0, 3}, {0, -6}}), 2.5 / 6.0, {0, 1});
  CheckHit(RayCastCapsule(capsule, kIdentity, {{-3, 0}, {6, 0}}), 1.5 / 6.0, {-1, 0});
  // Passing just over the side, or stopping just short of the cap.
  CHECK_FALSE(RayCastCapsule(capsule, kIdentity, {{-3, 0.5001}, {6, 0}}).hit);
  CHECK_FALSE(RayCastCapsule(capsule, kIdentity, {{-3, 0}, {1.49, 0}}).hit);
}

TEST_CASE("ray cast: a segment from either side", "[geometry]") {
  CheckHit(RayCastSegment({-1, 0}, {1, 0}, kIdentity, {{0, -2}, {0, 4}}), 0.5, {0, -1});
  CheckHit(RayCastSegment({-1, 0}, {1, 0}, kIdentity, {{0.5, 2}, {0, -4}}), 0.5, {0, 1});
  CHECK_FALSE(RayCastSegment({-1, 0}, {1, 0}, kIdentity, {{2, -1}, {0, 2}}).hit);
  CHECK_FALSE(RayCastSegment({-1, 0}, {1, 0}, kIdentity, {{-3, 0}, {6, 0}}).hit);  // along it
  // Placed: the segment turned upright at x = 2.
  CheckHit(RayCastSegment({-1, 0}, {1, 0}, {{2, 0}, Rot{0, 1}}, {{0, 0.5}, {4, 0}}), 0.5, {-1, 0});
}

TEST_CASE("ray cast: random rays against rounded polygons match root-finding on GJK", "[geometry]") {
  geometry_test::Random rng(31);
  int hits = 0, misses = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    const Polygon p = MakePolygon(geometry_test::RandomConvexPoints(rng, 3 + trial % 7, rng.Uniform(0.3, 1.0), rng.Uniform(0.3, 1.0)),
                                  trial % 2 == 0 ? 0.0 : rng.Uniform(0.05, 0.4));
    const Transform xf{rng.InBox(0.5), rng.AnyRotation()};
    const Vec2 origin = rng.InBox(3.0), target = rng.InBox(1.5);
    const RayCastInput ray{origin, target - origin};
    const ShapeProxy proxy = MakeProxy(p);
    const auto gap = [&](double t) {  // the point's distance to the rounded surface
      const DistanceOutput d = ShapeDistance(MakeProxy(std::vector<Vec2>{ray.origin + t * ray.translation}, 0.0), {}, proxy, xf);
      return d.distance - p.radius;
    };
    if (gap(0.0) <= 0.0) continue;  // starts inside (or on the surface)
    // The gap is convex along the ray: find its minimum, then the first root before it.
    double lo = 0.0, hi = 1.0;
    for (int i = 0; i < 200; ++i) {
      const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
      (gap(m1) < gap(m2) ? hi : lo) = gap(m1) < gap(m2) ? m2 : m1;
    }
    const CastOutput out = RayCastPolygon(p, xf, ray);
    if (gap(lo) > 1e-9) {
      CHECK_FALSE(out.hit);
      ++misses;
      continue;
    }
    double a = 0.0, b = lo;
    for (int i = 0; i < 100; ++i) (gap(0.5 * (a + b)) > 0.0 ? a : b) = 0.5 * (a + b);
    INFO("trial " << trial << " min gap " << gap(lo) << " at " << lo << ", gap(0) " << gap(0.0) << ", radius " << p.radius);
    REQUIRE(out.hit);
    CHECK(out.fraction == Approx(a).margin(1e-9));
    // The normal points from the core's nearest point out through the hit point.
    const DistanceOutput at = ShapeDistance(MakeProxy(std::vector<Vec2>{out.point}, 0.0), {}, proxy, xf);
    if (p.radius > 0.0) CHECK(engine::Length(out.normal + at.normal) < 1e-6);
    ++hits;
  }
  INFO("hits " << hits << ", misses " << misses);
  CHECK(hits > 300);
  CHECK(misses > 100);
}
