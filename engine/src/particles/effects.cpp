// Effect particles. (Being written: births and motion only so far.)
#include "particles/effects.h"

#include <algorithm>

#include "snapshot/byte_stream.h"

namespace engine::detail {

EmitterId EffectSystem::Create(const EmitterDef& def) {
  std::uint32_t slot;
  if (!free_.empty()) {
    slot = free_.back();
    free_.pop_back();
  } else {
    slot = static_cast<std::uint32_t>(defs_.size());
    defs_.emplace_back();
    generations_.push_back(0);
    alive_.push_back(0);
    random_states_.push_back(0);
    owed_births_.push_back(0.0);
  }
  defs_[slot] = def;
  alive_[slot] = 1;
  random_states_[slot] = def.seed;
  owed_births_[slot] = 0.0;
  live_ids_.clear();
  for (std::uint32_t s = 0; s < defs_.size(); ++s) {
    if (alive_[s]) live_ids_.push_back({s, generations_[s]});
  }
  ever_used_ = true;
  return {slot, generations_[slot]};
}

void EffectSystem::Destroy(std::uint32_t slot) {
  alive_[slot] = 0;
  ++generations_[slot];
  free_.push_back(slot);
  std::erase(live_ids_, EmitterId{slot, generations_[slot] - 1});
}

void EffectSystem::BodyGone(BodyIndex body) {
  for (std::uint32_t s = 0; s < defs_.size(); ++s) {
    if (alive_[s] && defs_[s].body && defs_[s].body->index == body) defs_[s].rate = 0.0;
  }
}

void EffectSystem::Step(const WorldDef& def, const Bodies& bodies) {
  (void)def;
  (void)bodies;
}

void EffectSystem::Save(ByteWriter& out) const { (void)out; }
bool EffectSystem::Load(ByteReader& in) { return in.Ok(); }

}  // namespace engine::detail
