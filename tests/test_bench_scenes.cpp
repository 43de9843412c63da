// Every scene of bench_solver, under every solver setting it compares, builds and steps briefly
// to a finite state and finite figures, so the benchmark cannot rot unnoticed. No timing here.
#include <catch2/catch.hpp>

#include "print_ids.h"

#include <cmath>

#include "bench/solver_scenes.h"
#include "engine/world.h"

TEST_CASE("every solver benchmark scene builds and steps 10 times to finite figures", "[bench]") {
  for (const solver_bench::Scene& scene : solver_bench::Scenes()) {
    for (solver_bench::Setting setting : solver_bench::Settings()) {
      INFO(scene.name << ", " << (setting.solver == engine::ContactSolver::kSequentialImpulse ? "seed" : "substep")
                      << " " << setting.substeps << " substeps");
      engine::World world = solver_bench::MakeWorld(scene, setting);
      REQUIRE(world.BodyCount() > 1);
      REQUIRE(world.Def().solver == setting.solver);
      REQUIRE_FALSE(world.Def().sleeping);  // the figures are measured awake
      const std::vector<solver_bench::Figure> figures = scene.measure(world, 10);
      REQUIRE(world.StepCount() == 10);
      bool finite = true;
      for (const engine::BodyId id : world.BodyIds()) {
        const engine::BodyState& s = world.State(id);
        finite = finite && engine::IsFinite(s.position) && engine::IsFinite(s.velocity);
      }
      REQUIRE(finite);
      REQUIRE_FALSE(figures.empty());
      for (const solver_bench::Figure& f : figures) {
        INFO(f.name << " = " << f.value);
        // NaN only where 10 steps cannot show the figure: the ball has not bounced yet.
        if (f.name == "max apex error") continue;
        CHECK(std::isfinite(f.value));
      }
    }
  }
}

TEST_CASE("the bouncing-ball benchmark scene sees its five bounces in its own run length", "[bench]") {
  // The one figure 10 steps cannot show; a single ball is cheap enough to run in full.
  for (const solver_bench::Scene& scene : solver_bench::Scenes()) {
    if (scene.name.find("bouncing ball") == std::string::npos) continue;
    engine::World world = solver_bench::MakeWorld(scene, {engine::ContactSolver::kSubstep, 4});
    for (const solver_bench::Figure& f : scene.measure(world, scene.steps)) {
      INFO(f.name << " = " << f.value);
      CHECK(std::isfinite(f.value));
    }
  }
}

TEST_CASE("bench_solver's passes reach the substep solver and leave the other one alone", "[bench]") {
  const solver_bench::Scene scene = solver_bench::Scenes().front();
  // The automatic choice stays the engine's own (World fills it in: one pass a substep where
  // nothing turns).
  const engine::World automatic = solver_bench::MakeWorld(scene, {engine::ContactSolver::kSubstep, 4});
  CHECK(automatic.Def().velocity_iterations == engine::World(engine::WorldDef{}).Def().velocity_iterations);
  // A scene's own setting stays when no passes are asked for.
  solver_bench::Scene own = scene;
  own.def.velocity_iterations = 5;
  CHECK(solver_bench::MakeWorld(own, {engine::ContactSolver::kSubstep, 4}).Def().velocity_iterations == 5);
  CHECK(solver_bench::MakeWorld(own, {engine::ContactSolver::kSubstep, 4}, false, 2).Def().velocity_iterations == 2);
  const engine::World three = solver_bench::MakeWorld(scene, {engine::ContactSolver::kSubstep, 8}, true, 3);
  CHECK(three.Def().velocity_iterations == 3);
  CHECK(three.Def().substeps == 8);
  // The sequential-impulse solver's passes are its own: --passes is the substep solver's.
  const engine::World impulse = solver_bench::MakeWorld(scene, {engine::ContactSolver::kSequentialImpulse, 1}, false, 3);
  engine::WorldDef impulse_def;
  impulse_def.solver = engine::ContactSolver::kSequentialImpulse;
  CHECK(impulse.Def().velocity_iterations == engine::World(impulse_def).Def().velocity_iterations);
}
