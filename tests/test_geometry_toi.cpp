// Time of impact by conservative advancement: a fast thin dart against a thin wall (against the
// analytic time), a spinning box (against a brute-force scan of the same sweep), misses.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "geometry/time_of_impact.h"

using engine::Rot;
using engine::Vec2;
using namespace engine::geometry;

namespace {

// A static sweep: the shape stays where it is.
Sweep Still(Vec2 center) { return {{0, 0}, center, center, Rot{}, Rot{}}; }

const ShapeProxy& Wall() {
  // 10 cm thick, 4 m tall, its near face at x = 10.5.
  static const ShapeProxy wall = MakeProxy(MakeOffsetBox(0.05, 2.0, {10.55, 0.0}, Rot{}));
  return wall;
}

}  // namespace

TEST_CASE("toi: a dart at 2000 m/s against a 10 cm wall", "[geometry]") {
  // A thin triangle, tip at x = 0.5; its centre of mass (the centroid) at x = 1/6.
  const ShapeProxy dart = MakeProxy(std::vector<Vec2>{{0, -0.01}, {0.5, 0}, {0, 0.01}}, 0.0);
  const Vec2 centroid{0.5 / 3.0, 0.0};
  const double step = 2000.0 / 60.0;  // 33.3 m in one step, 330 times the wall's thickness
  const Sweep sweep{centroid, centroid, centroid + Vec2{step, 0}, Rot{}, Rot{}};
  // At the step's end the dart is far past the wall: a discrete test would never see it.
  CHECK(ShapeDistance(dart, SweepTransform(sweep, 1.0), Wall(), {}).distance > 20.0);
  const ToiOutput toi = TimeOfImpact(dart, sweep, Wall(), Still({0, 0}));
  REQUIRE(toi.state == ToiState::kHit);
  // The tip reaches target separation after moving 10 − target.
  const ToiSettings settings;
  const double analytic = (10.0 - settings.target) / step;
  INFO("t = " << toi.fraction << " (analytic " << analytic << "), iterations " << toi.iterations);
  CHECK(std::abs(toi.fraction - analytic) * step <= settings.tolerance);
  CHECK(std::abs(toi.separation - settings.target) <= settings.tolerance);
  CHECK(toi.iterations <= 3);
}

TEST_CASE("toi: a spinning box against a wall matches a brute-force scan of the sweep", "[geometry]") {
  const ShapeProxy box = MakeProxy(MakeBox(0.5, 0.5));
  // Moves 1 m towards the wall while turning 1.2 rad.
  const Sweep sweep{{0, 0}, {9.0, 0}, {10.0, 0}, Rot{}, engine::MakeRot(1.2)};
  const ToiSettings settings;
  const ToiOutput toi = TimeOfImpact(box, sweep, Wall(), Still({0, 0}));
  REQUIRE(toi.state == ToiState::kHit);
  // The same sweep scanned finely: the separation is the wall's x minus the farthest corner's.
  const auto separation = [&](double t) {
    const Transform xf = SweepTransform(sweep, t);
    double farthest = -INFINITY;
    for (int i = 0; i < box.count; ++i) farthest = std::max(farthest, TransformPoint(xf, box.points[i]).x);
    return 10.5 - farthest;
  };
  const auto first_within = [&](double level) {
    for (int k = 0; k <= 1000000; ++k) {
      if (separation(k * 1e-6) <= level) return k * 1e-6;
    }
    return 2.0;
  };
  const double earliest = first_within(settings.target + settings.tolerance);
  const double latest = first_within(settings.target);
  REQUIRE(latest < 1.0);
  INFO("t = " << toi.fraction << " in [" << earliest << ", " << latest << "], iterations " << toi.iterations);
  CHECK(toi.fraction >= earliest - 1e-6);
  CHECK(toi.fraction <= latest + 1e-6);
  CHECK(separation(toi.fraction) == Approx(toi.separation).margin(1e-12));
  CHECK(toi.iterations < 20);
  // Capped at one iteration it fails, but the time it reports is still safe.
  ToiSettings capped = settings;
  capped.max_iterations = 1;
  const ToiOutput failed = TimeOfImpact(box, sweep, Wall(), Still({0, 0}), capped);
  CHECK(failed.state == ToiState::kFailed);
  CHECK(failed.fraction < earliest);
}

TEST_CASE("toi: no false hit for a miss", "[geometry]") {
  const ShapeProxy dart = MakeProxy(std::vector<Vec2>{{0, -0.01}, {0.5, 0}, {0, 0.01}}, 0.0);
  // Passing 5 cm over the wall's top (y = 2), fast.
  const Vec2 start{0, 2.06};
  const ToiOutput over = TimeOfImpact(dart, {{0, 0}, start, start + Vec2{33.3, 0}, Rot{}, Rot{}}, Wall(), Still({0, 0}));
  CHECK(over.state == ToiState::kSeparated);
  CHECK(over.fraction == 1.0);
  // Moving away, spinning.
  const ToiOutput away = TimeOfImpact(dart, {{0, 0}, {0, 0}, {-5, 0}, Rot{}, engine::MakeRot(2.0)}, Wall(), Still({0, 0}));
  CHECK(away.state == ToiState::kSeparated);
  // Stopping short of the wall.
  const ToiOutput short_of = TimeOfImpact(dart, {{0, 0}, {0, 0}, {9.9, 0}, Rot{}, Rot{}}, Wall(), Still({0, 0}));
  CHECK(short_of.state == ToiState::kSeparated);
}

TEST_CASE("toi: overlapping at the start, and rounded shapes", "[geometry]") {
  const ShapeProxy box = MakeProxy(MakeBox(0.5, 0.5));
  const ToiOutput overlapped = TimeOfImpact(box, Still({10.3, 0}), Wall(), Still({0, 0}));
  CHECK(overlapped.state == ToiState::kOverlapped);
  CHECK(overlapped.fraction == 0.0);
  // A ball (a point with radius 0.25) moving right 20 m: contact when its centre is at
  // 10.5 − 0.25 − target.
  const ShapeProxy ball = MakeProxy(std::vector<Vec2>{{0, 0}}, 0.25);
  const ToiOutput hit = TimeOfImpact(ball, {{0, 0}, {0, 1}, {20, 1}, Rot{}, Rot{}}, Wall(), Still({0, 0}));
  REQUIRE(hit.state == ToiState::kHit);
  CHECK(hit.fraction * 20.0 == Approx(10.5 - 0.25 - ToiSettings{}.target).margin(ToiSettings{}.tolerance));
}

TEST_CASE("toi: the sweep's transform at its ends and in between", "[geometry]") {
  const Sweep sweep{{0.5, 0}, {1, 2}, {3, 2}, Rot{}, Rot{0, 1}};
  const Transform start = SweepTransform(sweep, 0.0), end = SweepTransform(sweep, 1.0);
  // The centre of mass (local (0.5, 0)) is where the sweep says; the frame origin follows.
  CHECK(TransformPoint(start, {0.5, 0}).x == Approx(1.0));
  CHECK(TransformPoint(end, {0.5, 0}).x == Approx(3.0));
  CHECK(end.rotation.s == Approx(1.0));
  CHECK(end.position.y == Approx(2.0 - 0.5));
  // Halfway the blend of 0 and π/2 is exactly π/4.
  const Transform half = SweepTransform(sweep, 0.5);
  CHECK(half.rotation.c == Approx(std::sqrt(0.5)));
  CHECK(half.rotation.s == Approx(std::sqrt(0.5)));
}
