// The world: it owns the bodies, steps them, and answers queries about them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "engine/body.h"
#include "engine/contact.h"
#include "engine/debug_draw.h"
#include "engine/events.h"
#include "engine/filter.h"
#include "engine/ids.h"
#include "engine/joint.h"
#include "engine/math.h"
#include "engine/particles.h"
#include "engine/queries.h"
#include "engine/shape.h"
#include "engine/snapshot.h"
#include "engine/spring.h"
#include "engine/world_def.h"

namespace engine {

class World {
 public:
  /// Preconditions: dt > 0 and finite, finite gravity, iterations ≥ 1, slop and correction ≥ 0.
  explicit World(const WorldDef& def);
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;
  ~World();

  // Every call that takes a BodyId requires a live one (IsValid): a stale or made-up id stops
  // the program with a message naming the call, never reads another body.

  /// Preconditions: positive finite size and mass (or density) for dynamic bodies, finite state,
  /// not both static and kinematic. Takes the slot of the last destroyed body, if any.
  BodyId CreateBody(const BodyDef& def);
  /// Removes the body, its contacts (with end events after the next step) and its springs; the
  /// bodies it held up wake. Its id, and every copy of it, goes stale.
  void DestroyBody(BodyId id);
  /// Whether `id` names a body that exists now.
  bool IsValid(BodyId id) const;

  /// Advances the world by one fixed step of `Def().dt`. Does nothing once a fault is recorded.
  void Step();

  /// The first non-finite state a step produced, checked at the end of every step; once set,
  /// the world stops stepping so the fault goes no further.
  const std::optional<NumericFault>& Fault() const;
  /// The contact and sensor events of the last step.
  const StepEvents& Events() const;

  // Moving bodies by hand, between steps. Each wakes the body (and, for a static or kinematic
  // body, the bodies touching it); on a static body only the placement setters act.

  /// Places the body's frame: a circle's or box's centre, the origin of a body made of parts
  /// (as BodyDef::position).
  void SetPosition(BodyId id, Vec2 position);
  void SetAngle(BodyId id, double angle);
  void SetLinearVelocity(BodyId id, Vec2 velocity);
  void SetAngularVelocity(BodyId id, double angular_velocity);
  /// Adds a force (N) acting at a world point through the next step; off the centre it also
  /// makes a torque. Dynamic bodies only feel forces; others ignore them.
  void ApplyForce(BodyId id, Vec2 force, Vec2 point);
  void ApplyForceToCenter(BodyId id, Vec2 force);
  void ApplyTorque(BodyId id, double torque);
  /// Changes a dynamic body's velocity at once by impulse / mass (N·s) and, applied at a world
  /// point off the centre, its angular velocity too; static and kinematic bodies ignore it.
  void ApplyLinearImpulse(BodyId id, Vec2 impulse, Vec2 point);
  void ApplyLinearImpulseToCenter(BodyId id, Vec2 impulse);
  void ApplyAngularImpulse(BodyId id, double impulse);

  /// A disabled body keeps its state but is not simulated: no forces, no contacts, no springs.
  void SetEnabled(BodyId id, bool enabled);
  bool IsEnabled(BodyId id) const;
  void SetFilter(BodyId id, const Filter& filter);
  const Filter& GetFilter(BodyId id) const;
  void SetUserData(BodyId id, std::uint64_t user_data);
  std::uint64_t UserData(BodyId id) const;

  /// Adds a spring (preconditions: existing bodies, finite non-negative parameters). Springs act
  /// from the next step on.
  void AddSpring(const SpringDef& def);
  const std::vector<SpringDef>& Springs() const;

  // Joints (docs/joints.md): solved with the contacts, in slot order.

  /// Preconditions: live bodies (body_b alone for kTarget), two different ones, not both of
  /// infinite mass; finite points, a non-zero axis; limits lower ≤ upper; motor caps ≥ 0;
  /// lengths ≥ 0 with min ≤ max; a spring with hertz > 0 and damping ≥ 0 (required by kTarget,
  /// with max_force > 0). Takes the slot of the last destroyed joint, if any. The two bodies
  /// wake; unless `collide`, they stop colliding with each other.
  JointId CreateJoint(const JointDef& def);
  /// Removes the joint; its bodies wake. Destroying a body destroys its joints.
  void DestroyJoint(JointId id);
  bool IsValid(JointId id) const;
  /// The live joints, in slot order.
  std::span<const JointId> JointIds() const;
  /// The joint's definition as made (with the current target and motor speed).
  const JointDef& GetJointDef(JointId id) const;
  /// Where the joint's points are now, and how far it has turned or slid.
  JointFrame Joint(JointId id) const;
  /// Moves a target joint's target (the mouse moved); wakes its body.
  void SetJointTarget(JointId id, Vec2 target);
  /// Sets a motor's speed (rad/s or m/s; the joint must have a motor); wakes its bodies.
  void SetMotorSpeed(JointId id, double speed);

