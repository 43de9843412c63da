// World: body creation, the queries, and Step(), which reads as the list of phases it runs.
#include "engine/world.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "world_impl.h"

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
bool IsNonNegativeFinite(double v) { return std::isfinite(v) && v >= 0.0; }

void RequireValid(const WorldDef& def) {
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

void RequireValid(const BodyDef& def) {
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
  Require(def.is_static || IsPositiveFinite(detail::BodyMass(def)),
          "BodyDef mass (or density) must be positive and finite");
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
}

detail::ForceModel World::Impl::Forces() const {
  return {def, bodies.infos, springs.acting, sleep.awake, def.rotation, bodies.damped > 0};
}

bool World::Impl::SpeculativeContacts() const {
  return std::visit([](const auto& s) { return s.kSpeculative; }, solver);
}

World::World(const WorldDef& def) : impl_(std::make_unique<Impl>(def)) {}
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;
World::~World() = default;

BodyId World::CreateBody(const BodyDef& def) {
  RequireValid(def);
  detail::Bodies& bodies = impl_->bodies;
  const BodyInfo info = detail::MakeBodyInfo(def, impl_->def.rotation);
  if (def.linear_damping != 0.0 || def.angular_damping != 0.0) ++bodies.damped;
  if (info.inv_inertia != 0.0) ++bodies.turnable;
  BodyState state;
  state.position = def.position;
  state.angle = def.angle;
  if (!def.is_static) {
    state.velocity = def.velocity;
    state.angular_velocity = def.angular_velocity;
  }
  bodies.states.push_back(state);
  bodies.infos.push_back(info);
  impl_->sleep.AddBody(def.is_static);
  impl_->candidates.AddBody(def.shape, def.is_static);
  return static_cast<BodyId>(bodies.states.size() - 1);
}

void World::ApplyLinearImpulse(BodyId id, Vec2 impulse) {
  Require(id < BodyCount(), "ApplyLinearImpulse: no such body");
  Require(IsFinite(impulse), "ApplyLinearImpulse: impulse must be finite");
  const BodyInfo& info = impl_->bodies.infos[id];
  if (info.is_static) return;
  detail::WakeIsland(id, impl_->bodies.infos, impl_->sleep.View());
  impl_->bodies.states[id].velocity += impulse / info.mass;
}

void World::AddSpring(const SpringDef& def) {
  Require(def.body_a < BodyCount() && (!def.body_b || *def.body_b < BodyCount()), "AddSpring: no such body");
  Require(IsFinite(def.local_a) && IsFinite(def.local_b), "AddSpring: attachment points must be finite");
  Require(IsNonNegativeFinite(def.rest_length) && IsNonNegativeFinite(def.stiffness) &&
              IsNonNegativeFinite(def.damping),
          "AddSpring: rest length, stiffness and damping must be finite and >= 0");
  impl_->springs.all.push_back(def);
  if (def.stiffness != 0.0 || def.damping != 0.0) impl_->springs.acting.push_back(def);
}

void World::Step() {
  Impl& w = *impl_;
  if (w.fault) return;
  detail::Bodies& bodies = w.bodies;
  bodies.MarkStepStart();  // contacts measure how far bodies move from here
  // Broad phase: pairs whose bounds, grown by how far each body may reach, overlap.
  w.candidates.Find(w.def, w.SpeculativeContacts(), bodies.states, bodies.infos, w.sleep.awake);
  // A moving body reaching a sleeping one wakes its island; pairs where nothing moves drop out.
  detail::WakeTouchedIslands(&w.candidates.Pairs(), w.springs.acting, bodies.infos, w.sleep.View());
  // Narrow phase: manifolds, with last step's impulses to warm-start.
  w.narrow_phase.Update(w.candidates.Pairs(), bodies.states, bodies.infos, w.candidates.Margins());
  // Contact solver: forces, contacts and integration, as the chosen solver orders them.
  const detail::ForceModel forces = w.Forces();
  detail::StepContext context{.def = w.def,
                              .states = bodies.states,
                              .infos = bodies.infos,
                              .moving = w.sleep.awake,
                              .contacts = w.narrow_phase.Contacts(),
                              .start_positions = bodies.start_positions,
                              .can_turn = bodies.turnable > 0,
                              .forces = forces,
                              .free_motion = w.free_motion,
                              .step = w.step_count,
                              .fault = w.fault};
  std::visit([&](auto& solver) { solver.Step(context); }, w.solver);
  if (w.fault) return;                  // broken down mid-step: stop where it appeared
  if (w.def.sleeping) w.UpdateSleep();  // islands at rest long enough go to sleep
  // A non-finite number stops here, named, not in a frame.
  w.fault = detail::FindNonFinite(bodies.states, w.step_count);
  ++w.step_count;
}

void World::Impl::UpdateSleep() {
  // A body in a crowd is being pushed out of a pile, not resting, even when nothing else moves
  // it (no gravity): it stays awake, and so does its island, until the pile has spread.
  for (const std::uint32_t body : candidates.Budget().CrowdedBodies()) {
    if (sleep.awake[body]) sleep.rest_time[body] = 0.0;
  }
  sleep.accelerations.resize(bodies.states.size());
  sleep.angular_accelerations.resize(bodies.states.size());
  Forces().Evaluate(bodies.states, sleep.accelerations, sleep.angular_accelerations);
  detail::UpdateSleep(narrow_phase.Contacts(), springs.acting, sleep.accelerations, bodies.states,
                      bodies.infos, def, sleep.View());
}

const std::optional<NumericFault>& World::Fault() const { return impl_->fault; }
const std::vector<SpringDef>& World::Springs() const { return impl_->springs.all; }
std::size_t World::BodyCount() const { return impl_->bodies.states.size(); }
const BodyState& World::State(BodyId id) const { return impl_->bodies.states[id]; }
const BodyInfo& World::Info(BodyId id) const { return impl_->bodies.infos[id]; }
AABB World::BodyBounds(BodyId id) const {
  return detail::BodyBounds(impl_->bodies.infos[id].shape, impl_->bodies.states[id]);
}
const WorldDef& World::Def() const { return impl_->def; }
std::int64_t World::StepCount() const { return impl_->step_count; }
const std::vector<Contact>& World::Contacts() const { return impl_->narrow_phase.Contacts(); }
std::size_t World::CrowdedBodyCount() const { return impl_->candidates.Budget().CrowdedCount(); }
std::uint64_t World::DroppedPairCount() const { return impl_->candidates.Budget().DroppedCount(); }
std::uint32_t World::MostChargedPairs() const { return impl_->candidates.Budget().MostCharged(); }
bool World::IsAwake(BodyId id) const { return impl_->sleep.awake[id] != 0; }

}  // namespace engine
