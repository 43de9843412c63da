// bench_peers' and bench_scaling's scenes, ballbox side: each builds and steps briefly to finite
// figures; the state-based overlap and joint-gap measures on known cases; the joint scenes' layout.
// In a build with the peers (-DBALLBOX_BENCH_PEERS=ON) the joint scenes are built in them too.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "bench/peers/ballbox_engine.h"
#include "bench/peers/engines.h"
#include "bench/peers/scenes.h"

namespace {

const peers::Scene& JointScene(const std::vector<peers::Scene>& scenes, const std::string& name) {
  for (const peers::Scene& scene : scenes) {
    if (scene.spec.name == name) return scene;
  }
  FAIL("no scene " << name);
  return scenes.front();
}

}  // namespace

TEST_CASE("every side-by-side scene steps 10 times in ballbox to finite figures", "[bench]") {
  for (const peers::Scene& scene : peers::Scenes()) {
    std::vector<peers::BallboxSetting> settings = {{}};
    if (scene.sweep) {
      settings.push_back({engine::ContactSolver::kSequentialImpulse, 0});
      for (int n : {1, 2, 4, 8}) settings.push_back({engine::ContactSolver::kSubstep, n});
    }
    for (peers::BallboxSetting setting : settings) {
      INFO(scene.spec.name << ", " << setting.Label());
      peers::BallboxEngine engine(setting);
      engine.Build(scene.spec);
      REQUIRE(engine.World().BodyCount() == scene.spec.bodies.size());
      REQUIRE(engine.World().Def().rotation == scene.spec.rotation);
      REQUIRE_FALSE(engine.World().Def().sleeping);
      const std::vector<peers::Figure> figures = scene.measure(engine, scene.spec, 10);
      std::vector<peers::State> states;
      engine.Read(states);
      for (const peers::State& s : states) REQUIRE(peers::Finite(s));
      REQUIRE_FALSE(figures.empty());
      for (const peers::Figure& f : figures) {
        INFO(f.name << " = " << f.value);
        // The one figure 10 steps cannot show: the ball has not bounced yet.
        if (f.name == "max apex error") continue;
        CHECK(std::isfinite(f.value));
      }
    }
  }
}

TEST_CASE("the scaling scenes build at 1000 bodies and step to a finite state", "[bench]") {
  for (bool boxes : {false, true}) {
    const peers::SceneSpec spec = peers::ScalingScene(1000, boxes);
    INFO(spec.name);
    REQUIRE(spec.bodies.size() == 1004);  // and the container's four walls
    peers::BallboxEngine engine;
    const auto [ms, hash] = peers::TimeSteps(engine, spec, 1, 2);
    (void)ms;  // no timing in tests: only that it ran
    std::vector<peers::State> states;
    engine.Read(states);
    CHECK(peers::Hash(states) == hash);
    CHECK(peers::Escaped(spec, states) == 0);
    CHECK(std::isfinite(peers::MaxOverlap(spec, states)));
  }
}

TEST_CASE("the state-based overlap measure on known cases", "[bench]") {
  const peers::BodySpec circle = peers::Circle({0, 0}, 0.5), box = peers::Box({0, 0}, {1, 1});
  const auto at = [](engine::Vec2 p, double angle = 0) { return peers::State{p, {}, angle, 0}; };
  CHECK(peers::Penetration(circle, at({0, 0}), circle, at({0.9, 0})) == Approx(0.1));
  CHECK(peers::Penetration(circle, at({0, 0}), box, at({0.95, 0})) == Approx(0.05));
  CHECK(peers::Penetration(box, at({0.95, 0}), circle, at({0, 0})) == Approx(0.05));
  CHECK(peers::Penetration(circle, at({0, 0}), box, at({1.2, 1.2})) < 0);  // past the corner
  CHECK(peers::Penetration(box, at({0, 0}), box, at({0.98, 0.5})) == Approx(0.02));
  // A box turned 45° sitting on its corner 1 cm deep in another's top face.
  const double corner = std::sqrt(0.5);
  CHECK(peers::Penetration(box, at({0, 0}), box, at({0, 0.5 + corner - 0.01}, 0.7853981633974483)) == Approx(0.01));
  peers::SceneSpec scene;
  scene.bodies = {peers::Box({0, -0.5}, {10, 1}, 1, true), circle, circle};
  CHECK(peers::MaxOverlap(scene, {at({0, -0.5}), at({0, 0.48}), at({0.7, 0.48})}) == Approx(0.3));
}

