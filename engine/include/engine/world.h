// The world: body definitions, world settings, and World, which owns the bodies and steps them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "engine/broadphase.h"
#include "engine/collide.h"
#include "engine/contact.h"
#include "engine/forces.h"
#include "engine/math.h"

namespace engine {

namespace detail {
struct FreeMotion;
struct ForceModel;
struct DirectSolver;
struct ShockRow;
struct ShockScratch;
}  // namespace detail

enum class ShapeType : std::uint8_t { kCircle, kBox };

struct Shape {
  ShapeType type = ShapeType::kCircle;
  double radius = 0.5;             ///< m, circles only
  Vec2 half_extents{0.5, 0.5};     ///< m, boxes only (half the width and height)
};

enum class Integrator : std::uint8_t {
  kSemiImplicitEuler,  ///< velocity first, then position with the new velocity (symplectic)
  kExplicitEuler,      ///< position with the old velocity, then velocity (the seed's)
  kVelocityVerlet,     ///< position by the old acceleration, velocity by the mean of old and new
  kMidpoint,           ///< explicit second-order Runge-Kutta through the midpoint
  kRungeKutta4,        ///< the classic fourth-order Runge-Kutta
};

enum class ContactSolver : std::uint8_t {
  /// An impact pass for bounces, then substeps of warm-started rigid contacts with shock
  /// propagation and a split-impulse push-out (after Catto's "soft step")
  kSubstep,
  kSeed,  ///< the seed: rounds of impulses per step, then a projection; the baseline
};

struct BodyDef {
  Shape shape;
  Vec2 position;                  ///< centre, m
  Vec2 velocity;                  ///< m/s
  double angle = 0.0;             ///< rad (kept, not integrated, while rotation is off)
  double angular_velocity = 0.0;  ///< rad/s
  double mass = 0.0;              ///< kg; 0 means density × area
  double density = 1.0;           ///< kg/m², used when mass is 0
  bool is_static = false;         ///< infinite mass: never moves
  double restitution = 0.2;
  double friction = 0.3;
  bool fixed_rotation = false;
  bool bullet = false;
  double linear_damping = 0.0;    ///< 1/s: a force −c·m·v
  double angular_damping = 0.0;   ///< 1/s: a torque −c·I·ω
  /// Quadratic drag coefficient C_d in a fluid; negative means the shape's usual value
  /// (0.47 for a circle, 1.05 for a box).
  double drag_coefficient = -1.0;
};

struct WorldDef {
  Vec2 gravity{0.0, -9.8};              ///< m/s²
  double fluid_density = 0.0;           ///< kg/m³ of the air or water around; 0: vacuum, no drag
  double gravitational_constant = 0.0;  ///< N·m²/kg² between bodies; 0: no mutual gravitation
  double dt = 1.0 / 60.0;               ///< the fixed step, s
  bool rotation = false;                ///< false: the axis-aligned game, no angular work at all
  Integrator integrator = Integrator::kSemiImplicitEuler;
  BroadPhaseType broad_phase = BroadPhaseType::kAuto;
  ContactSolver solver = ContactSolver::kSubstep;
  int substeps = 0;                     ///< substep solver: substeps per step; 0: 4, or 8 with rotation
  double max_push_out_speed = 3.0;      ///< substep solver: m/s; overlap goes no faster than this
  /// Contact solver passes: per step for the seed (0: 10), per substep for the substep solver
  /// (0: 1, or 4 with rotation).
  int velocity_iterations = 0;
  double restitution_threshold = 1.0;   ///< m/s; slower impacts do not bounce, so rest is quiet
  double linear_slop = 0.005;           ///< m of overlap left alone, so resting contacts don't jitter
  double position_correction = 0.8;     ///< fraction of the overlap beyond the slop removed per step
  bool sleeping = true;                 ///< bodies at rest for a while stop costing work
  /// Fast bodies (moving over half their size per step) are caught wherever they pass; false:
  /// only where they land each step, so they may tunnel (bullets are always caught).
  bool continuous = true;
  double sleep_speed = 0.05;            ///< m/s below which a body counts as resting
  double time_to_sleep = 0.5;           ///< s an island must rest before it sleeps
  /// Bodies piled up keep a bounded number of contacts (the pair budget, docs/limits.md), so
  /// memory stays linear in the body count; false: every overlapping pair is a contact, at a cost
  /// quadratic in a pile's size (for tests that compare the two).
  bool pair_budget = true;
};

/// What every step writes.
struct BodyState {
  Vec2 position;
  Vec2 velocity;
  double angle = 0.0;
  double angular_velocity = 0.0;
};

/// What a step only reads.
/// The first non-finite number the simulation produced: which body, in which step, and which
/// part of its state. Inputs are checked when they enter, so this means the numbers overflowed.
struct NumericFault {
  std::int64_t step;  ///< the step that produced it (StepCount() before that step)
  BodyId body;
  const char* what;   ///< "position", "velocity", "angle" or "angular velocity"
};

/// Where a ray first meets a body.
struct RayHit {
  BodyId body;
  Vec2 point;       ///< on the body's outline
  Vec2 normal;      ///< the outline's outward normal there
  double fraction;  ///< of the way from the ray's start to its end, in [0, 1]
};

struct BodyInfo {
  Shape shape;
  double mass = 0.0;      ///< kg; 0 for static bodies
  double inv_mass = 0.0;  ///< 1/kg; 0 for static bodies, so impulses never move them
  double inertia = 0.0;      ///< kg·m² about the centre; 0 for static bodies
  double inv_inertia = 0.0;  ///< 0 for static bodies, fixed rotation, or a world without rotation
  double linear_damping = 0.0;
  double angular_damping = 0.0;
  double drag_coefficient = 0.0;
  double restitution = 0.0;
  double friction = 0.0;
  bool is_static = false;
  bool fixed_rotation = false;
  bool bullet = false;
};

class World {
 public:
  /// Preconditions: dt > 0 and finite, finite gravity, iterations ≥ 1, slop and correction ≥ 0.
  explicit World(const WorldDef& def);
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;
  ~World();

