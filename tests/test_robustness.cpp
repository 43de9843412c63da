// Extreme but valid scenes (issue 9): 100 000 bodies, bodies of 1 mm and 1 km, 10 000 m/s, mass
// ratios of 10⁶, steps of 1/1000 s and 1/10 s. Each must stay finite, end, and hold memory in
// proportion to the scene; where the engine also owes physics (no tunnelling), that is checked.
#include <catch2/catch.hpp>

#include "print_ids.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "bench/soak.h"
#include "game/default_scene.h"
#include "game/scene.h"
#include "game/script.h"
#include "game/session.h"

namespace {

// The first non-finite number in the world, named by body, or "" when all are finite.
std::string FirstNonFinite(const engine::World& world) {
  for (const engine::BodyId id : world.BodyIds()) {
    const engine::BodyState& s = world.State(id);
    for (double v : {s.position.x, s.position.y, s.velocity.x, s.velocity.y, s.angle, s.angular_velocity}) {
      if (!std::isfinite(v)) {
        return "body " + std::to_string(id.index) + " after step " + std::to_string(world.StepCount());
      }
    }
  }
  return "";
}

void RequireFinite(const engine::World& world) {
  const std::string bad = FirstNonFinite(world);
  INFO("not finite: " << bad);
  REQUIRE(bad.empty());
}

// Steps until `steps` are done, requiring finite state after each.
void StepFinite(engine::World& world, int steps) {
  for (int i = 0; i < steps; ++i) {
    world.Step();
    if (!FirstNonFinite(world).empty()) RequireFinite(world);
  }
}

game::Scene ParseOrFail(std::string_view json) {
  game::Expected<game::Scene> scene = game::ParseScene(json, "extreme.json", "extreme");
  if (!scene.HasValue()) FAIL(scene.Error().message);
  return scene.Value();
}

std::string Number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

// The lowest point of a body.
double Bottom(const engine::World& world, engine::BodyId id) { return world.BodyBounds(id).lower.y; }

}  // namespace

TEST_CASE("extreme: 100 000 bodies load, step and stay finite, in memory linear in the count",
          "[robustness][extreme]") {
  // Circles and boxes scattered at random (seeded) over a 1 km floor, some overlapping, all
  // falling: contacts, overlap recovery and the broad phase at scale, through the scene loader.
  // In scene order by x: in random order the sweep and prune's first sort is an insertion sort,
  // quadratic (27 s for the first step here, reported to the engine's owner).
  constexpr int kBodies = 100'000;
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> x(-500.0, 500.0), y(0.5, 100.0), size(0.1, 0.5);
  std::vector<double> xs(kBodies);
  for (double& v : xs) v = x(rng);
  std::sort(xs.begin(), xs.end());
  std::string json = R"({"name": "crowd", "bodies": [
    {"id": "floor", "shape": "box", "size": [1100, 1], "position": [0, -0.5], "static": true})";
  for (int i = 1; i < kBodies; ++i) {
    const std::string at = "[" + Number(xs[i]) + ", " + Number(y(rng)) + "]";
    if (i % 2 == 0) {
      json += ",\n{\"shape\": \"circle\", \"radius\": " + Number(size(rng)) + ", \"position\": " + at + "}";
    } else {
      json += ",\n{\"shape\": \"box\", \"size\": [" + Number(2 * size(rng)) + ", " + Number(2 * size(rng)) +
              "], \"position\": " + at + "}";
    }
  }
  json += "]}";

  const std::size_t heap_before = soak::HeapBytesInUse();
  game::Scene scene = ParseOrFail(json);
  json.clear();
  json.shrink_to_fit();
  REQUIRE(scene.bodies.size() == kBodies);
  engine::World world = game::BuildWorld(scene);
  StepFinite(world, 3);
  const std::size_t heap_after = soak::HeapBytesInUse();
  const double bytes_per_body = (static_cast<double>(heap_after) - heap_before) / kBodies;
  INFO("heap per body, scene and world together: " << bytes_per_body << " bytes");
  // Measured ~1.5 KiB (a SceneBody with its id string, the world's arrays, contacts); 4 KiB
  // leaves room for other allocators, while anything quadratic would need 10⁵ times more.
  CHECK(bytes_per_body < 4096);
  CHECK(world.BodyCount() == kBodies);
}

