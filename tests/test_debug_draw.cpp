// World::Draw through a recording DebugDraw: one call per live body in slot order with its
// place, size, angle and kind; springs at their anchors; bounds; contact points where bodies
// rest on each other; what DrawOptions leaves out is not called.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "engine/debug_draw.h"
#include "engine/world.h"
#include "world_builders.h"

using engine::BodyId;
using engine::BodyKind;
using engine::Vec2;
using testing::Box;
using testing::Circle;
using testing::Static;

namespace {

struct ShapeCall {
  BodyId body;
  bool circle;
  Vec2 center;
  double radius;
  Vec2 half_extents;
  double angle;
  BodyKind kind;
};

struct ContactCall {
  Vec2 point;
  Vec2 normal;
  double depth;
  double normal_impulse;
};

struct BoundsCall {
  BodyId body;
  engine::AABB bounds;
  BodyKind kind;
};

class RecordingDraw : public engine::DebugDraw {
 public:
  void DrawCircle(BodyId body, Vec2 center, double radius, double angle, BodyKind kind) override {
    shapes.push_back({body, true, center, radius, {}, angle, kind});
  }
  void DrawBox(BodyId body, Vec2 center, Vec2 half_extents, double angle, BodyKind kind) override {
    shapes.push_back({body, false, center, 0.0, half_extents, angle, kind});
  }
  void DrawSpring(Vec2 a, Vec2 b) override { springs.push_back({a, b}); }
  void DrawBounds(BodyId body, const engine::AABB& bounds, BodyKind kind) override {
    bounds_calls.push_back({body, bounds, kind});
  }
  void DrawContact(Vec2 point, Vec2 normal, double depth, double normal_impulse) override {
    contacts.push_back({point, normal, depth, normal_impulse});
  }

  std::vector<ShapeCall> shapes;
  std::vector<std::pair<Vec2, Vec2>> springs;
  std::vector<BoundsCall> bounds_calls;
  std::vector<ContactCall> contacts;
};

// One body of each kind, a turned box, and a spring; stepped a second, so that the ball resting
// on the floor has gone to sleep and the falling one has not.
struct KindsScene {
  engine::World world{engine::WorldDef{}};
  BodyId floor, sleeper, kinematic, sensor, disabled, faller, turned;

  KindsScene() {
    floor = world.CreateBody(Static(Box({0, -0.5}, {40, 1})));
    sleeper = world.CreateBody(Circle({-3, 0.5}, 0.5));
    engine::BodyDef mover = Box({5, 3}, {2, 1}, {1, 0});
    mover.is_kinematic = true;
    kinematic = world.CreateBody(mover);
    engine::BodyDef zone = Static(Circle({0, 5}, 2));
    zone.is_sensor = true;
    sensor = world.CreateBody(zone);
    engine::BodyDef off = Circle({8, 8}, 0.25);
    off.enabled = false;
    disabled = world.CreateBody(off);
    faller = world.CreateBody(Circle({-8, 40}, 0.5));
    engine::BodyDef plank = Static(Box({10, 10}, {3, 0.5}));
    plank.angle = 0.3;
    turned = world.CreateBody(plank);
    engine::SpringDef spring;
    spring.body_a = faller;
    spring.local_a = {0.25, 0};
    spring.local_b = {-8, 50};  // a world point
    spring.stiffness = 0.1;  // 1 N at 10 m: less than the ball's weight, 7.7 N
    world.AddSpring(spring);
    for (int i = 0; i < 60; ++i) world.Step();
  }
};

}  // namespace

TEST_CASE("debug draw: every live body once, in slot order, with its place, size, angle and kind",
          "[debug_draw]") {
  KindsScene scene;
  engine::World& world = scene.world;
  REQUIRE_FALSE(world.IsAwake(scene.sleeper));
  REQUIRE(world.IsAwake(scene.faller));

  RecordingDraw draw;
  world.Draw(draw);
  REQUIRE(draw.shapes.size() == world.BodyCount());
  const std::vector<BodyKind> kinds = {BodyKind::kStatic,   BodyKind::kAsleep,   BodyKind::kKinematic,
                                       BodyKind::kSensor,   BodyKind::kDisabled, BodyKind::kAwake,
                                       BodyKind::kStatic};
  for (std::size_t i = 0; i < draw.shapes.size(); ++i) {
    const ShapeCall& call = draw.shapes[i];
    const BodyId id = world.BodyIds()[i];
    INFO("slot " << i);
    CHECK(call.body == id);
    CHECK(call.kind == kinds[i]);
    CHECK(call.center == world.State(id).position);
    CHECK(call.angle == world.State(id).angle);
    const engine::Shape& shape = world.Info(id).shape;
    CHECK(call.circle == (shape.type == engine::ShapeType::kCircle));
    if (call.circle) CHECK(call.radius == shape.radius);
    if (!call.circle) CHECK(call.half_extents == shape.half_extents);
  }
  // The kinematic box has moved at 1 m/s for a second; the ball has fallen some metres.
  CHECK(draw.shapes[2].center.x == Approx(6).margin(1e-9));
  CHECK(draw.shapes[5].center.y < 37);
  CHECK(draw.shapes[6].angle == 0.3);

  // The spring, from 0.25 m right of the falling ball's centre to its world anchor.
  REQUIRE(draw.springs.size() == 1);
  const Vec2 ball = world.State(scene.faller).position;
  CHECK(draw.springs[0].first == ball + Vec2{0.25, 0});
  CHECK(draw.springs[0].second == Vec2{-8, 50});
  // Bounds and contacts are off unless asked for.
  CHECK(draw.bounds_calls.empty());
  CHECK(draw.contacts.empty());

  // A destroyed body is not drawn: its slot is passed over.
  world.DestroyBody(scene.disabled);
  RecordingDraw after;
  world.Draw(after);
  REQUIRE(after.shapes.size() == 6);
  CHECK(after.shapes[4].body == scene.faller);
}

