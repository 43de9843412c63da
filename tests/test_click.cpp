// The click rule (contract): J = max_impulse · (d/r) · (c − p)/d on the topmost dynamic ball.
#include <catch2/catch.hpp>

#include "game/click.h"
#include "game/commands.h"
#include "game/scene.h"
#include "game/session.h"
#include "render/camera.h"
#include "world_builders.h"

using engine::Vec2;
using testing::Box;
using testing::Circle;
using testing::Static;
using testing::WithMass;

TEST_CASE("click impulse at d = 0, r/4, r/2, r", "[click]") {
  const Vec2 c{1, 2};
  const double r = 0.8, max = 10;
  CHECK(game::ClickImpulse(c, r, c, max) == Vec2{});  // the exact centre: nothing, no NaN
  // Clicking left of the centre pushes right, with strength max·d/r.
  for (double fraction : {0.25, 0.5, 1.0}) {
    const Vec2 j = game::ClickImpulse(c, r, c - Vec2{fraction * r, 0}, max);
    CHECK(j.x == Approx(max * fraction).epsilon(1e-14));
    CHECK(j.y == 0.0);
  }
  // A click below and to the right along a 3-4-5 diagonal at d = r/2 pushes up and left.
  const Vec2 j = game::ClickImpulse(c, r, c + Vec2{0.24, -0.32}, max);
  CHECK(j.x == Approx(-0.6 * 5).epsilon(1e-14));
  CHECK(j.y == Approx(0.8 * 5).epsilon(1e-14));
}

TEST_CASE("a click changes the ball's velocity by J/m", "[click]") {
  engine::World world(testing::NoGravity());
  world.CreateBody(WithMass(Circle({0, 0}, 0.5, {1, 1}), 2.0));
  const auto hit = game::ApplyClick(world, {0, -0.25}, 10);  // d = r/2 below the centre
  REQUIRE(hit);
  CHECK(hit->body == engine::BodyId{0});
  CHECK(world.State({0}).velocity.x == 1.0);
  CHECK(world.State({0}).velocity.y == Approx(1.0 + 10 * 0.5 / 2.0).epsilon(1e-14));
}

TEST_CASE("a click outside every ball, on a box or on a static ball does nothing", "[click]") {
  engine::World world(testing::NoGravity());
  world.CreateBody(Circle({0, 0}, 0.5));
  world.CreateBody(Box({3, 0}, {1, 1}));
  world.CreateBody(Static(Circle({6, 0}, 0.5)));
  CHECK_FALSE(game::ApplyClick(world, {0.5000001, 0}, 10));
  CHECK_FALSE(game::ApplyClick(world, {3.1, 0.1}, 10));
  CHECK_FALSE(game::ApplyClick(world, {6.1, 0.1}, 10));
  for (engine::BodyId id{0}; id.index < 3; ++id.index) CHECK(world.State(id).velocity == Vec2{});
  // Exactly on the rim still hits, with the full impulse.
  const auto hit = game::ApplyClick(world, {0.5, 0}, 10);
  REQUIRE(hit);
  CHECK(hit->impulse.x == Approx(-10).epsilon(1e-14));
}

TEST_CASE("a click on a kinematic ball does nothing, even a moving one", "[click][kinematic]") {
  engine::World world(testing::NoGravity());
  world.CreateBody(testing::Kinematic(Circle({0, 0}, 0.5)));
  world.CreateBody(testing::Kinematic(Circle({3, 0}, 0.5), {1, 0}));
  CHECK_FALSE(game::ApplyClick(world, {0.25, 0}, 10));
  CHECK_FALSE(game::ApplyClick(world, {3.25, 0}, 10));
  CHECK(world.State({0}).velocity == Vec2{});
  CHECK(world.State({1}).velocity == Vec2{1, 0});
  // A dynamic ball under a kinematic one still takes the click meant for it.
  const engine::BodyId ball = world.CreateBody(Circle({0.5, 0}, 0.5));
  world.CreateBody(testing::Kinematic(Circle({0.5, 0}, 0.5)));  // on top, in scene order
  const auto hit = game::ApplyClick(world, {0.25, 0}, 10);
  REQUIRE(hit);
  CHECK(hit->body == ball);
}

