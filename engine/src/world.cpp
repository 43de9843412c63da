// World: body creation and Step(), which reads as the list of phases it runs.
#include "engine/world.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "integrate.h"
#include "solver.h"

namespace engine {

namespace {

// Preconditions of the public API hold in every build: a violated one stops the program with
// its reason instead of quietly corrupting the simulation. The edges validate user input first.
void Require(bool condition, const char* what) {
  if (condition) return;
  std::fprintf(stderr, "engine precondition failed: %s\n", what);
  std::abort();
}

bool IsPositiveFinite(double v) { return std::isfinite(v) && v > 0.0; }

double Area(const Shape& shape) {
  constexpr double kPi = 3.14159265358979323846;
  return shape.type == ShapeType::kCircle ? kPi * shape.radius * shape.radius
                                          : 4.0 * shape.half_extents.x * shape.half_extents.y;
}

// Up to this many bodies, testing every pair is cheaper than keeping sorted endpoint lists.
constexpr std::size_t kAllPairsMaxBodies = 16;

}  // namespace

World::World(const WorldDef& def) : def_(def) {
  Require(IsPositiveFinite(def.dt), "WorldDef::dt must be positive and finite");
  Require(IsFinite(def.gravity), "WorldDef::gravity must be finite");
  Require(def.velocity_iterations >= 1, "WorldDef::velocity_iterations must be >= 1");
  Require(def.restitution_threshold >= 0.0 && std::isfinite(def.restitution_threshold),
          "WorldDef::restitution_threshold must be finite and >= 0");
  Require(def.linear_slop >= 0.0 && std::isfinite(def.linear_slop),
          "WorldDef::linear_slop must be finite and >= 0");
  Require(def.position_correction >= 0.0 && def.position_correction <= 1.0,
          "WorldDef::position_correction must be in [0, 1]");
}

BodyId World::CreateBody(const BodyDef& def) {
  const Shape& shape = def.shape;
  Require(shape.type == ShapeType::kCircle ? IsPositiveFinite(shape.radius)
                                           : IsPositiveFinite(shape.half_extents.x) &&
                                                 IsPositiveFinite(shape.half_extents.y),
          "BodyDef::shape size must be positive and finite");
  Require(IsFinite(def.position) && IsFinite(def.velocity) && std::isfinite(def.angle) &&
              std::isfinite(def.angular_velocity),
          "BodyDef state must be finite");
  Require(def.restitution >= 0.0 && std::isfinite(def.restitution) && def.friction >= 0.0 &&
              std::isfinite(def.friction),
          "BodyDef restitution and friction must be finite and >= 0");

  BodyInfo info;
  info.shape = shape;
  info.restitution = def.restitution;
  info.friction = def.friction;
  info.is_static = def.is_static;
  info.fixed_rotation = def.fixed_rotation;
  info.bullet = def.bullet;
  BodyState state;
  state.position = def.position;
  state.angle = def.angle;
  if (!def.is_static) {
    const double mass = def.mass > 0.0 ? def.mass : def.density * Area(shape);
    Require(IsPositiveFinite(mass), "BodyDef mass (or density) must be positive and finite");
    info.mass = mass;
    info.inv_mass = 1.0 / mass;
    state.velocity = def.velocity;
    state.angular_velocity = def.angular_velocity;
  }
  states_.push_back(state);
  infos_.push_back(info);
  return static_cast<BodyId>(states_.size() - 1);
}

void World::ApplyLinearImpulse(BodyId id, Vec2 impulse) {
  Require(id < states_.size(), "ApplyLinearImpulse: no such body");
  Require(IsFinite(impulse), "ApplyLinearImpulse: impulse must be finite");
  const BodyInfo& info = infos_[id];
  if (info.is_static) return;
  states_[id].velocity += impulse / info.mass;
}

AABB World::BodyBounds(BodyId id) const {
  const Vec2 c = states_[id].position;
  const Shape& shape = infos_[id].shape;
  const Vec2 half = shape.type == ShapeType::kCircle ? Vec2{shape.radius, shape.radius}
                                                     : shape.half_extents;
  return {c - half, c + half};
}

void World::Step() {
  const std::size_t n = states_.size();
  positions_before_.resize(n);
  start_velocities_.resize(n);

  IntegrateVelocities();  // forces: gravity changes velocities
  FindCandidatePairs();   // broad phase: pairs whose bounding boxes overlap
  BuildContacts();        // narrow phase: exact manifolds for those pairs
  SolveContacts();        // impulses: restitution, friction, no approach
  IntegratePositions();   // move with the solved velocities
  CorrectPositions();     // push out what overlap remains beyond the slop
  ++step_count_;
}

void World::IntegrateVelocities() {
  detail::IntegrateVelocities(states_, infos_, def_.gravity, def_.dt, start_velocities_);
}

void World::FindCandidatePairs() {
  bounds_.resize(states_.size());
  for (BodyId id = 0; id < states_.size(); ++id) bounds_[id] = BodyBounds(id);
  const bool all_pairs = def_.broad_phase == BroadPhaseType::kAllPairs ||
                         (def_.broad_phase == BroadPhaseType::kAuto &&
                          states_.size() <= kAllPairsMaxBodies);
  if (all_pairs) {
    FindPairsAllPairs(bounds_, &pairs_);
  } else {
    sweep_and_prune_.FindPairs(bounds_, &pairs_);
  }
  // Two static bodies never need a contact.
  std::erase_if(pairs_, [this](BodyPair p) { return infos_[p.a].is_static && infos_[p.b].is_static; });
}

void World::BuildContacts() {
  contacts_.clear();
  for (const BodyPair& pair : pairs_) {
    const BodyInfo& ia = infos_[pair.a];
    const BodyInfo& ib = infos_[pair.b];
    const Vec2 pa = states_[pair.a].position;
    const Vec2 pb = states_[pair.b].position;
    const bool circle_a = ia.shape.type == ShapeType::kCircle;
    const bool circle_b = ib.shape.type == ShapeType::kCircle;
    Manifold m;
    bool touching;
    if (circle_a && circle_b) {
      touching = CollideCircles(pa, ia.shape.radius, pb, ib.shape.radius, &m);
    } else if (circle_a) {
      touching = CollideCircleBox(pa, ia.shape.radius, pb, ib.shape.half_extents, &m);
    } else if (circle_b) {
      // The narrow phase takes the circle first; flip its normal back to point from a to b.
      touching = CollideCircleBox(pb, ib.shape.radius, pa, ia.shape.half_extents, &m);
      m.normal = -m.normal;
    } else {
      touching = CollideBoxes(pa, ia.shape.half_extents, pb, ib.shape.half_extents, &m);
    }
    if (!touching) continue;
    contacts_.push_back({pair.a, pair.b, m, std::max(ia.restitution, ib.restitution),
                         std::sqrt(ia.friction * ib.friction)});
  }
}

void World::SolveContacts() {
  detail::PrepareContacts(contacts_, states_, infos_, def_.restitution_threshold, &constraints_);
  detail::SolveVelocities(constraints_, states_, infos_, def_.velocity_iterations);
}

void World::IntegratePositions() {
  for (std::size_t i = 0; i < states_.size(); ++i) positions_before_[i] = states_[i].position;
  detail::IntegratePositions(def_.integrator, states_, infos_, start_velocities_, def_.gravity,
                             def_.dt);
}

void World::CorrectPositions() {
  detail::CorrectPositions(contacts_, positions_before_, states_, infos_, def_.linear_slop,
                           def_.position_correction);
}

}  // namespace engine
