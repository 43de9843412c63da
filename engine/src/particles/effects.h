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

  /// One step of dt: births, ageing and deaths, motion, and bounces off the bodies.
  void Step(const WorldDef& def, const Bodies& bodies);

  void Save(ByteWriter& out) const;
  bool Load(ByteReader& in);

 private:
  std::vector<EmitterDef> defs_;
  std::vector<std::uint32_t> generations_;
  std::vector<std::uint8_t> alive_;
  std::vector<std::uint32_t> free_;
  std::vector<EmitterId> live_ids_;
  std::vector<std::uint64_t> random_states_;  ///< each emitter's generator
  std::vector<double> owed_births_;           ///< each emitter's fraction of a particle carried over
  std::vector<EffectParticle> particles_;
  bool ever_used_ = false;
};

}  // namespace engine::detail