  /// Preconditions: positive finite size and mass (or density) for dynamic bodies, finite state.
  BodyId CreateBody(const BodyDef& def);

  /// Advances the world by one fixed step of `Def().dt`. Does nothing once a fault is recorded.
  void Step();

  /// The first non-finite state a step produced, checked at the end of every step; once set,
  /// the world stops stepping so the fault goes no further.
  const std::optional<NumericFault>& Fault() const { return fault_; }

  /// Changes a dynamic body's velocity by impulse / mass (N·s, applied at the centre); static
  /// bodies ignore it.
  void ApplyLinearImpulse(BodyId id, Vec2 impulse);

  /// Adds a spring (preconditions: existing bodies, finite non-negative parameters). Springs act
  /// from the next step on.
  void AddSpring(const SpringDef& def);
  const std::vector<SpringDef>& Springs() const { return springs_; }

  std::size_t BodyCount() const { return states_.size(); }
  const BodyState& State(BodyId id) const { return states_[id]; }
  const BodyInfo& Info(BodyId id) const { return infos_[id]; }
  AABB BodyBounds(BodyId id) const;
  const WorldDef& Def() const { return def_; }
  std::int64_t StepCount() const { return step_count_; }
  /// The contacts found in the last step, in body-pair order (with the substep solver these
  /// include speculative ones, with a gap: negative depth).
  const std::vector<Contact>& Contacts() const { return contacts_; }
  /// Bodies the pair budget found in a crowd in the last step, and the pairs it left out there;
  /// both 0 unless bodies are piled up (docs/limits.md).
  std::size_t CrowdedBodyCount() const { return crowded_bodies_; }
  std::uint64_t DroppedPairCount() const { return dropped_pairs_; }
  /// The most pairs charged to one body in the last step, against quotas of 16 and up (a measure
  /// of how far a scene is from the budget; 0 with the budget off).
  std::uint32_t MostChargedPairs() const { return most_charged_; }
  /// False while the body sleeps (and always for static bodies).
  bool IsAwake(BodyId id) const { return awake_[id] != 0; }