TEST_CASE("the state-based joint gap on known cases", "[bench]") {
  peers::SceneSpec scene;
  scene.bodies = {peers::Box({0, 0}, {1, 0.2}), peers::Box({1, 0}, {1, 0.2})};
  scene.joints = {{0, 1, {0.5, 0}}};
  const auto at = [](engine::Vec2 p, double angle = 0) { return peers::State{p, {}, angle, 0}; };
  CHECK(peers::MaxJointGap(scene, {at({0, 0}), at({1, 0})}) == 0);
  CHECK(peers::MaxJointGap(scene, {at({0, 0}), at({1, -0.01})}) == Approx(0.01));
  // A turns a quarter turn about its centre: its end point goes to (0, 0.5), B's stays at (0.5, 0).
  CHECK(peers::MaxJointGap(scene, {at({0, 0}, 1.5707963267948966), at({1, 0})}) == Approx(std::sqrt(0.5)));
  // Both turn a quarter turn about the shared point: closed.
  CHECK(peers::MaxJointGap(scene, {at({0.5, -0.5}, 1.5707963267948966), at({0.5, 0.5}, 1.5707963267948966)}) ==
        Approx(0).margin(1e-12));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK(std::isnan(peers::MaxJointGap(scene, {at({0, 0}), at({nan, 0})})));
}

TEST_CASE("the joint gap from body states matches ballbox's own joint frames", "[bench]") {
  const std::vector<peers::Scene> scenes = peers::Scenes();
  for (const std::string name : {"chain 20 horizontal", "heavy chain 1000:1"}) {
    INFO(name);
    const peers::SceneSpec& spec = JointScene(scenes, name).spec;
    peers::BallboxEngine engine;
    engine.Build(spec);
    peers::StepN(engine, 30);
    std::vector<peers::State> states;
    engine.Read(states);
    const auto ids = engine.World().JointIds();
    REQUIRE(ids.size() == spec.joints.size());
    for (std::size_t i = 0; i < ids.size(); ++i) {
      const engine::JointFrame frame = engine.World().Joint(ids[i]);
      const auto [a, b] = peers::JointAnchors(spec, spec.joints[i], states);
      CHECK(engine::Length(a - frame.anchor_a) < 1e-12);
      CHECK(engine::Length(b - frame.anchor_b) < 1e-12);
    }
    // The horizontal chain has fallen by now (the heavy one hangs still): the comparison above was
    // not only of start points.
    if (name == "chain 20 horizontal") CHECK(engine::Length(states.back().position - spec.bodies.back().position) > 0.1);
  }
}