  // Soft bodies, fluid and effects (engine/particles.h, docs/soft-bodies.md, docs/fluids.md):
  // stepped after the rigid bodies each step, soft bodies and fluid pushing the bodies they
  // touch as much as those push them.

  /// Preconditions: a circle or box of positive finite size, spacing > 0 (a circle gets at
  /// least 6 rim particles, a box at least one cell each way, up to 100 000 particles), finite
  /// placement, density > 0, compliances, damping and friction ≥ 0, pressure > 0, `attach_to`
  /// a live body. Takes the slot of the last
  /// destroyed soft body, if any.
  SoftBodyId CreateSoftBody(const SoftBodyDef& def);
  /// Removes the soft body and its particles; its id goes stale.
  void DestroySoftBody(SoftBodyId id);
  bool IsValid(SoftBodyId id) const;
  /// The live soft bodies, in slot order.
  std::span<const SoftBodyId> SoftBodyIds() const;
  const SoftBodyDef& GetSoftBodyDef(SoftBodyId id) const;
  /// The soft body's particles: where they are and how fast they go. A box's come row by row
  /// from its lower left corner (in its own frame), a circle's anticlockwise round its rim.
  std::span<const Vec2> SoftBodyPositions(SoftBodyId id) const;
  std::span<const Vec2> SoftBodyVelocities(SoftBodyId id) const;
  /// Its rim, as indices into its particles, anticlockwise: the outline to draw.
  std::span<const std::uint32_t> SoftBodyOutline(SoftBodyId id) const;
  /// kg: each of its particles' mass (all equal).
  double SoftBodyParticleMass(SoftBodyId id) const;
  /// m: each particle's radius (half the spacing the lattice or rim came out with).
  double SoftBodyParticleRadius(SoftBodyId id) const;
  /// Changes particle `particle`'s velocity by impulse / mass, at once.
  void ApplySoftBodyImpulse(SoftBodyId id, std::uint32_t particle, Vec2 impulse);

  /// Adds a block of fluid; returns how many particles it made. Preconditions: a region with
  /// area and finite corners, spacing > 0 (the same as earlier blocks'), density > 0,
  /// viscosity in [0, 1], vorticity and friction ≥ 0, a finite velocity.
  std::size_t AddFluid(const FluidDef& def);
  /// The fluid's particles, block by block in the order they were added, each block row by row
  /// from its lower left corner.
  std::span<const Vec2> FluidPositions() const;
  std::span<const Vec2> FluidVelocities() const;
  /// kg/m²: each fluid particle's density as the last step's kernel sum measured it.
  std::span<const double> FluidDensities() const;
  /// kg/m²: each particle's rest density (its block's FluidDef::density).
  std::span<const double> FluidRestDensities() const;
  /// kg: each fluid particle's mass.
  std::span<const double> FluidMasses() const;
  /// m: the spacing every fluid block shares (0 before the first).
  double FluidSpacing() const;
  void ApplyFluidImpulse(std::uint32_t particle, Vec2 impulse);

  /// Preconditions: finite numbers; spread, speeds, lifetimes, sizes, drag, rate, restitution
  /// and friction ≥ 0 (mean lifetime > 0, spreads no larger than their means), colours in
  /// [0, 1]; `body` a live body.
  EmitterId CreateEmitter(const EmitterDef& def);
  /// Removes the emitter; its particles live out their lives.
  void DestroyEmitter(EmitterId id);
  bool IsValid(EmitterId id) const;
  std::span<const EmitterId> EmitterIds() const;
  const EmitterDef& GetEmitterDef(EmitterId id) const;
  void SetEmitterPosition(EmitterId id, Vec2 position);
  /// Particles per second; 0 stops it.
  void SetEmitterRate(EmitterId id, double rate);
  /// The live effect particles, oldest first.
  std::span<const EffectParticle> Effects() const;

