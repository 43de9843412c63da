// bench_peers' and bench_scaling's scenes, ballbox side (the peers are not in the test suite): each
// builds and steps briefly to finite figures; the state-based overlap measure on known cases.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "bench/peers/ballbox_engine.h"
#include "bench/peers/scenes.h"

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
