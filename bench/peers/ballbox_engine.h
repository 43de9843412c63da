// ballbox behind the side-by-side benchmark's engine interface: a peers::SceneSpec becomes an
// engine::World with the scene's settings and joints, sleeping off, and the default or a chosen solver.
#pragma once

#include <algorithm>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bench/peers/scenes.h"
#include "engine/world.h"

namespace peers {

/// A solver setting to compare: the default (substeps and passes chosen by the world), the
/// sequential-impulse solver, or the substep solver at a given number of substeps.
struct BallboxSetting {
  engine::ContactSolver solver = engine::ContactSolver::kSubstep;
  int substeps = 0;  ///< 0: the world's default (4, or 8 with rotation)
  int threads = 1;   ///< WorldDef::threads

  std::string Label() const {
    if (threads > 1) return std::to_string(threads) + " threads";
    if (solver == engine::ContactSolver::kSequentialImpulse) return "sequential_impulse";
    return substeps == 0 ? "default" : std::to_string(substeps) + (substeps == 1 ? " substep" : " substeps");
  }
};

class BallboxEngine : public PhysicsEngine {
 public:
  explicit BallboxEngine(BallboxSetting setting = {}) : setting_(setting) {}

  std::string Name() const override {
    const bool plain = setting_.solver == engine::ContactSolver::kSubstep && setting_.substeps == 0 &&
                       setting_.threads == 1;
    return plain ? "ballbox" : "ballbox " + setting_.Label();
  }

  std::string Settings(const SceneSpec& scene) const override {
    const engine::WorldDef def = Def(scene);
    if (def.solver == engine::ContactSolver::kSequentialImpulse) return "sequential_impulse: 10 passes per step, double";
    const engine::WorldDef filled = engine::World(def).Def();  // the automatic settings filled in
    // A turning world of circles alone, without joints, takes the circles' passes once it has
    // 256 contacts or more (WorldDef::circle_velocity_iterations).
    const bool circles = scene.rotation && scene.joints.empty() &&
                         std::all_of(scene.bodies.begin(), scene.bodies.end(),
                                     [](const BodySpec& b) { return b.is_static || b.kind == Kind::kCircle; });
    const int passes = circles ? filled.circle_velocity_iterations : filled.velocity_iterations;
    return std::to_string(filled.substeps) + " substeps x " + std::to_string(passes) +
           (passes == 1 ? " pass" : " passes") + ", double" +
           (def.threads > 1 ? ", " + std::to_string(def.threads) + " threads" : "");
  }

  void Build(const SceneSpec& scene) override {
    world_.emplace(Def(scene));
    std::vector<engine::BodyId> ids;
    ids.reserve(scene.bodies.size());
    for (const BodySpec& b : scene.bodies) {
      engine::BodyDef def;
      def.shape.type = b.kind == Kind::kCircle ? engine::ShapeType::kCircle : engine::ShapeType::kBox;
      def.shape.radius = b.radius;
      def.shape.half_extents = b.half;
      if (b.as_polygon) {
        engine::ShapePart square;
        square.type = engine::ShapeType::kPolygon;
        square.points = {{-b.half.x, -b.half.y}, {b.half.x, -b.half.y}, {b.half.x, b.half.y}, {-b.half.x, b.half.y}};
        def.parts = {square};
      }
      def.position = b.position;
      def.velocity = b.velocity;
      def.is_static = b.is_static;
      def.mass = b.mass;
      def.friction = scene.friction;
      def.restitution = scene.restitution;
      def.filter.group_index = -b.group;
      ids.push_back(world_->CreateBody(def));
    }
    for (const JointSpec& j : scene.joints) {
      engine::JointDef def;  // a revolute joint; its bodies stop colliding with each other
      def.type = engine::JointType::kRevolute;
      def.body_a = ids[j.body_a];
      def.body_b = ids[j.body_b];
      def.anchor = j.anchor;
      world_->CreateJoint(def);
    }
  }

  void Step() override { world_->Step(); }

  void Read(std::vector<State>& out) const override {
    out.resize(world_->BodyCount());
    for (const engine::BodyId id : world_->BodyIds()) {
      const engine::BodyState& s = world_->State(id);
      out[id.index] = {s.position, s.velocity, s.angle, s.angular_velocity};
    }
  }

  std::size_t JointCount() const override { return world_->JointIds().size(); }

  const engine::World& World() const { return *world_; }

 private:
  engine::WorldDef Def(const SceneSpec& scene) const {
    engine::WorldDef def;
    def.gravity = scene.gravity;
    def.dt = scene.dt;
    def.rotation = scene.rotation;
    def.sleeping = false;  // stability must not lean on sleep, and timing must not either
    def.solver = setting_.solver;
    def.substeps = setting_.substeps;
    def.threads = setting_.threads;
    return def;
  }

  BallboxSetting setting_;
  std::optional<engine::World> world_;
};

}  // namespace peers
