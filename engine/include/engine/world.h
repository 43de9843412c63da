// The world: it owns the bodies, steps them, and answers queries about them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "engine/body.h"
#include "engine/contact.h"
#include "engine/events.h"
#include "engine/ids.h"
#include "engine/math.h"
#include "engine/queries.h"
#include "engine/shape.h"
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

  /// Preconditions: positive finite size and mass (or density) for dynamic bodies, finite state.
  BodyId CreateBody(const BodyDef& def);

  /// Advances the world by one fixed step of `Def().dt`. Does nothing once a fault is recorded.
  void Step();

  /// The first non-finite state a step produced, checked at the end of every step; once set,
  /// the world stops stepping so the fault goes no further.
  const std::optional<NumericFault>& Fault() const;

  /// Changes a dynamic body's velocity by impulse / mass (N·s, applied at the centre); static
  /// bodies ignore it.
  void ApplyLinearImpulse(BodyId id, Vec2 impulse);

  /// Adds a spring (preconditions: existing bodies, finite non-negative parameters). Springs act
  /// from the next step on.
  void AddSpring(const SpringDef& def);
  const std::vector<SpringDef>& Springs() const;

  std::size_t BodyCount() const;
  const BodyState& State(BodyId id) const;
  const BodyInfo& Info(BodyId id) const;
  AABB BodyBounds(BodyId id) const;
  /// The settings, with the automatic ones (0 substeps or iterations) filled in.
  const WorldDef& Def() const;
  std::int64_t StepCount() const;
  /// The contacts found in the last step, in body-pair order (with the substep solver these
  /// include speculative ones, with a gap: negative depth).
  const std::vector<Contact>& Contacts() const;
  /// Bodies the pair budget found in a crowd in the last step, and the pairs it left out there;
  /// both 0 unless bodies are piled up (docs/limits.md).
  std::size_t CrowdedBodyCount() const;
  std::uint64_t DroppedPairCount() const;
  /// The most pairs charged to one body in the last step, against quotas of 16 and up (a measure
  /// of how far a scene is from the budget; 0 with the budget off).
  std::uint32_t MostChargedPairs() const;
  /// False while the body sleeps (and always for static bodies).
  bool IsAwake(BodyId id) const;

  /// The first body a ray from `from` to `to` hits (static or dynamic), or nothing.
  std::optional<RayHit> RayCast(Vec2 from, Vec2 to) const;

  /// FNV-1a 64 over the little-endian IEEE-754 bytes of x, y, vx, vy, angle, ω of every body.
  std::uint64_t StateHash() const;

 private:
  struct Impl;  // engine/src/world_impl.h: the bodies, the step's stages and their scratch
  std::unique_ptr<Impl> impl_;
};

}  // namespace engine