TEST_CASE("debug draw: bounds for every live body, and only what the options select",
          "[debug_draw]") {
  KindsScene scene;
  RecordingDraw draw;
  engine::DrawOptions options;
  options.shapes = false;
  options.springs = false;
  options.bounds = true;
  scene.world.Draw(draw, options);
  CHECK(draw.shapes.empty());
  CHECK(draw.springs.empty());
  REQUIRE(draw.bounds_calls.size() == scene.world.BodyCount());
  for (std::size_t i = 0; i < draw.bounds_calls.size(); ++i) {
    const BodyId id = scene.world.BodyIds()[i];
    const engine::AABB expected = scene.world.BodyBounds(id);
    CHECK(draw.bounds_calls[i].body == id);
    CHECK(draw.bounds_calls[i].bounds.lower == expected.lower);
    CHECK(draw.bounds_calls[i].bounds.upper == expected.upper);
  }
  CHECK(draw.bounds_calls[4].kind == BodyKind::kDisabled);
  // The turned plank's bounds: half extents 1.5 × 0.25 turned 0.3 rad reach
  // 1.5·cos 0.3 + 0.25·sin 0.3 = 1.433004 + 0.073880 m along x.
  CHECK(draw.bounds_calls[6].bounds.upper.x - 10 == Approx(1.506884).margin(1e-6));
}

TEST_CASE("debug draw: contact points where bodies rest, with the normal and impulse",
          "[debug_draw]") {
  engine::World world{engine::WorldDef{}};
  world.CreateBody(Static(Box({0, -0.5}, {40, 1})));                // 0: top at y = 0
  const BodyId ball = world.CreateBody(Circle({-3, 0.5}, 0.5));      // 1: resting at x = −3
  const BodyId crate = world.CreateBody(Box({3, 0.5}, {1, 1}));      // 2: resting on x ∈ [2.5, 3.5]
  world.CreateBody(Circle({10, 5}, 0.5));                            // 3: far from everything
  for (int i = 0; i < 5; ++i) world.Step();

  RecordingDraw draw;
  engine::DrawOptions options;
  options.contacts = true;
  world.Draw(draw, options);
  std::size_t points = 0;
  for (const engine::Contact& contact : world.Contacts()) points += contact.manifold.point_count;
  REQUIRE(draw.contacts.size() == points);

  // Each drawn point is the world's, with its impulse, in the world's order.
  std::size_t k = 0;
  for (const engine::Contact& contact : world.Contacts()) {
    for (int i = 0; i < contact.manifold.point_count; ++i, ++k) {
      CHECK(draw.contacts[k].point == contact.manifold.points[i].point);
      CHECK(draw.contacts[k].normal_impulse == contact.normal_impulse[i]);
    }
  }

  // The floor holds up the ball at one point under its centre and the crate at its two bottom
  // corners, the normals pointing up from the floor (slot 0); the free-falling ball has none.
  // Without rotation the solver may carry the crate's weight on either corner, so the impulses
  // are checked per body: the floor pushes each up.
  auto impulse_near = [&](std::vector<Vec2> places) {
    double impulse = 0;
    for (const Vec2 where : places) {
      std::size_t count = 0;
      for (const ContactCall& c : draw.contacts) {
        if (engine::Length(c.point - where) > 0.01) continue;
        ++count;
        impulse += c.normal_impulse;
        CHECK(c.normal.x == Approx(0).margin(1e-12));
        CHECK(c.normal.y == Approx(1).margin(1e-12));
        CHECK(std::abs(c.depth) < world.Def().linear_slop);
      }
      CHECK(count == 1);
    }
    return impulse;
  };
  const double x_ball = world.State(ball).position.x, x_crate = world.State(crate).position.x;
  CHECK(impulse_near({{x_ball, 0}}) > 0);
  CHECK(impulse_near({{x_crate - 0.5, 0}, {x_crate + 0.5, 0}}) > 0);
  CHECK(draw.contacts.size() == 3);
}