TEST_CASE("extreme: 1 mm and 1 km bodies together stay finite and do not fall through",
          "[robustness][extreme]") {
  // A 1 km dynamic slab and 1 mm balls and boxes on a 3 km static floor, some of the small ones
  // dropped onto the slab.
  std::string json = R"({"bodies": [
    {"id": "floor", "shape": "box", "size": [3000, 10], "position": [0, -5], "static": true},
    {"id": "slab", "shape": "box", "size": [1000, 10], "position": [0, 6]})";
  for (int i = 0; i < 20; ++i) {
    const double px = -1200.0 + 25.0 * i;  // on the floor, left of the slab
    json += R"(, {"shape": "circle", "radius": 0.0005, "position": [)" + Number(px) + ", 0.01]}";
    json += R"(, {"shape": "box", "size": [0.001, 0.001], "position": [)" + Number(px + 10) + ", 0.01]}";
    json += R"(, {"shape": "circle", "radius": 0.0005, "position": [)" + Number(-400.0 + 40 * i) + ", 11.01]}";
  }
  json += "]}";
  engine::World world = game::BuildWorld(ParseOrFail(json));
  StepFinite(world, 600);  // 10 s
  // Resting things may sink by the solver's slop (5 mm), never through what holds them.
  CHECK(Bottom(world, {1}) > -0.01);
  for (engine::BodyId id{2}; id.index < world.BodyCount(); ++id.index) {
    INFO("body " << id << " at y = " << world.State(id).position.y);
    const bool on_slab = (id.index - 2) % 3 == 2;
    const double support = on_slab ? world.BodyBounds({1}).upper.y : 0.0;
    CHECK(Bottom(world, id) > support - 0.01);
    CHECK(std::abs(world.State(id).velocity.y) < 0.1);
  }
}

TEST_CASE("extreme: a ball at 10 000 m/s stays finite and does not pass through a wall",
          "[robustness][extreme]") {
  // 10 km/s is 167 m a step at 60 Hz, 160 times the wall's thickness: continuous collision
  // must catch it. Both with and without "bullet".
  for (const char* bullet : {"false", "true"}) {
    INFO("bullet: " << bullet);
    engine::World world = game::BuildWorld(ParseOrFail(std::string(R"({"gravity": [0, 0], "bodies": [
      {"id": "wall", "shape": "box", "size": [1, 20], "position": [1000, 0], "static": true},
      {"id": "ball", "shape": "circle", "radius": 0.5, "position": [0, 0], "velocity": [10000, 0],
       "restitution": 0.5, "bullet": )") + bullet + "}]}"));
    StepFinite(world, 120);
    CHECK(world.State({1}).position.x < 1000.0 - 0.5);
    CHECK(world.State({1}).velocity.x < 0.0);  // it bounced back
    CHECK(world.State({1}).velocity.x > -10000.0);
  }
}

TEST_CASE("extreme: a mass ratio of 10⁶ in a stack and in a collision stays finite",
          "[robustness][extreme]") {
  SECTION("a 10⁶ kg box resting on a 1 kg box") {
    engine::World world = game::BuildWorld(ParseOrFail(R"({"bodies": [
      {"id": "floor", "shape": "box", "size": [20, 1], "position": [0, -0.5], "static": true},
      {"id": "small", "shape": "box", "size": [1, 1], "position": [0, 0.5], "mass": 1},
      {"id": "heavy", "shape": "box", "size": [4, 1], "position": [0, 1.5], "mass": 1e6}]})"));
    StepFinite(world, 600);
    // Neither sinks more than the slop into what holds it.
    CHECK(Bottom(world, {1}) > -0.01);
    CHECK(Bottom(world, {2}) > world.BodyBounds({1}).upper.y - 0.01);
  }
  SECTION("a 1 kg ball hits a resting 10⁶ kg ball, and the other way round") {
    // No sleep: the heavy ball's 2·10⁻⁵ m/s would count as resting and be put to sleep.
    engine::World world = game::BuildWorld(ParseOrFail(R"({"gravity": [0, 0], "sleep": false, "bodies": [
      {"id": "light", "shape": "circle", "radius": 0.5, "position": [0, 0], "velocity": [10, 0], "mass": 1,
       "restitution": 1},
      {"id": "heavy", "shape": "circle", "radius": 0.5, "position": [3, 0], "mass": 1e6, "restitution": 1},
      {"id": "heavy2", "shape": "circle", "radius": 0.5, "position": [0, 5], "velocity": [10, 0],
       "mass": 1e6, "restitution": 1},
      {"id": "light2", "shape": "circle", "radius": 0.5, "position": [3, 5], "mass": 1, "restitution": 1}]})"));
    StepFinite(world, 120);
    // Elastic: the light ball comes back at ~10 m/s, the heavy one barely moves (2·10/10⁶ m/s).
    CHECK(world.State({0}).velocity.x == Approx(-10.0).epsilon(0.01));
    CHECK(world.State({1}).velocity.x == Approx(2e-5).epsilon(0.05));
    // The heavy one runs on at ~10 m/s and sends the light one off at ~20 m/s.
    CHECK(world.State({2}).velocity.x == Approx(10.0).epsilon(0.01));
    CHECK(world.State({3}).velocity.x == Approx(20.0).epsilon(0.01));
  }
}

