// The skip ablation's pairs of worlds: a feature absent, and present but with nothing to do;
// shared by bench_skip (hash and cost side by side) and the test that steps each pair briefly.
#pragma once

#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "bench/scene_rules.h"
#include "bench/stress_scenes.h"
#include "engine/world.h"

namespace skip_ablation {

struct Ablation {
  std::string feature;
  /// Why the present world has nothing to do, or why the two are one definition.
  std::string note;
  std::function<engine::World()> absent;
  std::function<engine::World()> present;
  int steps = 300;
};

/// How the bodies of a base scene are changed for the "present" side.
using BodyEdit = std::function<void(engine::BodyDef&)>;

constexpr double kWidth = 30, kHeight = 30;
constexpr int kMixedCount = 1500;

/// 1500 bodies of 0.5 m (two circles to every box) on a jittered grid in a closed 30 m container,
/// falling into a pile: circle and box contacts of every kind, never at rest within 300 steps.
inline void AddMixedPour(engine::World& world, const BodyEdit& edit) {
  stress::AddContainer(world, kWidth, kHeight);
  int i = 0;
  bench::JitteredGrid(kMixedCount, 0.25, kWidth, 3, [&](engine::Vec2 position, engine::Vec2 velocity) {
    engine::BodyDef def;
    if (i++ % 3 == 2) {
      def.shape.type = engine::ShapeType::kBox;
      def.shape.half_extents = {0.25, 0.25};
    } else {
      def.shape.radius = 0.25;
    }
    def.position = position;
    def.velocity = velocity;
    def.friction = 0.6;
    edit(def);
    world.CreateBody(def);
  });
}

inline engine::WorldDef AwakeDef() {
  engine::WorldDef def;
  def.sleeping = false;  // every body simulated: the timing is the cost of the feature alone
  return def;
}

/// AwakeDef with continuous collision on or off.
inline engine::WorldDef ContinuousDef(bool continuous) {
  engine::WorldDef def = AwakeDef();
  def.continuous = continuous;
  return def;
}

inline engine::World Mixed(engine::WorldDef def, const BodyEdit& edit = [](engine::BodyDef&) {}) {
  engine::World world(def);
  AddMixedPour(world, edit);
  return world;
}

/// 1500 circles in a closed box with no gravity, perfectly elastic at any speed and frictionless,
/// moving at 3-6 m/s: a gas that keeps its energy, so no body rests long enough to sleep. (At
/// 1-3 m/s, one body came nearly to rest and slept after 243 steps: in a gas a fraction of about
/// (s / v_rms)² of the bodies is slower than s at any moment, Maxwell-Boltzmann in 2D.)
inline engine::World Gas(bool sleeping) {
  engine::WorldDef def;
  def.gravity = {0, 0};
  def.sleeping = sleeping;
  def.restitution_threshold = 0.0;
  engine::World world(def);
  stress::AddContainer(world, kWidth, kHeight);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> angle(0, 2 * 3.14159265358979323846), speed(3.0, 6.0);
  const double pitch = 0.7;
  const int per_row = static_cast<int>((kWidth - pitch) / pitch);
  for (int i = 0; i < kMixedCount; ++i) {
    engine::BodyDef def_body;
    def_body.shape.radius = 0.25;
    def_body.position = {-0.5 * kWidth + pitch * (1 + i % per_row), pitch * (1 + i / per_row)};
    const double a = angle(rng), v = speed(rng);
    def_body.velocity = {v * std::cos(a), v * std::sin(a)};
    def_body.restitution = 1.0;
    def_body.friction = 0.0;
    world.CreateBody(def_body);
  }
  return world;
}

inline std::vector<Ablation> Ablations() {
  std::vector<Ablation> out;
  out.push_back({"springs of stiffness 0 and damping 0",
                 "a spring between every two consecutive bodies (1499), pulling with nothing",
                 [] { return Mixed(AwakeDef()); },
                 [] {
                   engine::World world = Mixed(AwakeDef());
                   for (engine::BodyIndex i = 5; i < world.BodyCount(); ++i) {
                     engine::SpringDef spring;
                     spring.body_a = {i - 1};
                     spring.body_b = engine::BodyId{i};
                     spring.rest_length = 1.0;
                     world.AddSpring(spring);
                   }
                   return world;
                 }});
  out.push_back({"linear and angular damping 0",
                 "0 is the default: both sides are one definition, so this row measures the timing noise",
                 [] { return Mixed(AwakeDef()); },
                 [] { return Mixed(AwakeDef(), [](engine::BodyDef& b) { b.linear_damping = 0, b.angular_damping = 0; }); }});
  out.push_back({"drag coefficient, fluid density 0",
                 "every body's C_d set to 1.2 in a vacuum",
                 [] { return Mixed(AwakeDef()); },
                 [] { return Mixed(AwakeDef(), [](engine::BodyDef& b) { b.drag_coefficient = 1.2; }); }});
  out.push_back({"gravitational constant 0",
                 "0 is the default: both sides are one definition, so this row measures the timing noise",
                 [] { return Mixed(AwakeDef()); },
                 [] {
                   engine::WorldDef def = AwakeDef();
                   def.gravitational_constant = 0.0;
                   return Mixed(def);
                 }});
  out.push_back({"rotation on, every body fixed_rotation",
                 "both pinned to 4 substeps of 1 pass (rotation would otherwise pick 8 of 4)",
                 [] {
                   engine::WorldDef def = AwakeDef();
                   def.substeps = 4, def.velocity_iterations = 1;
                   return Mixed(def);
                 },
                 [] {
                   engine::WorldDef def = AwakeDef();
                   def.substeps = 4, def.velocity_iterations = 1, def.rotation = true;
                   return Mixed(def, [](engine::BodyDef& b) { b.fixed_rotation = true; });
                 }});
  out.push_back({"sleeping on, a scene that never rests",
                 "an elastic frictionless gas of 1500 circles at 3-6 m/s, no gravity",
                 [] { return Gas(false); }, [] { return Gas(true); }});
  out.push_back({"continuous collision on, no fast body",
                 "no body moves half its size (0.25 m) in a step; off: the switch WorldDef::continuous",
                 [] { return Mixed(ContinuousDef(false)); }, [] { return Mixed(ContinuousDef(true)); }});
  out.push_back({"every body a bullet, no fast body",
                 "bullets are always caught, but none is fast (continuous collision off on both sides)",
                 [] { return Mixed(ContinuousDef(false)); },
                 [] { return Mixed(ContinuousDef(false), [](engine::BodyDef& b) { b.bullet = true; }); }});
  return out;
}

}  // namespace skip_ablation
