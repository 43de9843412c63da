// Effect particles: emitters that spawn light, short-lived particles (smoke, fire, sparks)
// feeling gravity, drag and buoyancy and bouncing off the rigid bodies, which never feel them
// (one-way). Seeded, so the same emitters make the same particles step for step. Internal.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "bodies.h"
#include "engine/ids.h"
#include "engine/particles.h"
#include "engine/world_def.h"
#include "parallel/worker_pool.h"
#include "particles/body_bins.h"
#include "particles/body_contact.h"

namespace engine::detail {

class ByteWriter;
class ByteReader;

class EffectSystem {
 public:
  EmitterId Create(const EmitterDef& def);
  void Destroy(std::uint32_t slot);
  bool IsLive(EmitterId id) const {
    return id.index < defs_.size() && alive_[id.index] && generations_[id.index] == id.generation;
  }
  std::span<const EmitterId> Ids() const { return live_ids_; }
  const EmitterDef& Def(std::uint32_t slot) const { return defs_[slot]; }
  EmitterDef& MutableDef(std::uint32_t slot) { return defs_[slot]; }
  /// An emitter riding on a body that goes stops (its particles live on).
  void BodyGone(BodyIndex body);

  /// The live particles, oldest first.
  std::span<const EffectParticle> Particles() const { return particles_; }
  bool EverUsed() const { return ever_used_; }

  /// One step of dt: ageing and deaths, motion, births, and bounces off the bodies.
  /// Motion and bounces are shared among `pool`'s threads, each particle on its own.
  void Step(const WorldDef& def, const Bodies& bodies, WorkerPool& pool);

  /// Every slot, the free list, the generators and the particles (effects_snapshot.cpp).
  void Save(ByteWriter& out) const;
  /// Replaces this system with a saved one; false, and this system unchanged, if the bytes are
  /// not a consistent save.
  bool Load(ByteReader& in);

 private:
  /// What moving one emitter's particles through a step takes, worked out once a step.
  struct Motion {
    Vec2 gravity;        ///< m/s²: the world's less the buoyancy's share
    double decay = 1.0;  ///< the drag's factor over a whole step
    double radius = 0.0; ///< m: the largest its particles grow to
  };
  /// A particle born this step, and when: the share of the step already gone.
  struct Birth {
    double fraction = 0.0;
    EffectParticle particle;
    Vec2 start;  ///< where it was born
  };

  /// A thread's planes while it bounces particles; a cache line each, as the vectors' ends
  /// change with every particle and two threads' on one line slowed both to one thread's speed.
  struct alignas(64) PlaneScratch {
    std::vector<BodyPlane> planes, touching;
  };

  void AgeAndBury(double dt);
  void Move(const WorldDef& def, WorkerPool& pool);
  void Emit(const WorldDef& def, const Bodies& bodies);
  void EmitFrom(std::uint32_t slot, const WorldDef& def, const Bodies& bodies);
  void Collide(const WorldDef& def, const Bodies& bodies, WorkerPool& pool);
  static bool CollideWith(EffectParticle* p, Vec2 start, double radius, BodyIndex body, const EmitterDef& emitter,
                          const WorldDef& def, const Bodies& bodies, PlaneScratch& scratch);
  void ReleaseDrained();
  void RebuildLiveIds();
  bool LoadParticles(ByteReader& in, std::span<const std::uint8_t> roles);

  std::vector<EmitterDef> defs_;
  std::vector<std::uint32_t> generations_;
  std::vector<std::uint8_t> alive_;
  std::vector<std::uint32_t> free_;
  std::vector<EmitterId> live_ids_;
  std::vector<std::uint64_t> random_states_;  ///< each emitter's generator
  std::vector<double> owed_births_;           ///< each emitter's fraction of a particle carried over
  std::vector<EffectParticle> particles_;
  /// Each slot's particles alive. A destroyed emitter's slot waits in draining_ until its
  /// particles have died, so they keep its def and a new emitter never takes it over.
  std::vector<std::uint32_t> alive_counts_;
  std::vector<std::uint32_t> draining_;  ///< in the order destroyed
  bool ever_used_ = false;

  // Step's scratch, kept from step to step.
  std::vector<Motion> motions_;  ///< by slot
  std::vector<Birth> births_;
  std::vector<Vec2> starts_;     ///< each particle's position when the step began (or it was born)
  double farthest_ = 0.0;        ///< m²: the square of the farthest any particle moved this step
  BodyBins bins_;
  std::vector<PlaneScratch> scratch_;     ///< one per thread
  /// Move's farthest move, one per thread (a cache line each: written by every block).
  struct alignas(64) Farthest {
    double value = 0.0;
  };
  std::vector<Farthest> thread_farthest_;
};

}  // namespace engine::detail