TEST_CASE("extreme: the default scene at dt 1/1000 s and 1/10 s stays finite and in its box",
          "[robustness][extreme]") {
  for (const double dt : {1.0 / 1000.0, 1.0 / 10.0}) {
    INFO("dt = " << dt);
    game::Scene scene = ParseOrFail(game::DefaultSceneJson());
    scene.world.dt = dt;
    game::Expected<std::vector<game::InputEvent>> events =
        game::ParseScript(game::DefaultScriptText(), "<default script>");
    REQUIRE(events.HasValue());
    // The demo clicks land at the same moments in seconds.
    for (game::InputEvent& e : events.Value()) {
      e.step = static_cast<std::int64_t>(std::llround(e.step * (1.0 / 60.0) / dt));
    }
    game::Session session(scene, events.Value(), 800, 600);
    const int steps = static_cast<int>(std::lround(10.0 / dt));  // 10 s
    const engine::World& world = session.World();
    int crossings = 0;
    for (int i = 0; i < steps; ++i) {
      std::vector<engine::Vec2> before;
      for (const engine::BodyId id : world.BodyIds()) before.push_back(world.State(id).position);
      session.Step();
      if (!FirstNonFinite(world).empty()) RequireFinite(world);
      // A click may throw a ball over a wall (14 m high), never through a wall or the floor.
      // At 1/10 s a crowded body can be pushed deep into the floor for a step (then recovers),
      // so "through" is a centre past the middle of a wall (x = ±9.5) or of the floor (y = −0.5).
      for (engine::BodyId id{4}; id.index < world.BodyCount(); ++id.index) {
        const engine::Vec2 p = world.State(id).position;
        const bool left_the_box = std::abs(before[id.index].x) < 9.5 && std::abs(p.x) >= 9.5;
        const bool through = (left_the_box && std::min(before[id.index].y, p.y) < 14.0) ||
                             (std::abs(p.x) < 9.5 && p.y < -0.5);
        if (through) {
          ++crossings;
          INFO(scene.bodies[id.index].id << " from " << before[id.index].x << ", " << before[id.index].y << " to " << p.x
                                   << ", " << p.y << " at step " << world.StepCount());
          CHECK_FALSE(through);
        }
      }
    }
    CHECK(crossings == 0);
    for (engine::BodyId id{4}; id.index < world.BodyCount(); ++id.index) {
      INFO(scene.bodies[id.index].id << " ends at " << world.State(id).position.x << ", " << world.State(id).position.y);
      if (std::abs(world.State(id).position.x) < 9.0) CHECK(Bottom(world, id) > -0.05);
    }
  }
}

TEST_CASE("extreme: 1000 bodies placed at one point hold memory linear in their count",
          "[robustness][extreme]") {
  // Every pair overlaps, so every pair would be a contact: memory and time in the square of the
  // count (4000 such bodies took 4.5 GB and 15 s a step). The pair budget keeps each crowded
  // body's 4 best pairs instead (docs/limits.md).
  constexpr int kBodies = 1000;
  const std::size_t heap_before = soak::HeapBytesInUse();
  engine::World world{engine::WorldDef{}};
  engine::BodyDef floor;
  floor.shape = {engine::ShapeType::kBox, 0, {10, 0.5}};
  floor.position = {0, -0.5};
  floor.is_static = true;
  world.CreateBody(floor);
  for (int i = 1; i < kBodies; ++i) {
    engine::BodyDef ball;
    ball.shape = {engine::ShapeType::kCircle, 0.5, {}};
    ball.position = {0, 1};
    world.CreateBody(ball);
  }
  StepFinite(world, 1);
  const double bytes_per_body = (static_cast<double>(soak::HeapBytesInUse()) - heap_before) / kBodies;
  INFO("heap per body: " << bytes_per_body << " bytes");
  CHECK(bytes_per_body < 4096);  // measured 2.9 KiB; without the budget 225 KiB
  CHECK(world.CrowdedBodyCount() > 900);
  CHECK(world.Contacts().size() < 5 * kBodies);
}

