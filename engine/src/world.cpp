// World: body creation and Step(), which reads as the list of phases it runs.
#include "engine/world.h"
#include "world_impl.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <numeric>

#include "solver/contact_colouring.h"
#include "solver/direct_solver.h"
#include "forces/force_model.h"
#include "narrow_phase/collide.h"
#include "solver/impact.h"
#include "integrate.h"
#include "solver/seed_solver.h"
#include "solver/shock_propagation.h"
#include "sleep.h"
#include "solver/substep_solver.h"

namespace engine {

namespace {

// Preconditions of the public API hold in every build: a violated one stops the program with
// its reason instead of quietly corrupting the simulation. The edges validate user input first.
void Require(bool condition, const char* what) {
  if (condition) return;
  std::fprintf(stderr, "engine precondition failed: %s\n", what);
  std::abort();
}

constexpr double kInfinity = std::numeric_limits<double>::infinity();

bool IsPositiveFinite(double v) { return std::isfinite(v) && v > 0.0; }
bool IsNonNegativeFinite(double v) { return std::isfinite(v) && v >= 0.0; }

// Drag coefficients of a long cylinder and a square bar across a flow (textbook values).
constexpr double kCircleDrag = 0.47;
constexpr double kBoxDrag = 1.05;

// Moving farther than this fraction of its size in one step makes a body fast (Box2D's default
// safety factor is the same half).
constexpr double kFastFraction = 0.5;

// Speculative contacts start this far apart (Box2D's 4 × linear slop), so a body coming to
// rest is caught a little before it touches.
constexpr double kSpeculativeSlops = 4.0;

// The pair budget (PairCollector, docs/limits.md): a body keeps every pair charged to it, that
// is every pair with a body at least as wide as itself, up to its quota. Solid circles or
// squares of one size can give a body at most 8 such pairs (a 3 by 3 block: the diagonal ones
// through the bounding boxes), so 16 is twice what they need; squares turned 45° meet 12, but
// their bounding boxes have twice their area, which doubles the quota (below). A box also
// carries up to two bodies at least as wide per unit of its aspect along each long side: 4 more
// per unit of aspect, up to PairQuota::kMaxQuota. The collector grows the quota with the box the
// broad phase is given, grown by the speculative margin or turned (PairQuota::area).
constexpr double kPairQuota = 16;
constexpr double kPairQuotaPerAspect = 4;

PairQuota QuotaOf(const Shape& shape, bool is_static) {
  constexpr double kMax = PairQuota::kMaxQuota;
  if (shape.type == ShapeType::kCircle) {
    const double d = 2.0 * shape.radius;
    return {is_static ? kInfinity : d, static_cast<std::uint32_t>(kPairQuota), d * d};
  }
  const Vec2 h = shape.half_extents;
  const double aspect = std::max(h.x, h.y) / std::min(h.x, h.y);
  const double quota = std::min(kMax, kPairQuota + kPairQuotaPerAspect * std::ceil(aspect - 1.0));
  return {is_static ? kInfinity : 2.0 * std::min(h.x, h.y), static_cast<std::uint32_t>(quota), 4.0 * h.x * h.y};
}

// The settings a scene left at 0 ("automatic") get the values its kind of world needs: the
// axis-aligned game is solved exactly with one pass per substep (shock propagation finishes
// what it leaves); turning boxes couple their contacts and need more (8 substeps of 4 passes
// keep a 40-base pyramid within 5 mm, docs/solver.md).
WorldDef Resolve(WorldDef def) {
  if (def.substeps == 0) def.substeps = def.rotation ? 8 : 4;
  if (def.velocity_iterations == 0) {
    def.velocity_iterations = def.solver == ContactSolver::kSequentialImpulse ? 10 : def.rotation ? 4 : 1;
  }
  return def;
}

}  // namespace

World::Impl::Impl(const WorldDef& def)
    : def_(Resolve(def)),
      free_motion_(std::make_unique<detail::FreeMotion>()),
      direct_solver_(std::make_unique<detail::DirectSolver>()),
      shock_scratch_(std::make_unique<detail::ShockScratch>()) {
  Require(IsPositiveFinite(def.dt), "WorldDef::dt must be positive and finite");
  Require(IsFinite(def.gravity), "WorldDef::gravity must be finite");
  Require(def.velocity_iterations >= 0, "WorldDef::velocity_iterations must be >= 0");
  Require(def.substeps >= 0, "WorldDef::substeps must be >= 0");
  Require(IsPositiveFinite(def.max_push_out_speed), "WorldDef::max_push_out_speed must be > 0");
  Require(IsNonNegativeFinite(def.restitution_threshold),
          "WorldDef::restitution_threshold must be finite and >= 0");
  Require(IsNonNegativeFinite(def.linear_slop), "WorldDef::linear_slop must be finite and >= 0");
  Require(def.position_correction >= 0.0 && def.position_correction <= 1.0,
          "WorldDef::position_correction must be in [0, 1]");
  Require(IsNonNegativeFinite(def.sleep_speed) && IsNonNegativeFinite(def.time_to_sleep),
          "WorldDef sleep settings must be finite and >= 0");
}

World::World(const WorldDef& def) : impl_(std::make_unique<Impl>(def)) {}
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;
World::~World() = default;

BodyId World::CreateBody(const BodyDef& def) { return impl_->CreateBody(def); }
void World::Step() { impl_->Step(); }
const std::optional<NumericFault>& World::Fault() const { return impl_->fault_; }
const std::vector<SpringDef>& World::Springs() const { return impl_->springs_; }
std::size_t World::BodyCount() const { return impl_->states_.size(); }
const BodyState& World::State(BodyId id) const { return impl_->states_[id]; }
const BodyInfo& World::Info(BodyId id) const { return impl_->infos_[id]; }
AABB World::BodyBounds(BodyId id) const { return impl_->BodyBounds(id); }
const WorldDef& World::Def() const { return impl_->def_; }
std::int64_t World::StepCount() const { return impl_->step_count_; }
const std::vector<Contact>& World::Contacts() const { return impl_->contacts_; }
std::size_t World::CrowdedBodyCount() const { return impl_->crowded_bodies_; }
std::uint64_t World::DroppedPairCount() const { return impl_->dropped_pairs_; }
std::uint32_t World::MostChargedPairs() const { return impl_->most_charged_; }
bool World::IsAwake(BodyId id) const { return impl_->awake_[id] != 0; }

BodyId World::Impl::CreateBody(const BodyDef& def) {
  const Shape& shape = def.shape;
  Require(shape.type == ShapeType::kCircle ? IsPositiveFinite(shape.radius)
                                           : IsPositiveFinite(shape.half_extents.x) &&
                                                 IsPositiveFinite(shape.half_extents.y),
          "BodyDef::shape size must be positive and finite");
  Require(IsFinite(def.position) && IsFinite(def.velocity) && std::isfinite(def.angle) &&
              std::isfinite(def.angular_velocity),
          "BodyDef state must be finite");
  Require(IsNonNegativeFinite(def.restitution) && IsNonNegativeFinite(def.friction),
          "BodyDef restitution and friction must be finite and >= 0");
  Require(IsNonNegativeFinite(def.linear_damping) && IsNonNegativeFinite(def.angular_damping) &&
              std::isfinite(def.drag_coefficient),
          "BodyDef damping must be finite and >= 0, the drag coefficient finite");

  BodyInfo info;
  info.shape = shape;
  info.restitution = def.restitution;
  info.friction = def.friction;
  info.is_static = def.is_static;
  info.fixed_rotation = def.fixed_rotation;
  info.bullet = def.bullet;
  info.linear_damping = def.linear_damping;
  info.angular_damping = def.angular_damping;
  if (def.linear_damping != 0.0 || def.angular_damping != 0.0) ++damped_bodies_;
  info.drag_coefficient = def.drag_coefficient >= 0.0 ? def.drag_coefficient
                          : shape.type == ShapeType::kCircle ? kCircleDrag
                                                              : kBoxDrag;
  BodyState state;
  state.position = def.position;
  state.angle = def.angle;
  if (!def.is_static) {
    const double mass = def.mass > 0.0 ? def.mass : def.density * ShapeArea(shape);
    Require(IsPositiveFinite(mass), "BodyDef mass (or density) must be positive and finite");
    info.mass = mass;
    info.inv_mass = 1.0 / mass;
    info.inertia = ShapeInertia(shape, mass);
    // Without rotation (world or body) nothing can turn the body: infinite inertia.
    info.inv_inertia = def_.rotation && !def.fixed_rotation ? 1.0 / info.inertia : 0.0;
    if (info.inv_inertia != 0.0) ++turnable_bodies_;
    state.velocity = def.velocity;
    state.angular_velocity = def.angular_velocity;
  }
  states_.push_back(state);
  infos_.push_back(info);
  rest_time_.push_back(0.0);
  awake_.push_back(def.is_static ? 0 : 1);
  island_.push_back(0);
  quotas_.push_back(QuotaOf(shape, def.is_static));
  return static_cast<BodyId>(states_.size() - 1);
}

void World::ApplyLinearImpulse(BodyId id, Vec2 impulse) {
  Require(id < impl_->states_.size(), "ApplyLinearImpulse: no such body");
  Require(IsFinite(impulse), "ApplyLinearImpulse: impulse must be finite");
  const BodyInfo& info = impl_->infos_[id];
  if (info.is_static) return;
  detail::WakeIsland(id, impl_->infos_, {impl_->rest_time_, impl_->awake_, impl_->island_});
  impl_->states_[id].velocity += impulse / info.mass;
}

void World::AddSpring(const SpringDef& def) {
  Require(def.body_a < impl_->states_.size() && (!def.body_b || *def.body_b < impl_->states_.size()),
          "AddSpring: no such body");
  Require(IsFinite(def.local_a) && IsFinite(def.local_b), "AddSpring: attachment points must be finite");
  Require(IsNonNegativeFinite(def.rest_length) && IsNonNegativeFinite(def.stiffness) &&
              IsNonNegativeFinite(def.damping),
          "AddSpring: rest length, stiffness and damping must be finite and >= 0");
  impl_->springs_.push_back(def);
  if (def.stiffness != 0.0 || def.damping != 0.0) impl_->acting_springs_.push_back(def);
}

AABB World::Impl::BodyBounds(BodyId id) const {
  const Vec2 c = states_[id].position;
  const Shape& shape = infos_[id].shape;
  Vec2 half = shape.type == ShapeType::kCircle ? Vec2{shape.radius, shape.radius} : shape.half_extents;
  if (shape.type == ShapeType::kBox && states_[id].angle != 0.0) {
    const Rot q = MakeRot(states_[id].angle);
    const Vec2 h = shape.half_extents;
    half = {std::abs(q.c) * h.x + std::abs(q.s) * h.y, std::abs(q.s) * h.x + std::abs(q.c) * h.y};
  }
  return {c - half, c + half};
}

double World::Impl::Reach(BodyId id) const {
  if (def_.solver == ContactSolver::kSequentialImpulse) return 0.0;  // the seed only sees real overlap
  const double speculative = 0.5 * kSpeculativeSlops * def_.linear_slop;
  if (!awake_[id]) return speculative;
  // The farthest a body can travel in this step under gravity, and then some; a turning body's
  // outline also sweeps |ω|·r. Contacts within that reach are speculative: the solver lets the
  // bodies close the gap and no more, at any speed (continuous collision, Catto's speculative
  // contacts), and the impact pass places the bounce at the moment of impact.
  const double dt = def_.dt;
  const Shape& shape = infos_[id].shape;
  const double motion = Length(states_[id].velocity) * dt + Length(def_.gravity) * dt * dt;
  const double outer = shape.type == ShapeType::kCircle ? shape.radius : Length(shape.half_extents);
  const double turning = infos_[id].inv_inertia != 0.0 ? std::abs(states_[id].angular_velocity) * outer * dt : 0.0;
  // A body moving farther in a step than half its size is fast. With continuous collision off
  // (and the body no bullet) a fast body is tested only where it is, as a discrete engine does:
  // it may tunnel. Slow bodies are the same either way, so a scene without fast bodies does
  // not change at all.
  const double size = shape.type == ShapeType::kCircle ? 2.0 * shape.radius
                                                       : 2.0 * std::min(shape.half_extents.x, shape.half_extents.y);
  const bool fast = motion + turning > kFastFraction * size;
  if (fast && !def_.continuous && !infos_[id].bullet) return speculative;
  double reach = motion + speculative;
  if (infos_[id].inv_inertia != 0.0) reach += turning;
  return reach;
}

void World::Impl::Step() {
  if (fault_) return;
  const std::size_t n = states_.size();
  positions_before_.resize(n);
  for (std::size_t i = 0; i < n; ++i) positions_before_[i] = states_[i].position;

  FindCandidatePairs();  // broad phase: pairs whose grown bounds overlap; wakes touched sleepers
  BuildContacts();       // narrow phase: manifolds, with last step's impulses to warm-start
  if (def_.solver == ContactSolver::kSequentialImpulse) {
    StepSeed();
  } else {
    StepSubstep();
  }
  if (fault_) return;                // broken down mid-step: stop where it appeared
  if (def_.sleeping) UpdateSleep();  // islands at rest long enough go to sleep
  CheckFinite();                     // a non-finite number stops here, named, not in a frame
  ++step_count_;
}

void World::Impl::FindCandidatePairs() {
  const std::size_t n = states_.size();
  bounds_.resize(n);
  reach_.resize(n);
  for (BodyId id = 0; id < n; ++id) {
    reach_[id] = Reach(id);
    const Vec2 grow{reach_[id], reach_[id]};
    const AABB b = BodyBounds(id);
    bounds_[id] = {b.lower - grow, b.upper + grow};
  }
  // The pair budget bounds what bodies piled up cost; elsewhere every pair is kept.
  broad_phase_.FindPairs(def_.broad_phase, bounds_, &pairs_,
                         def_.pair_budget ? std::span<const PairQuota>(quotas_) : std::span<const PairQuota>());
  const PairCollector& budget = broad_phase_.LastCollector();
  crowded_bodies_ = budget.CrowdedCount();
  dropped_pairs_ = budget.DroppedCount();
  most_charged_ = budget.MostCharged();
  // A moving body reaching a sleeping one wakes its whole island before anything is solved.
  for (const BodyPair& p : pairs_) {
    if (awake_[p.a] != awake_[p.b]) {
      const BodyId sleeper = awake_[p.a] ? p.b : p.a;
      if (!infos_[sleeper].is_static) detail::WakeIsland(sleeper, infos_, {rest_time_, awake_, island_});
    }
  }
  // So does a spring (one that acts) from a moving body.
  for (const SpringDef& spring : acting_springs_) {
    if (!spring.body_b || awake_[spring.body_a] == awake_[*spring.body_b]) continue;
    const BodyId sleeper = awake_[spring.body_a] ? *spring.body_b : spring.body_a;
    if (!infos_[sleeper].is_static) detail::WakeIsland(sleeper, infos_, {rest_time_, awake_, island_});
  }
  // Pairs where nothing moves need no contact: static with static, or with a sleeping body.
  std::erase_if(pairs_, [this](BodyPair p) { return !awake_[p.a] && !awake_[p.b]; });
}

void World::Impl::BuildContacts() {
  previous_contacts_.swap(contacts_);
  contacts_.clear();
  // At most one contact a pair: reserving that much at once avoids growth by doubling, which
  // could hold twice what a large pile needs.
  contacts_.reserve(pairs_.size());
  std::size_t previous = 0;
  for (const BodyPair& pair : pairs_) {
    const BodyInfo& ia = infos_[pair.a];
    const BodyInfo& ib = infos_[pair.b];
    const Vec2 pa = states_[pair.a].position;
    const Vec2 pb = states_[pair.b].position;
    const double margin = reach_[pair.a] + reach_[pair.b];
    const bool circle_a = ia.shape.type == ShapeType::kCircle;
    const bool circle_b = ib.shape.type == ShapeType::kCircle;
    // A box that has turned takes the oriented tests; an unturned one the exact axis-aligned
    // ones, so a scene where nothing turns computes exactly what the axis-aligned game does.
    const double angle_a = states_[pair.a].angle, angle_b = states_[pair.b].angle;
    auto box_a = [&] { return OrientedBox{pa, ia.shape.half_extents, MakeRot(angle_a)}; };
    auto box_b = [&] { return OrientedBox{pb, ib.shape.half_extents, MakeRot(angle_b)}; };
    Manifold m;
    bool touching;
    if (circle_a && circle_b) {
      touching = CollideCircles(pa, ia.shape.radius, pb, ib.shape.radius, &m, margin);
    } else if (circle_a) {
      touching = angle_b == 0.0 ? CollideCircleBox(pa, ia.shape.radius, pb, ib.shape.half_extents, &m, margin)
                                : CollideCircleOrientedBox(pa, ia.shape.radius, box_b(), &m, margin);
    } else if (circle_b) {
      // The narrow phase takes the circle first; flip its normal back to point from a to b.
      touching = angle_a == 0.0 ? CollideCircleBox(pb, ib.shape.radius, pa, ia.shape.half_extents, &m, margin)
                                : CollideCircleOrientedBox(pb, ib.shape.radius, box_a(), &m, margin);
      m.normal = -m.normal;
    } else if (angle_a == 0.0 && angle_b == 0.0) {
      touching = CollideBoxes(pa, ia.shape.half_extents, pb, ib.shape.half_extents, &m, margin);
    } else {
      touching = CollideOrientedBoxes(box_a(), box_b(), &m, margin);
    }
    if (!touching) continue;

    Contact contact{pair.a, pair.b, m, std::max(ia.restitution, ib.restitution),
                    std::sqrt(ia.friction * ib.friction)};
    // Warm start: both lists are in pair order, so the old contact is found by walking forward.
    while (previous < previous_contacts_.size() &&
           (previous_contacts_[previous].a < pair.a ||
            (previous_contacts_[previous].a == pair.a && previous_contacts_[previous].b < pair.b))) {
      ++previous;
    }
    if (previous < previous_contacts_.size() && previous_contacts_[previous].a == pair.a &&
        previous_contacts_[previous].b == pair.b) {
      const Contact& old = previous_contacts_[previous];
      if (Dot(old.manifold.normal, m.normal) > 0.99) {
        for (int i = 0; i < m.point_count; ++i) {
          for (int j = 0; j < old.manifold.point_count; ++j) {
            if (old.manifold.points[j].id != m.points[i].id) continue;
            contact.normal_impulse[i] = old.normal_impulse[j];
            contact.tangent_impulse[i] = old.tangent_impulse[j];
          }
        }
      }
    }
    contacts_.push_back(contact);
  }
}

detail::ForceModel World::Impl::Forces() const {
  return {def_, infos_, acting_springs_, awake_, def_.rotation, damped_bodies_ > 0};
}

void World::Impl::StepSeed() {
  const double dt = def_.dt;
  detail::FreeStep(def_.integrator, Forces(), states_, dt, free_motion_.get());
  if (CheckFinite()) return;  // the forces overflowed: name the body before contacts spread it
  detail::PrepareContacts(contacts_, states_, infos_, def_.restitution_threshold, &seed_constraints_);
  detail::SolveVelocities(seed_constraints_, states_, infos_, def_.velocity_iterations);
  MarkPushed(seed_constraints_);
  detail::MoveBodies(def_.integrator, states_, awake_, pushed_, def_.rotation, *free_motion_, dt);
  detail::CorrectPositions(contacts_, positions_before_, states_, infos_, def_.linear_slop,
                           def_.position_correction);
}

void World::Impl::StepSubstep() {
  // Where nothing can turn, the compact constraints in colour order: shock propagation makes
  // the solve indifferent to order there, and the colour order runs faster. Turning stacks need
  // their passes to converge, which contact order does better where a scene is built bottom-up:
  // a turning pyramid of base 40 drifts 6.7 mm in 10 s in contact order against 2.2 cm by colour.
  if (turnable_bodies_ > 0) {
    contact_slot_.resize(contacts_.size());
    std::iota(contact_slot_.begin(), contact_slot_.end(), 0u);
    StepSubstep(&substep_constraints_);
  } else {
    detail::ColourContacts(contacts_, infos_, &body_colours_, &contact_slot_);
    StepSubstep(&linear_constraints_);
  }
}

template <typename C>
void World::Impl::StepSubstep(std::vector<C>* constraints_vector) {
  constexpr bool kCanTurn = detail::kCanTurn<C>;
  const double h = def_.dt / def_.substeps;
  const double inv_h = 1.0 / h;
  // What free flight would do to each body this step: the impact pass places bounces with it.
  accelerations_.resize(states_.size());
  angular_accelerations_.resize(states_.size());
  Forces().Evaluate(states_, accelerations_, angular_accelerations_);

  detail::PrepareSubstepConstraints(contacts_, contact_slot_, infos_, states_, constraints_vector);
  const std::span<C> constraints = *constraints_vector;
  // Shock propagation supports against gravity; without gravity there is no up.
  const double g = Length(def_.gravity);
  const bool has_up = g > 0.0;
  if (has_up) detail::BuildShockRows<C>(constraints, infos_, -def_.gravity / g, shock_scratch_.get(), &shock_rows_);
  // Islands of turning bodies that hold a large mass ratio get their contacts solved exactly.
  bool direct = false;
  if constexpr (kCanTurn) direct = detail::PrepareDirectSolve(constraints, infos_, direct_solver_.get());
  detail::ResolveImpacts(constraints, contact_slot_, contacts_, states_, accelerations_, def_,
                         &impact_lags_);  // bounces first
  push_velocities_.resize(states_.size());
  push_angular_velocities_.resize(states_.size());
  const detail::PushVelocities push{push_velocities_, push_angular_velocities_};
  // Which bodies an applied force pushes: their contacts may carry a load, and the warm start
  // keeps it whole; the warm start of force-free contacts never adds energy. Gravity (uniform or
  // mutual) loads every moving body; otherwise a spring loads the bodies it pulls. Drag and
  // damping only slow a body down and load nothing.
  const bool all_loaded = def_.gravity != Vec2{} || def_.gravitational_constant != 0.0;
  loaded_.assign(all_loaded ? 0 : states_.size(), 0);
  if (!all_loaded) {
    for (const SpringDef& spring : acting_springs_) {
      loaded_[spring.body_a] = awake_[spring.body_a];
      if (spring.body_b) loaded_[*spring.body_b] = awake_[*spring.body_b];
    }
  }
  // Nothing loaded at all: a closed world without applied forces, where the contacts must never
  // add kinetic energy; a last check per substep holds them to it.
  const bool force_free = !all_loaded && std::find(loaded_.begin(), loaded_.end(), 1) == loaded_.end();
  warm_free_.resize(all_loaded ? 0 : states_.size());
  warm_free_angular_.resize(all_loaded || !def_.rotation ? 0 : states_.size());
  const detail::WarmStartImpulses warm{warm_free_, warm_free_angular_};
  if (def_.rotation) {
    angles_before_.resize(states_.size());
    turned_.resize(states_.size());
    for (std::size_t i = 0; i < states_.size(); ++i) angles_before_[i] = states_[i].angle;
    UpdateTurned();  // nothing has turned yet this step
  }
  const detail::StepStart start{positions_before_, def_.rotation ? std::span<const Rot>(turned_)
                                                                 : std::span<const Rot>()};
  // Remove the same fraction of the overlap per step as the seed does, spread over the substeps:
  // 1 − (1 − f)^(1/n) of it each substep, so the push-out speed is that times the overlap / h.
  const double push_out_rate =
      (1.0 - std::pow(1.0 - def_.position_correction, 1.0 / def_.substeps)) * inv_h;
  for (int substep = 0; substep < def_.substeps; ++substep) {
    detail::FreeStep(def_.integrator, Forces(), states_, h, free_motion_.get());
    // Forces beyond gravity may overflow: name the body before contacts spread it. (Gravity
    // alone cannot; the check at the step's end catches anything else.)
    if (ForcesBeyondGravity() && CheckFinite()) return;
    const double energy_before = force_free ? detail::KineticEnergy(states_, infos_) : 0.0;
    detail::WarmStart(constraints, states_, infos_, loaded_, start, inv_h, warm);
    for (int pass = 0; pass < def_.velocity_iterations; ++pass) {
      detail::SolveContacts(constraints, states_, start, inv_h);
    }
    if constexpr (kCanTurn) {
      if (direct) detail::SolveDirect(direct_solver_.get(), constraints, states_, start, inv_h);
    }
    if (force_free) detail::LimitContactEnergy(constraints, states_, infos_, energy_before, warm);
    if (has_up) {
      detail::PropagateShock(shock_rows_, states_, positions_before_, inv_h, def_.linear_slop);
    }
    MarkPushed(*constraints_vector);
    detail::MoveBodies(def_.integrator, states_, awake_, pushed_, def_.rotation, *free_motion_, h);
    if (def_.rotation) UpdateTurned();
    detail::PushOut(constraints, states_, start, push, push_out_rate,
                    def_.max_push_out_speed, def_.linear_slop);
    if constexpr (kCanTurn) {
      if (direct) {
        detail::PushOutDirect(direct_solver_.get(), constraints, states_, start, push, push_out_rate,
                              def_.max_push_out_speed, def_.linear_slop);
      }
    }
    detail::MoveByPush(states_, push, def_.rotation, h);
    if (def_.rotation) UpdateTurned();
  }
  detail::ApplyImpactLags<C>(constraints, contact_slot_, impact_lags_, states_);
  detail::StoreImpulses<C>(constraints, contact_slot_, contacts_);
}

bool World::Impl::CheckFinite() {
  for (BodyId id = 0; id < states_.size(); ++id) {
    const BodyState& s = states_[id];
    const char* what = !IsFinite(s.position)              ? "position"
                       : !IsFinite(s.velocity)            ? "velocity"
                       : !std::isfinite(s.angle)          ? "angle"
                       : !std::isfinite(s.angular_velocity) ? "angular velocity"
                                                          : nullptr;
    if (what) {
      fault_ = NumericFault{step_count_, id, what};
      return true;
    }
  }
  return false;
}

template <typename Constraint>
void World::Impl::MarkPushed(const std::vector<Constraint>& constraints) {
  pushed_.clear();
  if (def_.integrator == Integrator::kSemiImplicitEuler) return;  // it moves every body by h·v
  pushed_.assign(states_.size(), 0);
  for (const Constraint& c : constraints) {
    if constexpr (std::is_same_v<Constraint, LinearConstraint>) {
      if (c.normal_impulse > 0.0) pushed_[c.a] = pushed_[c.b] = 1;
    } else {
      for (int k = 0; k < c.point_count; ++k) {
        if (c.points[k].normal_impulse > 0.0) pushed_[c.a] = pushed_[c.b] = 1;
      }
    }
  }
}

bool World::Impl::ForcesBeyondGravity() const {
  return damped_bodies_ > 0 || !acting_springs_.empty() || def_.fluid_density != 0.0 ||
         def_.gravitational_constant != 0.0;
}

void World::Impl::UpdateTurned() {
  for (std::size_t i = 0; i < states_.size(); ++i) {
    turned_[i] = infos_[i].inv_inertia != 0.0 ? MakeRot(states_[i].angle - angles_before_[i]) : Rot{};
  }
}

void World::Impl::UpdateSleep() {
  // A body in a crowd is being pushed out of a pile, not resting, even when nothing else moves
  // it (no gravity): it stays awake, and so does its island, until the pile has spread.
  for (const std::uint32_t body : broad_phase_.LastCollector().CrowdedBodies()) {
    if (awake_[body]) rest_time_[body] = 0.0;
  }
  accelerations_.resize(states_.size());
  angular_accelerations_.resize(states_.size());
  Forces().Evaluate(states_, accelerations_, angular_accelerations_);
  detail::UpdateSleep(contacts_, acting_springs_, accelerations_, states_, infos_, def_,
                      {rest_time_, awake_, island_});
}

}  // namespace engine
