// Greedy colouring with a 64-bit mask of taken colours per body, then a stable counting sort.
#include "solver/contact_order.h"

#include <algorithm>
#include <array>
#include <bit>

namespace engine::detail {

void ColourContacts(std::span<const Contact> contacts, std::span<const BodyInfo> infos,
                    std::vector<std::uint64_t>* body_colours, std::vector<std::uint32_t>* slot) {
  constexpr int kColours = 64;
  std::vector<std::uint64_t>& taken = *body_colours;
  taken.assign(infos.size(), 0);
  slot->resize(contacts.size());
  // First the colour of each contact (kept in `slot` for now) and how many take each one.
  std::array<std::uint32_t, kColours + 1> first{};
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const BodyIndex a = contacts[i].a, b = contacts[i].b;
    // A body with every colour taken shares the last one: that only costs parallelism.
    const int colour = std::min(std::countr_one(taken[a] | taken[b]), kColours - 1);
    const std::uint64_t bit = std::uint64_t{1} << colour;
    if (!HasInfiniteMass(infos[a])) taken[a] |= bit;
    if (!HasInfiniteMass(infos[b])) taken[b] |= bit;
    (*slot)[i] = static_cast<std::uint32_t>(colour);
    ++first[colour + 1];
  }
  for (int c = 1; c <= kColours; ++c) first[c] += first[c - 1];
  for (std::uint32_t& s : *slot) s = first[s]++;
}

}  // namespace engine::detail
