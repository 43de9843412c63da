// Joint slots: allocation, and the lists a step reads, rebuilt when joints or bodies change.
#include "joints/joint_table.h"

#include <algorithm>

namespace engine::detail {

std::uint32_t JointTable::Allocate() {
  if (!free_slots.empty()) {
    const std::uint32_t slot = free_slots.back();
    free_slots.pop_back();
    alive[slot] = 1;
    return slot;
  }
  joints.emplace_back();
  generations.push_back(0);
  alive.push_back(1);
  return static_cast<std::uint32_t>(joints.size() - 1);
}

void JointTable::Free(std::uint32_t slot) {
  alive[slot] = 0;
  ++generations[slot];
  free_slots.push_back(slot);
}

void JointTable::Rebuild(std::span<const std::uint8_t> body_enabled) {
  acting.clear();
  no_collide.clear();
  links.clear();
  live_ids.clear();
  for (std::uint32_t slot = 0; slot < joints.size(); ++slot) {
    if (!alive[slot]) continue;
    live_ids.push_back({slot, generations[slot]});
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
