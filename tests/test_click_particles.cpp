// The click on soft bodies and fluid (docs/click-rule.md, "Particles"): a click that hits no
// ball changes the velocity of every soft-body and fluid particle within click.particle_radius R
// of it by speed · 2u (u = d / R up to ½), then speed · 2(1 − u), away from the click; a click
// that hits a ball acts on the ball exactly as before and on nothing else. Expected velocity
// changes are worked out by hand in the comments.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "game/click.h"
#include "game/event_log.h"
#include "game/scene.h"
#include "game/session.h"
#include "world_builders.h"

namespace {

using engine::Vec2;

game::Scene Parse(const std::string& json) {
  game::Expected<game::Scene> scene = game::ParseScene(json, "click.json", "click");
  if (!scene.HasValue()) FAIL(scene.Error().message);
  return scene.Value();
}

game::InputEvent ClickWorld(Vec2 at, std::int64_t step = 0) {
  game::InputEvent event;
  event.step = step;
  event.kind = game::EventKind::kClickWorld;
  event.at = at;
  return event;
}

void CheckVelocity(Vec2 v, Vec2 expected) {
  CHECK(v.x == Approx(expected.x).margin(1e-12));
  CHECK(v.y == Approx(expected.y).margin(1e-12));
}

}  // namespace

TEST_CASE("particle click: the velocity change rises to half the radius and falls to nothing at it",
          "[click][particles]") {
  const Vec2 p{1, 1};
  const double radius = 2, speed = 4;
  const auto dv = [&](Vec2 offset) { return game::ParticleClickVelocity(p + offset, p, radius, speed); };
  CHECK(dv({0, 0}) == Vec2{});                   // at the click: no direction, nothing (no NaN)
  CheckVelocity(dv({0.5, 0}), {2, 0});           // u = 1/4: 4 · 2 · 1/4 = 2
  CheckVelocity(dv({-1, 0}), {-4, 0});           // u = 1/2: the full 4, away from the click
  CheckVelocity(dv({0, -1.5}), {0, -2});         // u = 3/4: 4 · 2 · 1/4 = 2
  CheckVelocity(dv({0.3, 0.4}), {1.2, 1.6});     // d = 0.5 on a 3-4-5 line: 2 along (0.6, 0.8)
  CheckVelocity(dv({-1.2, -0.9}), {-1.6, -1.2}); // d = 1.5: 2 along (−0.8, −0.6)
  CHECK(dv({1.2, 1.6}) == Vec2{});               // d = 2, the edge: nothing
  CHECK(dv({0, 2.4}) == Vec2{});                 // beyond it
  CHECK(game::ParticleClickVelocity({2, 1}, p, radius, 0.0) == Vec2{});  // speed 0: nothing
}

TEST_CASE("particle click: a soft box's 3 × 3 lattice clicked at its centre", "[click][particles]") {
  engine::World world(testing::NoGravity());
  engine::SoftBodyDef def;
  def.shape = {engine::ShapeType::kBox, 0, {0.15, 0.15}};  // 0.3 × 0.3 at spacing 0.1: particles at −0.1, 0, 0.1
  def.spacing = 0.1;
  const engine::SoftBodyId soft = world.CreateSoftBody(def);
  const auto x = world.SoftBodyPositions(soft);
  const auto v = world.SoftBodyVelocities(soft);
  REQUIRE(x.size() == 9);
  CheckVelocity(x[0], {-0.1, -0.1});
  CheckVelocity(x[4], {0, 0});

  SECTION("radius 0.4: every particle but the centre one is pushed") {
    // R = 0.4, speed 2. Edge middles: d = 0.1, u = 1/4, 2 · 2 · 1/4 = 1 m/s outwards. Corners:
    // d = 0.1·√2, u = √2/4, 2 · 2 · √2/4 = √2 along the diagonal: (±1, ±1).
    CHECK(game::PushParticles(world, {0, 0}, 0.4, 2.0) == 8);
    CheckVelocity(v[4], {0, 0});
    CheckVelocity(v[1], {0, -1});
    CheckVelocity(v[3], {-1, 0});
    CheckVelocity(v[5], {1, 0});
    CheckVelocity(v[7], {0, 1});
    CheckVelocity(v[0], {-1, -1});
    CheckVelocity(v[2], {1, -1});
    CheckVelocity(v[6], {-1, 1});
    CheckVelocity(v[8], {1, 1});
  }
  SECTION("radius 0.12: the corners lie beyond it, the middles near its edge") {
    // Edge middles: u = 0.1 / 0.12 = 5/6, 2 · 2 · (1 − 5/6) = 2/3 m/s. Corners: d = 0.1414 > 0.12.
    CHECK(game::PushParticles(world, {0, 0}, 0.12, 2.0) == 4);
    CheckVelocity(v[5], {2.0 / 3.0, 0});
    CheckVelocity(v[7], {0, 2.0 / 3.0});
    for (const std::size_t corner : {0, 2, 6, 8}) CHECK(v[corner] == Vec2{});
  }
  SECTION("from the side, the whole body is pushed away") {
    // The click 0.3 m left of the centre, R = 1, speed 3: the left column at d = 0.2 (u = 0.2,
    // 3 · 0.4 = 1.2 m/s), the middle at d = 0.3 (u = 0.3, 1.8 m/s), the right at 0.4 (2.4 m/s).
    CHECK(game::PushParticles(world, {-0.3, 0}, 1.0, 3.0) == 9);
    CheckVelocity(v[3], {1.2, 0});
    CheckVelocity(v[4], {1.8, 0});
    CheckVelocity(v[5], {2.4, 0});
    // The top right corner, offset (0.4, 0.1) from the click: d = 0.412 < R/2, so the change is
    // 3 · 2 · (d / R) along the offset / d, which is 6 · (0.4, 0.1).
    CheckVelocity(v[8], {2.4, 0.6});
  }
}