TEST_CASE("overlapping balls: the last in scene order takes the click", "[click]") {
  engine::World world(testing::NoGravity());
  world.CreateBody(Circle({0, 0}, 1.0));
  world.CreateBody(Circle({0.5, 0}, 1.0));
  world.CreateBody(Static(Circle({0.25, 0}, 1.0)));  // static: skipped, not a shield
  const auto hit = game::ApplyClick(world, {0.25, 0}, 10);
  REQUIRE(hit);
  CHECK(hit->body == engine::BodyId{1});
  CHECK(world.State({0}).velocity == Vec2{});
  CHECK(world.State({1}).velocity.x > 0);
}

TEST_CASE("pixels map to the world through the camera", "[click][camera]") {
  const render::Camera camera{{0, 5}, 20};  // 800x600: s = 0.025 m per pixel
  auto check = [&](double px, double py, Vec2 expected) {
    const Vec2 w = render::PixelToWorld(camera, 800, 600, px, py);
    CHECK(w.x == Approx(expected.x).margin(1e-12));
    CHECK(w.y == Approx(expected.y).margin(1e-12));
    const Vec2 back = render::WorldToPixel(camera, 800, 600, w);
    CHECK(back.x == Approx(px).margin(1e-9));
    CHECK(back.y == Approx(py).margin(1e-9));
  };
  check(400, 300, {0, 5});
  check(0, 0, {-10, 12.5});
  check(800, 600, {10, -2.5});
  check(412, 300, {0.3, 5});
}

TEST_CASE("a pixel click in a script hits the ball under that pixel, before its step", "[click]") {
  game::Scene scene;
  scene.world.gravity = {0, 0};
  scene.camera.center = Vec2{0, 0};
  scene.camera.width = 8;  // 100 px per metre at 800x600
  scene.click_max_impulse = 4;
  game::SceneBody ball;
  ball.id = "ball";
  ball.def = WithMass(Circle({1, 1}, 1.0), 2);
  scene.bodies.push_back(ball);
  // Pixel (450, 200) is world (0.5, 1): half a radius left of the centre, so J = (2, 0).
  const game::InputEvent click{3, game::EventKind::kClickPixel, {450, 200}};
  game::Session session(scene, {click}, 800, 600);
  for (int i = 0; i < 3; ++i) session.Step();
  CHECK(session.World().State({0}).velocity == Vec2{});  // steps 0, 1, 2: not yet
  session.Step();                                      // applied before step 3 is simulated
  CHECK(session.World().State({0}).velocity.x == Approx(1.0).epsilon(1e-14));
  CHECK(session.World().State({0}).position.x == Approx(1.0 + scene.world.dt).epsilon(1e-14));
}

TEST_CASE("without a scene camera, the fit shows every body inside the image", "[camera]") {
  game::Scene scene;
  game::SceneBody a, b;
  a.def = Static(Box({-5, 0}, {2, 2}));
  b.def = Circle({7, 3}, 1);
  scene.bodies = {a, b};
  const game::Session session(scene, {}, 800, 600);
  for (Vec2 corner : {Vec2{-6, -1}, Vec2{8, 4}}) {
    const Vec2 px = render::WorldToPixel(session.Camera(), 800, 600, corner);
    CHECK(px.x > 0);
    CHECK(px.x < 800);
    CHECK(px.y > 0);
    CHECK(px.y < 600);
  }
}

TEST_CASE("every demo click of the default scene hits a ball inside the image", "[click]") {
  game::Expected<game::RunInput> input = game::LoadRunInput({});
  REQUIRE(input.HasValue());
  const std::vector<game::InputEvent> events = input.Value().events;
  REQUIRE(events.size() >= 5);
  game::Session session(input.Value().scene, {}, 800, 600);  // replayed by hand below
  for (const game::InputEvent& event : events) {
    while (session.StepIndex() < event.step) session.Step();
    REQUIRE(event.kind == game::EventKind::kClickPixel);
    CHECK(event.at.x >= 0);
    CHECK(event.at.x <= 800);
    CHECK(event.at.y >= 0);
    CHECK(event.at.y <= 600);
    const Vec2 p = render::PixelToWorld(session.Camera(), 800, 600, event.at.x, event.at.y);
    INFO("click at step " << event.step);
    const auto hit = game::ResolveClick(session.World(), p, session.SceneDef().click_max_impulse);
    REQUIRE(hit);
    session.ApplyEvent(event);
  }
}
