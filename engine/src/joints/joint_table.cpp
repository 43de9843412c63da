// Joint slots: allocation, and the lists a step reads, rebuilt when joints or bodies change.
#include "joints/joint_table.h"

#include <algorithm>

namespace engine::detail {

namespace {
bool SlotBefore(JointId x, JointId y) { return x.index < y.index; }
}  // namespace

std::uint32_t JointTable::Allocate() {
  stale = true;
  std::uint32_t slot;
  if (!free_slots.empty()) {
    slot = free_slots.back();
    free_slots.pop_back();
    alive[slot] = 1;
  } else {
    joints.emplace_back();
    generations.push_back(0);
    alive.push_back(1);
    slot = static_cast<std::uint32_t>(joints.size() - 1);
  }
  const JointId id{slot, generations[slot]};
  live_ids.insert(std::lower_bound(live_ids.begin(), live_ids.end(), id, SlotBefore), id);
  return slot;
}

void JointTable::Free(std::uint32_t slot) {
  stale = true;
  const auto at = std::lower_bound(live_ids.begin(), live_ids.end(), JointId{slot, 0}, SlotBefore);
  live_ids.erase(at);
  alive[slot] = 0;
  ++generations[slot];
  free_slots.push_back(slot);
}

void JointTable::Rebuild(std::span<const std::uint8_t> body_enabled) {
  stale = false;
  acting.clear();
  no_collide.clear();
  links.clear();
  for (std::uint32_t slot = 0; slot < joints.size(); ++slot) {
    if (!alive[slot]) continue;
    const Joint& j = joints[slot];
    if (!body_enabled[j.b] || (j.a != kNoBody && !body_enabled[j.a])) continue;
    acting.push_back(slot);
    if (j.a == kNoBody) continue;
    links.push_back(MakePair(j.a, j.b));
    if (!j.def.collide) no_collide.push_back(MakePair(j.a, j.b));
  }
  std::sort(no_collide.begin(), no_collide.end());
  no_collide.erase(std::unique(no_collide.begin(), no_collide.end()), no_collide.end());
}

void DropJoinedPairs(std::span<const BodyPair> no_collide, std::vector<BodyPair>* pairs) {
  if (no_collide.empty()) return;
  std::erase_if(*pairs, [&](BodyPair p) { return std::binary_search(no_collide.begin(), no_collide.end(), p); });
}

}  // namespace engine::detail
