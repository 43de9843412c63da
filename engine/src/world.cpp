// World: body creation, the queries, and Step(), which reads as the list of phases it runs.
#include "engine/world.h"

#include <cmath>

#include "continuous.h"
#include "require.h"
#include "world_impl.h"

namespace engine {

namespace {

using detail::IsNonNegativeFinite;
using detail::IsPositiveFinite;
using detail::Require;

void RequireValid(const WorldDef& def) {
  Require(IsPositiveFinite(def.dt), "WorldDef::dt must be positive and finite");
  Require(IsFinite(def.gravity), "WorldDef::gravity must be finite");
  Require(def.velocity_iterations >= 0, "WorldDef::velocity_iterations must be >= 0");
  Require(def.circle_velocity_iterations >= 0, "WorldDef::circle_velocity_iterations must be >= 0");
  Require(def.substeps >= 0, "WorldDef::substeps must be >= 0");
  Require(def.threads >= 1 && def.threads <= kMaxThreads, "WorldDef::threads must be in [1, 256]");
  Require(def.substep_features.lanes == 0 || def.substep_features.lanes == 1 || def.substep_features.lanes == 2 ||
              def.substep_features.lanes == 4,
          "WorldDef::substep_features.lanes must be 0, 1, 2 or 4");
  Require(IsPositiveFinite(def.max_push_out_speed), "WorldDef::max_push_out_speed must be > 0");
  Require(IsNonNegativeFinite(def.restitution_threshold),
          "WorldDef::restitution_threshold must be finite and >= 0");
  Require(IsNonNegativeFinite(def.linear_slop), "WorldDef::linear_slop must be finite and >= 0");
  Require(def.position_correction >= 0.0 && def.position_correction <= 1.0,
          "WorldDef::position_correction must be in [0, 1]");
  Require(IsNonNegativeFinite(def.sleep_speed) && IsNonNegativeFinite(def.time_to_sleep),
          "WorldDef sleep settings must be finite and >= 0");
}

detail::AnyContactSolver MakeSolver(ContactSolver solver) {
  if (solver == ContactSolver::kSequentialImpulse) return detail::SequentialImpulseSolver{};
  return detail::SubstepSolver{};
}

// The settings a scene left at 0 ("automatic") get the values the chosen solver needs.
WorldDef WithAutomaticSettings(WorldDef def, const detail::AnyContactSolver& solver) {
  std::visit([&](const auto& s) { s.FillAutomaticSettings(&def); }, solver);
  return def;
}

}  // namespace

World::Impl::Impl(const WorldDef& world_def)
    : solver(MakeSolver(world_def.solver)) {
  RequireValid(world_def);
  def = WithAutomaticSettings(world_def, solver);
  pool = std::make_unique<detail::WorkerPool>(def.threads);
}

detail::ForceModel World::Impl::Forces() const {
  const bool applied = bodies.forces_applied;
  return {.def = def,
          .infos = bodies.infos,
          .springs = springs.acting,
          .moving = sleep.awake,
          .applied_forces = applied ? std::span<const Vec2>(bodies.applied_forces) : std::span<const Vec2>(),
          .applied_torques = applied ? std::span<const double>(bodies.applied_torques) : std::span<const double>(),
          .rotation = def.rotation,
          .damping = bodies.damped > 0,
          .enabled = bodies.inactive > 0 ? std::span<const std::uint8_t>(bodies.enabled)
                                         : std::span<const std::uint8_t>(),
          .geometries = bodies.with_parts > 0 ? std::span<const std::shared_ptr<const detail::BodyGeometry>>(
                                                    bodies.geometries)
                                              : std::span<const std::shared_ptr<const detail::BodyGeometry>>()};
}

bool World::Impl::SpeculativeContacts() const {
  return std::visit([](const auto& s) { return s.kSpeculative; }, solver);
}

World::World(const WorldDef& def) : impl_(std::make_unique<Impl>(def)) {}
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;
World::~World() = default;

void World::Step() {
  Impl& w = *impl_;
  if (w.fault) return;
  // The pool judges whether its threads ran alongside this step (WorldDef::adapt_threads).
  struct PoolStep {
    detail::WorkerPool* pool;
    explicit PoolStep(detail::WorkerPool* p) : pool(p) {
      if (pool) pool->BeginStep();
    }
    ~PoolStep() {
      if (pool) pool->EndStep();
    }
    PoolStep(const PoolStep&) = delete;
    PoolStep& operator=(const PoolStep&) = delete;
  } pool_step(w.def.adapt_threads ? w.pool.get() : nullptr);
  detail::Bodies& bodies = w.bodies;
  w.events.Clear();  // keeps the lists' storage from step to step
  bodies.MarkStepStart(w.pool.get());  // contacts measure how far bodies move from here
  if (!w.particles.Empty()) w.particles.MarkStepStart(bodies);  // particles see bodies move through the step
  // Broad phase: pairs of enabled bodies whose bounds, grown by how far each may reach, overlap
  // and whose filters let them meet.
  w.candidates.Find(w.def, w.SpeculativeContacts(), bodies, w.sleep.awake, *w.pool);
  if (w.joints.stale) w.joints.Rebuild(bodies.enabled);
  // Bodies a joint holds together do not collide, unless the joint says they do.
  detail::DropJoinedPairs(w.joints.no_collide, &w.candidates.Pairs());
  // Pairs with a sensor only report overlaps, after the step.
  if (bodies.sensors > 0) w.sensors.TakeSensorPairs(&w.candidates.Pairs(), bodies.infos);
  // A moving body reaching a sleeping one wakes its island; pairs where nothing moves drop out.
  detail::WakeTouchedIslands(&w.candidates.Pairs(), w.springs.acting, w.joints.links, bodies.infos,
                             w.sleep.View(), w.pool.get(), &w.sleep.kept_pairs);
  // Narrow phase: manifolds, with last step's impulses to warm-start.
  w.narrow_phase.Update(w.candidates.Pairs(), bodies.states, bodies.infos, bodies.geometries,
                        w.candidates.Margins(), w.candidates.BoxTurns(), bodies.with_parts > 0, *w.pool);
  if (w.def.contact_events) w.contact_events.RecordStartVelocities(bodies.states, *w.pool);
  // Contact solver: forces, contacts and integration, as the chosen solver orders them.
  const detail::ForceModel forces = w.Forces();
  detail::StepContext context{.def = w.def,
                              .states = bodies.states,
                              .infos = bodies.infos,
                              .moving = w.sleep.awake,
                              .contacts = w.narrow_phase.Contacts(),
                              .contact_pairs = w.narrow_phase.ContactPairs(),
                              .start_positions = bodies.start_positions,
                              .can_turn = bodies.turnable > 0,
                              .forces = forces,
                              .free_motion = w.free_motion,
                              .joints = w.joints.acting.empty() ||
                                                !w.joint_solver.Prepare(&w.joints, bodies.states, bodies.infos,
                                                                        w.sleep.awake, w.def, *w.pool)
                                            ? nullptr
                                            : &w.joint_solver,
                              .step = w.step_count,
                              .fault = w.fault,
                              .pool = *w.pool};
  std::visit([&](auto& solver) { solver.Step(context); }, w.solver);
  bodies.ClearAppliedForces();
  if (w.fault) return;                  // broken down mid-step: stop where it appeared
  // Fast bodies made of parts that the step carried through something go back to the touch.
  if (bodies.with_parts > 0 && w.def.continuous) {
    detail::SolveContinuous(bodies, bodies.start_angles, w.candidates.Pairs(), w.sleep.awake,
                            context.joints ? context.joints->Joined() : std::span<const std::uint8_t>(), w.def);
  }
  // Soft bodies and fluid, two-way with the bodies they touch; then the effect particles.
  w.StepParticles();
  if (w.fault) return;
  if (w.def.sleeping) w.UpdateSleep();  // islands at rest long enough go to sleep
  // Events: contacts that began or ended touching, sensors that began or ended overlapping.
  if (w.def.contact_events) {
    w.contact_events.Update(w.narrow_phase.Contacts(), bodies, w.sleep.awake, w.def, *w.pool, &w.events);
  }
  if (bodies.sensors > 0 || w.sensors.HasQueuedEnds()) w.sensors.Update(bodies, &w.events);
  // A non-finite number stops here, named, not in a frame.
  w.fault = detail::FindNonFinite(bodies.states, w.step_count, w.pool.get());
  ++w.step_count;
}

void World::Impl::UpdateSleep() {
  // A body in a crowd is being pushed out of a pile, not resting, even when nothing else moves
  // it (no gravity): it stays awake, and so does its island, until the pile has spread.
  for (const std::uint32_t crowded : candidates.Budget().CrowdedBodies()) {
    const BodyIndex body = candidates.CrowdedSlot(crowded);
    if (sleep.awake[body]) sleep.rest_time[body] = 0.0;
  }
  sleep.accelerations.resize(bodies.states.size());
  sleep.angular_accelerations.resize(bodies.states.size());
  Forces().Evaluate(bodies.states, sleep.accelerations, sleep.angular_accelerations);
  detail::UpdateSleep(narrow_phase.Contacts(), springs.acting, joints.links, sleep.accelerations, bodies.states,
                      bodies.infos, def, sleep.View());
}

const std::optional<NumericFault>& World::Fault() const { return impl_->fault; }
const StepEvents& World::Events() const { return impl_->events; }
const std::vector<SpringDef>& World::Springs() const { return impl_->springs.all; }
std::span<const BodyId> World::BodyIds() const { return impl_->bodies.live_ids; }
std::size_t World::BodyCount() const { return impl_->bodies.live_ids.size(); }
BodyId World::IdAt(BodyIndex index) const {
  Require(index < impl_->bodies.alive.size() && impl_->bodies.alive[index], "IdAt: no body in that slot");
  return impl_->bodies.IdOf(index);
}
const BodyState& World::State(BodyId id) const { return impl_->bodies.states[impl_->Slot(id, "State")]; }
const BodyInfo& World::Info(BodyId id) const { return impl_->bodies.infos[impl_->Slot(id, "Info")]; }
AABB World::BodyBounds(BodyId id) const {
  const BodyIndex i = impl_->Slot(id, "BodyBounds");
  return detail::BoundsOf(impl_->bodies, i);
}
Vec2 World::Origin(BodyId id) const { return impl_->bodies.Origin(impl_->Slot(id, "Origin")); }
Vec2 World::LocalCenter(BodyId id) const {
  const auto& geometry = impl_->bodies.geometries[impl_->Slot(id, "LocalCenter")];
  return geometry ? geometry->local_center : Vec2{};
}
std::span<const ShapePart> World::Parts(BodyId id) const {
  const auto& geometry = impl_->bodies.geometries[impl_->Slot(id, "Parts")];
  return geometry ? std::span<const ShapePart>(geometry->parts) : std::span<const ShapePart>();
}
std::span<const ConvexPiece> World::Pieces(BodyId id) const {
  const auto& geometry = impl_->bodies.geometries[impl_->Slot(id, "Pieces")];
  return geometry ? std::span<const ConvexPiece>(geometry->public_pieces) : std::span<const ConvexPiece>();
}
const WorldDef& World::Def() const { return impl_->def; }
std::int64_t World::StepCount() const { return impl_->step_count; }
const std::vector<Contact>& World::Contacts() const { return impl_->narrow_phase.Contacts(); }
std::size_t World::CrowdedBodyCount() const { return impl_->candidates.Budget().CrowdedCount(); }
std::uint64_t World::DroppedPairCount() const { return impl_->candidates.Budget().DroppedCount(); }
std::uint32_t World::MostChargedPairs() const { return impl_->candidates.Budget().MostCharged(); }
bool World::IsAwake(BodyId id) const { return impl_->sleep.awake[impl_->Slot(id, "IsAwake")] != 0; }

}  // namespace engine