TEST_CASE("particle click: a row of fluid particles pushed along it", "[click][particles]") {
  engine::World world(testing::NoGravity());
  engine::FluidDef def;
  def.region = {{0, 0}, {0.3, 0.1}};  // particles at x = 0.05, 0.15, 0.25, y = 0.05
  def.spacing = 0.1;
  REQUIRE(world.AddFluid(def) == 3);
  // From (−0.35, 0.05), R = 1, speed 5: d = 0.4, 0.5, 0.6 give 5 · 0.8, 5 · 1, 5 · 0.8.
  CHECK(game::PushParticles(world, {-0.35, 0.05}, 1.0, 5.0) == 3);
  const auto v = world.FluidVelocities();
  CheckVelocity(v[0], {4, 0});
  CheckVelocity(v[1], {5, 0});
  CheckVelocity(v[2], {4, 0});
  // Again from the far side, closer: d = 0.25, 0.15, 0.05 with R = 0.5 (u = 1/2, 3/10, 1/10).
  CHECK(game::PushParticles(world, {0.3, 0.05}, 0.5, 5.0) == 3);
  CheckVelocity(v[0], {4 - 5, 0});
  CheckVelocity(v[1], {5 - 3, 0});
  CheckVelocity(v[2], {4 - 1, 0});
}

TEST_CASE("particle click: a click on a ball acts on the ball exactly as before, and on nothing else",
          "[click][particles]") {
  const std::string ball = R"({"id": "ball", "shape": "circle", "radius": 0.5, "position": [0, 1], "mass": 2})";
  const game::Scene with_water = Parse(std::string(R"({"gravity": [0, 0], "bodies": [)") + ball +
                                       R"(], "fluids": [{"region": [[-1, 0], [1, 0.4]], "spacing": 0.1}],
                                          "soft_bodies": [{"shape": "circle", "radius": 0.3, "position": [0.9, 1.2]}]})");
  const game::Scene alone = Parse(std::string(R"({"gravity": [0, 0], "bodies": [)") + ball + "]}");
  game::Session wet(with_water, {}, 800, 600);
  game::Session dry(alone, {}, 800, 600);
  const Vec2 p{0.3, 0.8};  // inside the ball, within 1 m of fluid and soft particles
  wet.ApplyEvent(ClickWorld(p));
  dry.ApplyEvent(ClickWorld(p));
  const Vec2 wet_v = wet.World().State(engine::BodyId{0}).velocity;
  const Vec2 dry_v = dry.World().State(engine::BodyId{0}).velocity;
  CHECK(wet_v.x == dry_v.x);  // bit for bit
  CHECK(wet_v.y == dry_v.y);
  // The contract's impulse: d = √(0.09 + 0.04), J = 10 · d / 0.5 along (c − p) / d, v = J / 2.
  CheckVelocity(dry_v, {10 * (-0.3) / 0.5 / 2, 10 * 0.2 / 0.5 / 2});
  for (const Vec2 v : wet.World().FluidVelocities()) CHECK(v == Vec2{});
  for (const Vec2 v : wet.World().SoftBodyVelocities(wet.World().SoftBodyIds()[0])) CHECK(v == Vec2{});
  CHECK(wet.Events().Hits() == 1);
  CHECK(wet.Events().ParticlePushes() == 0);
}

TEST_CASE("particle click: the events summary counts clicks that pushed particles", "[click][particles]") {
  const game::Scene scene = Parse(R"({"gravity": [0, 0], "click": {"particle_radius": 0.5},
    "bodies": [{"id": "ball", "shape": "circle", "radius": 0.5, "position": [5, 5]}],
    "fluids": [{"region": [[-1, 0], [1, 0.4]], "spacing": 0.1}]})");
  game::Session session(scene, {}, 800, 600);
  session.ApplyEvent(ClickWorld({5, 5.2}));   // the ball
  session.ApplyEvent(ClickWorld({0, 0.6}));   // 0.25 m above the water's top row (y = 0.35): pushes it
  session.ApplyEvent(ClickWorld({0, 1.2}));   // 0.85 m above it, R = 0.5: a miss
  CHECK(session.Events().Hits() == 1);
  CHECK(session.Events().ParticlePushes() == 1);
  CHECK(session.Events().Misses().size() == 1);
  CHECK(game::EventSummary(session.Events(), session.EventsLeft(), false) ==
        "events: 3 clicks applied, 1 hit a ball, 1 pushed particles, 1 missed (--misses lists where)");
  // The water under the second click was pushed down, and only within 0.5 m of it.
  const auto x = session.World().FluidPositions();
  const auto v = session.World().FluidVelocities();
  int pushed = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double d = engine::Length(x[i] - Vec2{0, 0.6});
    if (d < 0.5) {
      ++pushed;
      CHECK(v[i].y < 0);
    } else {
      CHECK(v[i] == Vec2{});
    }
  }
  CHECK(pushed > 0);
}