namespace {

// `count` circles of 5 cm radius on a golden-angle spiral 1 mm across: every pair overlaps, yet no
// two centres coincide, so the pile opens out in every direction (coincident centres have no
// direction and are pushed straight up).
void AddSpiralPile(engine::World& world, int count) {
  for (int i = 0; i < count; ++i) {
    const double angle = 2.39996322972865332 * i;
    const double r = 0.001 * std::sqrt((i + 0.5) / count);
    engine::BodyDef ball;
    ball.shape = {engine::ShapeType::kCircle, 0.05, {}};
    ball.position = {r * std::cos(angle), r * std::sin(angle)};
    world.CreateBody(ball);
  }
}

}  // namespace

TEST_CASE("extreme: 4000 bodies at one point step in memory linear in their count and spread apart",
          "[robustness][extreme]") {
  // 4000 circles of 5 cm radius within 1 mm of one point, without gravity, so that nothing but
  // their overlap moves them: every one of the 8 million pairs overlaps (as many as 4000 circles
  // at one point on a floor, which took 3.4 GB and 16 s a step without the budget). The pile must
  // push itself apart, in bounded memory and at bounded speeds, with every number finite.
  constexpr int kBodies = 4000;
  constexpr int kSteps = 40;
  const std::size_t heap_before = soak::HeapBytesInUse();
  engine::WorldDef def;
  def.gravity = {0, 0};
  engine::World world{def};
  AddSpiralPile(world, kBodies);
  auto extent = [&] {
    double low = 0.0, high = 0.0;
    for (const engine::BodyId id : world.BodyIds()) {
      low = std::min(low, world.State(id).position.x);
      high = std::max(high, world.State(id).position.x);
    }
    return high - low;
  };
  std::size_t peak_heap = 0;
  double fastest = 0.0;       // m a step
  double fastest_real = 0.0;  // m/s
  std::size_t first_crowd = 0;
  for (int step = 0; step < kSteps; ++step) {
    std::vector<engine::Vec2> before;
    for (const engine::BodyId id : world.BodyIds()) before.push_back(world.State(id).position);
    StepFinite(world, 1);
    if (step == 0) first_crowd = world.CrowdedBodyCount();
    peak_heap = std::max(peak_heap, soak::HeapBytesInUse());
    for (const engine::BodyId id : world.BodyIds()) {
      fastest = std::max(fastest, Length(world.State(id).position - before[id.index]));
      fastest_real = std::max(fastest_real, Length(world.State(id).velocity));
    }
  }
  const double bytes_per_body = (static_cast<double>(peak_heap) - heap_before) / kBodies;
  INFO("peak heap per body: " << bytes_per_body << " bytes; crowded bodies " << first_crowd << " -> "
                              << world.CrowdedBodyCount() << "; extent " << extent() << " m; fastest "
                              << fastest / def.dt << " m/s pushed, " << fastest_real << " m/s");
  // Measured 4.8 KiB: the pile keeps 4 pairs a body at first, more (up to the quota) as it
  // opens out and fewer bodies are crowded.
  CHECK(bytes_per_body < 8192);
  CHECK(first_crowd > 3900);
  // Measured 3975 -> 2852 crowded, 2 mm -> 2.3 m across in 40 steps (all spread: next test).
  CHECK(5 * world.CrowdedBodyCount() < 4 * first_crowd);
  CHECK(extent() > 1.0);
  // Overlap is pushed out, not thrown: no real speed at all. The push itself compounds along
  // chains of overlapping bodies (8.3 m/s at most here; 19.6 m/s for 1000 such circles without
  // the budget), so it is held to a few times the per-contact limit, not to the limit.
  CHECK(fastest_real < def.max_push_out_speed);
  CHECK(fastest <= 4.0 * def.max_push_out_speed * def.dt);
}

TEST_CASE("extreme: 1000 bodies at one point spread until none is crowded", "[robustness][extreme]") {
  // The same pile, 1000 circles: it opens out until no body is charged with more pairs than its
  // quota, and from then on every overlapping pair is a contact again.
  constexpr int kBodies = 1000;
  engine::WorldDef def;
  def.gravity = {0, 0};
  engine::World world{def};
  AddSpiralPile(world, kBodies);
  int steps = 0;
  StepFinite(world, 1);
  const std::size_t first_crowd = world.CrowdedBodyCount();
  while (world.CrowdedBodyCount() > 0 && steps < 200) {
    StepFinite(world, 1);
    ++steps;
  }
  INFO("crowded bodies: " << first_crowd << " at first, none after " << steps << " more steps");
  CHECK(first_crowd > 950);
  CHECK(world.CrowdedBodyCount() == 0);
  CHECK(steps < 120);  // measured 76
  CHECK(world.DroppedPairCount() == 0);
}