TEST_CASE("the joint scenes' layout: links end to end, the weight at its rigid position", "[bench]") {
  const std::vector<peers::Scene> scenes = peers::Scenes();
  const peers::SceneSpec& chain = JointScene(scenes, "chain 20 horizontal").spec;
  REQUIRE(chain.bodies.size() == 21);
  REQUIRE(chain.joints.size() == 20);
  CHECK(chain.rotation);
  CHECK(chain.steps == 600);
  for (std::size_t i = 0; i < chain.joints.size(); ++i) {
    const peers::JointSpec& j = chain.joints[i];
    CHECK(j.body_a == i);
    CHECK(j.body_b == i + 1);
    CHECK(j.anchor.x == Approx(0.5 * i));  // the left end of link i, the right end of the one before
    CHECK(j.anchor.y == 0);
    CHECK(chain.bodies[i + 1].position.x - chain.bodies[i + 1].half.x == Approx(j.anchor.x));
  }
  CHECK(chain.bodies[0].is_static);
  CHECK(chain.bodies[1].mass == Approx(0.05));

  const peers::SceneSpec& heavy = JointScene(scenes, "heavy chain 1000:1").spec;
  REQUIRE(heavy.bodies.size() == 12);  // the anchor, ten links, the weight
  REQUIRE(heavy.joints.size() == 11);
  for (std::size_t i = 1; i <= 10; ++i) {
    CHECK(heavy.bodies[i].mass == Approx(0.05));
    CHECK(2 * heavy.bodies[i].half.y == Approx(0.25));
  }
  const peers::BodySpec& weight = heavy.bodies.back();
  CHECK(weight.mass == Approx(50));
  CHECK(weight.mass / heavy.bodies[1].mass == Approx(1000));
  // Rigid position: hanging straight, its top edge at the bottom of the tenth 25 cm link.
  CHECK(weight.position.x == 0);
  CHECK(weight.position.y == Approx(-10 * 0.25 - 0.25));
  CHECK(heavy.joints.back().anchor.y == Approx(weight.position.y + weight.half.y));

  const peers::SceneSpec& grid = JointScene(scenes, "joint grid 100 x 100").spec;
  REQUIRE(grid.bodies.size() == 10000);
  // Right and lower neighbours (2 · 100 · 99), less the six between the seven static top bodies.
  CHECK(grid.joints.size() == 2 * 100 * 99 - 6);
  std::size_t statics = 0;
  for (const peers::BodySpec& b : grid.bodies) {
    statics += b.is_static ? 1 : 0;
    CHECK(b.group == 1);
  }
  CHECK(statics == 7);
  for (const peers::JointSpec& j : grid.joints) {
    CHECK_FALSE((grid.bodies[j.body_a].is_static && grid.bodies[j.body_b].is_static));
    // At the midpoint between the two centres, 1 m apart.
    CHECK(engine::Length(grid.bodies[j.body_b].position - grid.bodies[j.body_a].position) == 1);
    CHECK(engine::Length(0.5 * (grid.bodies[j.body_a].position + grid.bodies[j.body_b].position) - j.anchor) == 0);
  }
}

TEST_CASE("every engine built in holds each joint scene's joints, closed at the start", "[bench]") {
  const std::vector<peers::Scene> scenes = peers::Scenes();
  for (const std::string name : {"chain 20 horizontal", "heavy chain 1000:1", "joint grid 100 x 100"}) {
    const peers::SceneSpec& spec = JointScene(scenes, name).spec;
    for (const peers::EngineEntry& entry : peers::Engines()) {
      INFO(name << ", " << entry.name);
      std::unique_ptr<peers::PhysicsEngine> engine = entry.make();
      engine->Build(spec);
      CHECK(engine->JointCount() == spec.joints.size());
      std::vector<peers::State> states;
      engine->Read(states);
      REQUIRE(states.size() == spec.bodies.size());
      CHECK(peers::MaxJointGap(spec, states) < 1e-6);
      // The last body (the heavy chain's weight) starts where the scene puts it: its rigid position.
      CHECK(engine::Length(states.back().position - spec.bodies.back().position) < 1e-6);
      engine->Step();
      engine->Read(states);
      CHECK(std::isfinite(peers::MaxJointGap(spec, states)));
    }
  }
}

TEST_CASE("ballbox's adapter: a shared group or a joint keeps two overlapping bodies apart", "[bench]") {
  peers::SceneSpec spec;
  spec.gravity = {0, 0};
  spec.rotation = true;
  spec.bodies = {peers::Circle({0, 0}, 0.5), peers::Circle({0.6, 0}, 0.5)};
  const auto contacts = [](const peers::SceneSpec& s) {
    peers::BallboxEngine engine;
    engine.Build(s);
    engine.Step();
    return engine.World().Contacts().size();
  };
  CHECK(contacts(spec) > 0);
  peers::SceneSpec grouped = spec;
  for (peers::BodySpec& b : grouped.bodies) b.group = 1;
  CHECK(contacts(grouped) == 0);
  peers::SceneSpec other_groups = grouped;
  other_groups.bodies[1].group = 2;
  CHECK(contacts(other_groups) > 0);
  peers::SceneSpec joined = spec;
  joined.joints = {{0, 1, {0.3, 0}}};
  CHECK(contacts(joined) == 0);
}
