// The solver benchmark's scenes, each with its stability figures and the stability tests'
// thresholds; shared by bench_solver (which times them) and the test that runs each briefly.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "bench/scene_rules.h"
#include "bench/stress_scenes.h"
#include "engine/world.h"

namespace solver_bench {

using bench::kBallDrop;
using bench::kBallRadius;
using bench::kBallRestitution;
using bench::kCradleSpeed;

/// One column of the comparison: the baseline, or the substep solver at a number of substeps.
struct Setting {
  engine::ContactSolver solver = engine::ContactSolver::kSubstep;
  int substeps = 4;  ///< ignored by the sequential-impulse solver
};

/// The sequential-impulse solver, then the substep solver at 1, 2, 4 (the default) and 8
/// substeps: stability against cost.
inline std::vector<Setting> Settings() {
  return {{engine::ContactSolver::kSequentialImpulse, 1},
          {engine::ContactSolver::kSubstep, 1},
          {engine::ContactSolver::kSubstep, 2},
          {engine::ContactSolver::kSubstep, 4},
          {engine::ContactSolver::kSubstep, 8}};
}

struct Figure {
  std::string name;
  std::string unit;
  double value = 0.0;     ///< NaN when the run was too short to see it (no bounce yet)
  std::string threshold;  ///< the stability test's, as text
  bool pass = false;
};

struct Scene {
  std::string name;
  int steps = 600;          ///< a full run: 10 s at 60 Hz unless the test looks at less
  engine::WorldDef def;     ///< solver and substeps are set per Setting
  std::function<void(engine::World&)> build;
  /// Steps the freshly built world `steps` times and measures it; the figures need samples
  /// along the way (bounce apexes, the fastest body), so the stepping lives here.
  std::function<std::vector<Figure>(engine::World&, int steps)> measure;
};

/// `rotation`: the same scene with turning bodies (the substep solver then takes 4 passes per
/// substep instead of 1).
/// `passes`: the substep solver's velocity passes per substep (0: the scene's own setting, the
/// world's automatic choice in every scene here).
inline engine::World MakeWorld(const Scene& scene, Setting setting, bool rotation = false, int passes = 0) {
  engine::WorldDef def = scene.def;
  def.solver = setting.solver;
  def.substeps = setting.substeps;
  def.rotation = rotation;
  if (passes > 0 && setting.solver == engine::ContactSolver::kSubstep) def.velocity_iterations = passes;
  engine::World world(def);
  scene.build(world);
  return world;
}

inline engine::WorldDef AwakeWorld() {
  engine::WorldDef def;
  def.sleeping = false;  // stability must not lean on sleep, and timing must not either
  return def;
}

inline void StepN(engine::World& world, int steps) {
  for (int i = 0; i < steps; ++i) world.Step();
}

/// The largest distance any body ends from where it started, over `steps` steps.
inline double MaxDrift(engine::World& world, int steps) {
  std::vector<engine::Vec2> start;
  for (const engine::BodyId id : world.BodyIds()) start.push_back(world.State(id).position);
  StepN(world, steps);
  double drift = 0;
  for (const engine::BodyId id : world.BodyIds()) {
    drift = std::max(drift, engine::Length(world.State(id).position - start[id.index]));
  }
  return drift;
}

/// The deepest overlap among the last step's contacts.
inline double MaxOverlap(const engine::World& world) {
  double deepest = 0;
  for (const engine::Contact& c : world.Contacts()) {
    for (int p = 0; p < c.manifold.point_count; ++p) deepest = std::max(deepest, c.manifold.points[p].depth);
  }
  return deepest;
}

inline Figure Below(std::string name, std::string unit, double value, double limit) {
  char text[32];
  std::snprintf(text, sizeof text, "< %g", limit);
  return {std::move(name), std::move(unit), value, text, value < limit};
}

inline Scene DriftScene(std::string name, std::function<void(engine::World&)> build, double limit) {
  Scene scene{std::move(name), 600, AwakeWorld(), std::move(build), {}};
  scene.measure = [limit](engine::World& world, int steps) {
    return std::vector<Figure>{Below("max drift", "m", MaxDrift(world, steps), limit)};
  };
  return scene;
}

inline Scene HeavyOnLightScene() {
  Scene scene{"heavy on light 1000:1", 600, AwakeWorld(),
              [](engine::World& world) { stress::AddHeavyOnLight(world, 3, 1e3); }, {}};
  scene.measure = [](engine::World& world, int steps) {
    const engine::BodyId heavy = static_cast<engine::BodyId>(world.BodyCount() - 1);
    const double y0 = world.State(heavy).position.y;
    StepN(world, steps);
    return std::vector<Figure>{Below("heavy box sank", "m", y0 - world.State(heavy).position.y, 0.01)};
  };
  return scene;
}

inline Scene OverlapRecoveryScene() {
  Scene scene{"overlap recovery (base 4, 25%)", 60, AwakeWorld(),
              [](engine::World& world) { stress::AddPyramid(world, 4, 0.25); }, {}};
  scene.measure = [](engine::World& world, int steps) {
    const double g = engine::Length(world.Def().gravity);
    double fastest = 0;
    bool within_limit = true;
    for (int i = 1; i <= steps; ++i) {
      world.Step();
      // The push-out speed plus free fall: overlap must never launch a body.
      const double limit = world.Def().max_push_out_speed + g * i * world.Def().dt;
      for (const engine::BodyId id : world.BodyIds()) {
        const double speed = engine::Length(world.State(id).velocity);
        fastest = std::max(fastest, speed);
        within_limit = within_limit && speed <= limit;
      }
    }
    const double slop = world.Def().linear_slop;
    return std::vector<Figure>{Below("overlap left", "m", MaxOverlap(world), 2 * slop),
                               {"fastest body", "m/s", fastest, "<= 3 + g t", within_limit}};
  };
  return scene;
}

constexpr int kPourCount = 4000;
constexpr double kPourRadius = 0.25;
constexpr double kPourWidth = 40, kPourHeight = 40;  // 59 rows of 68 start below y = 35

inline Scene PourScene() {
  Scene scene{"pour 4000 circles r 0.25", 600, AwakeWorld(), [](engine::World& world) {
                stress::AddContainer(world, kPourWidth, kPourHeight);
                stress::AddCirclePour(world, kPourCount, kPourRadius, kPourWidth);
              }, {}};
  scene.measure = [](engine::World& world, int steps) {
    StepN(world, steps);
    int escaped = 0, not_finite = 0;
    for (const engine::BodyId id : world.BodyIds().subspan(4)) {  // after the container's 4 walls
      const engine::BodyState& s = world.State(id);
      if (!engine::IsFinite(s.position) || !engine::IsFinite(s.velocity)) {
        ++not_finite;
      } else if (!(std::abs(s.position.x) < 0.5 * kPourWidth && s.position.y > 0 &&
                   s.position.y < kPourHeight)) {
        ++escaped;
      }
    }
    return std::vector<Figure>{{"escaped", "", double(escaped), "= 0", escaped == 0},
                               {"NaN", "", double(not_finite), "= 0", not_finite == 0},
                               Below("max overlap", "m", MaxOverlap(world), 0.01)};
  };
  return scene;
}

inline Scene BouncingBallScene() {
  engine::WorldDef def = AwakeWorld();
  def.gravity = {0, -9.81};
  Scene scene{"bouncing ball e 0.8 from 10 m", 600, def, [](engine::World& world) {
                world.CreateBody(stress::Ground({0, -0.5}, {4, 1}));
                engine::BodyDef ball;
                ball.shape.radius = kBallRadius;
                ball.position = {0, kBallDrop + kBallRadius};
                ball.restitution = kBallRestitution;
                world.CreateBody(ball);
              }, {}};
  scene.measure = [](engine::World& world, int steps) {
    bench::BounceApexes apexes;
    for (int i = 0; i < steps; ++i) {
      world.Step();
      apexes.Observe(world.State({1}).position.y, world.State({1}).velocity.y);
    }
    const int seen = apexes.Bounces();
    const double worst = apexes.WorstError();
    return std::vector<Figure>{{"bounces", "", double(seen), "= 5", seen == bench::kBallBounces},
                               {"max apex error", "", worst, "< 0.005", worst < 0.005}};
  };
  return scene;
}

inline Scene CradleScene() {
  engine::WorldDef def = AwakeWorld();
  def.gravity = {0, 0};
  Scene scene{"Newton's cradle, 5 + striker", 120, def, [](engine::World& world) {
                engine::BodyDef ball;
                ball.shape.radius = 0.5;
                ball.restitution = 1.0;
                ball.friction = 0.0;
                ball.position = {-3, 0};
                ball.velocity = {kCradleSpeed, 0};
                world.CreateBody(ball);
                ball.velocity = {};
                for (int i = 0; i < 5; ++i) {
                  ball.position = {double(i), 0};
                  world.CreateBody(ball);
                }
              }, {}};
  scene.measure = [](engine::World& world, int steps) {
    StepN(world, steps);
    const engine::BodyId last = world.BodyIds().back();
    const double ratio = engine::Length(world.State(last).velocity) / kCradleSpeed;
    double others = 0;
    for (const engine::BodyId id : world.BodyIds().first(world.BodyCount() - 1)) {
      others = std::max(others, engine::Length(world.State(id).velocity));
    }
    return std::vector<Figure>{{"last / striker speed", "", ratio, "1 +- 0.01", std::abs(ratio - 1) < 0.01},
                               Below("others' max speed", "m/s", others, 0.01 * kCradleSpeed)};
  };
  return scene;
}

/// Every scene of the issue, in the order the results table shows them.
inline std::vector<Scene> Scenes() {
  return {DriftScene("pyramid base 20", [](engine::World& w) { stress::AddPyramid(w, 20); }, 0.005),
          DriftScene("pyramid base 40", [](engine::World& w) { stress::AddPyramid(w, 40); }, 0.01),
          DriftScene("stack of 20", [](engine::World& w) { stress::AddStack(w, 20); }, 0.005),
          HeavyOnLightScene(),
          OverlapRecoveryScene(),
          PourScene(),
          BouncingBallScene(),
          CradleScene()};
}

}  // namespace solver_bench