  /// The live bodies, in slot order: the order bodies are stepped, dumped and hashed in.
  std::span<const BodyId> BodyIds() const;
  std::size_t BodyCount() const;
  /// The live body in slot `index` (contacts and faults name bodies by slot).
  BodyId IdAt(BodyIndex index) const;
  const BodyState& State(BodyId id) const;
  const BodyInfo& Info(BodyId id) const;
  /// The origin of the body's frame (BodyDef::position), which the dump and the state hash
  /// report: State(id).position less the turned LocalCenter.
  Vec2 Origin(BodyId id) const;
  /// The centre of mass in the body's frame: {0, 0} for circles and boxes.
  Vec2 LocalCenter(BodyId id) const;
  /// A body's parts as BodyDef::parts gave them (empty for a lone circle or box).
  std::span<const ShapePart> Parts(BodyId id) const;
  /// The convex pieces it collides as, in the body's frame (none for a lone circle or box:
  /// Info(id).shape is all there is to it).
  std::span<const ConvexPiece> Pieces(BodyId id) const;
  AABB BodyBounds(BodyId id) const;
  /// The settings, with the automatic ones (0 substeps or iterations) filled in.
  const WorldDef& Def() const;
  std::int64_t StepCount() const;
  /// The contacts found in the last step, in body-slot-pair order (with the substep solver these
  /// include speculative ones, with a gap: negative depth).
  const std::vector<Contact>& Contacts() const;
  /// Bodies the pair budget found in a crowd in the last step, and the pairs it left out there;
  /// both 0 unless bodies are piled up (docs/limits.md).
  std::size_t CrowdedBodyCount() const;
  std::uint64_t DroppedPairCount() const;
  /// The most pairs charged to one body in the last step, against quotas of 16 and up (a measure
  /// of how far a scene is from the budget; 0 with the budget off).
  std::uint32_t MostChargedPairs() const;
  /// False while the body sleeps (and always for static, disabled and resting kinematic bodies).
  bool IsAwake(BodyId id) const;

  // Queries, between steps (docs/embedding.md). They see every enabled body, static and sensor
  // ones too; never a disabled or destroyed one. Results come in slot order, or by fraction with
  // slot order breaking ties. A `filter` keeps the bodies a body with that filter would collide
  // with (ShouldCollide, as Box2D's query filter does); without one, every body counts.

  /// The first body a ray from `from` to `to` enters, or nothing. A body the ray starts inside
  /// is not entered, so it is not reported.
  std::optional<RayHit> RayCast(Vec2 from, Vec2 to,
                                const std::optional<Filter>& filter = std::nullopt) const;
  /// Every body the ray enters, by fraction.
  std::vector<RayHit> RayCastAll(Vec2 from, Vec2 to,
                                 const std::optional<Filter>& filter = std::nullopt) const;
  /// The bodies whose bounding boxes (BodyBounds) overlap `box`; touching counts (Overlaps).
  std::vector<BodyId> OverlapAABB(const AABB& box,
                                  const std::optional<Filter>& filter = std::nullopt) const;
  /// The bodies whose shapes overlap or touch `shape` at `position`, turned by `angle` (rad).
  std::vector<BodyId> OverlapShape(const Shape& shape, Vec2 position, double angle,
                                   const std::optional<Filter>& filter = std::nullopt) const;
  /// The first body `shape` (at `position`, turned by `angle`) meets when it moves by
  /// `translation` without turning: exact up to rounding. `point` is where they touch, `normal`
  /// points from the body towards the shape. A body the shape starts overlapping is met at
  /// fraction 0 (normal {0, 0}, point `position`); one it starts only touching, at 0 when the
  /// motion goes into it, and not at all when the motion leaves it or slides along it.
  std::optional<RayHit> ShapeCast(const Shape& shape, Vec2 position, double angle, Vec2 translation,
                                  const std::optional<Filter>& filter = std::nullopt) const;

  /// Describes the world to `draw`: every live body in slot order (disabled ones as such), then
  /// the springs, the bounds and the last step's contact points, as `options` selects.
  void Draw(DebugDraw& draw, const DrawOptions& options = {}) const;

  /// FNV-1a 64 over the little-endian IEEE-754 bytes of x, y, vx, vy, angle, ω of every body,
  /// (x, y) its Origin; then, in a world with particles, x, y, vx, vy of every soft body's
  /// particles (soft bodies in slot order), of every effect particle (oldest first) and of every
  /// fluid particle (in FluidPositions order). A world without particles hashes its bodies only.
  std::uint64_t StateHash() const;

  /// The whole state as bytes: every body (destroyed slots and generations included), the
  /// springs, the sleep timers, last step's contacts with their warm-start impulses, what the
  /// events and the solver carry from step to step, the step count. A world made with the same
  /// WorldDef that restores it steps on to the same bits as this one (docs/embedding.md).
  std::vector<std::uint8_t> TakeSnapshot() const;
  /// The same into `out` (its storage reused: no allocation once it is large enough).
  void TakeSnapshot(std::vector<std::uint8_t>* out) const;
  /// Replaces this world's state with a snapshot's. Refuses (and changes nothing) a snapshot of
  /// a world with other settings, or one that is truncated or corrupt. The last step's events
  /// are not part of a snapshot: Events() is empty after a restore.
  RestoreResult RestoreSnapshot(std::span<const std::uint8_t> snapshot);

 private:
  struct Impl;  // engine/src/world_impl.h: the bodies, the step's stages and their scratch
  std::unique_ptr<Impl> impl_;
};

}  // namespace engine