  /// The first body a ray from `from` to `to` hits (static or dynamic), or nothing.
  std::optional<RayHit> RayCast(Vec2 from, Vec2 to) const;

  /// FNV-1a 64 over the little-endian IEEE-754 bytes of x, y, vx, vy, angle, ω of every body.
  std::uint64_t StateHash() const;

 private:
  void FindCandidatePairs();
  void BuildContacts();
  void StepSeed();
  void StepSubstep();
  template <typename C>
  void StepSubstep(std::vector<C>* constraints);
  void UpdateSleep();
  /// Records a fault for the first body (in id order) with a non-finite state; true if any.
  bool CheckFinite();
  /// Sets `pushed_` to the bodies a contact pushed (positive normal impulse), for the
  /// integrators that move bodies by more than h·v; empty for semi-implicit Euler.
  template <typename Constraint>
  void MarkPushed(const std::vector<Constraint>& constraints);
  /// Whether any force besides gravity acts (damping, drag, springs, gravitation).
  bool ForcesBeyondGravity() const;
  /// How far each body has turned since the step's start, for the contacts' separations.
  void UpdateTurned();
  /// How far a body may reach within a step (speculative margin), m.
  double Reach(BodyId id) const;
  detail::ForceModel Forces() const;

  WorldDef def_;
  std::vector<BodyState> states_;
  std::vector<BodyInfo> infos_;
  std::vector<SpringDef> springs_;
  std::size_t damped_bodies_ = 0;  ///< bodies with linear or angular damping
  std::size_t turnable_bodies_ = 0;  ///< bodies free to turn (finite inertia)
  /// The springs that pull at all (stiffness or damping not 0), in the order added: the only ones
  /// the force evaluations, waking and sleep see, so a spring with nothing to pull costs nothing.
  std::vector<SpringDef> acting_springs_;
  std::int64_t step_count_ = 0;
  std::optional<NumericFault> fault_;
  // Sleep state per body; `awake` doubles as the "moving" mask the integrators read.
  std::vector<double> rest_time_;
  std::vector<std::uint8_t> awake_;
  std::vector<std::uint32_t> island_;
  std::vector<PairQuota> quotas_;  ///< per body, from its shape: the pair budget's inputs
  std::size_t crowded_bodies_ = 0;
  std::uint64_t dropped_pairs_ = 0;
  std::uint32_t most_charged_ = 0;

  // Scratch reused across steps, so a step allocates nothing once the scene has settled in.
  std::vector<AABB> bounds_;
  std::vector<double> reach_;
  std::vector<BodyPair> pairs_;
  std::vector<Contact> contacts_;
  std::vector<Contact> previous_contacts_;
  std::vector<Vec2> positions_before_;
  std::unique_ptr<detail::FreeMotion> free_motion_;
  std::vector<Vec2> accelerations_;
  std::vector<double> angular_accelerations_;
  std::vector<std::uint8_t> pushed_;
  std::vector<Vec2> push_velocities_;
  std::vector<double> push_angular_velocities_;
  std::vector<std::uint8_t> loaded_;  ///< an applied force acts on the body (substep solver)
  std::vector<Vec2> warm_free_;
  std::vector<double> warm_free_angular_;
  std::vector<double> angles_before_;
  std::vector<Rot> turned_;
  std::vector<ContactConstraint> seed_constraints_;
  std::vector<std::uint64_t> body_colours_;  ///< the colours each body's contacts have taken
  std::vector<std::uint32_t> contact_slot_;  ///< each contact's place in the solve order
  std::vector<SubstepConstraint> substep_constraints_;  ///< where something can turn
  std::vector<LinearConstraint> linear_constraints_;    ///< where nothing can
  std::vector<double> impact_lags_;                     ///< per contact (ResolveImpacts)
  std::unique_ptr<detail::DirectSolver> direct_solver_;  ///< islands with a large mass ratio
  std::unique_ptr<detail::ShockScratch> shock_scratch_;
  std::vector<detail::ShockRow> shock_rows_;
  BroadPhase broad_phase_;  ///< every structure, so the choice can change between steps
};

}  // namespace engine
