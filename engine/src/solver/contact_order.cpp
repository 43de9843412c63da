// Greedy colouring with a 64-bit mask of taken colours per body, then a stable counting sort.
#include "solver/contact_order.h"

#include <algorithm>
#include <array>
#include <bit>

namespace engine::detail {

namespace {

// `slot` holds each contact's group on entry; on return its place in the contacts sorted by
// group (ties in contact order), with `group_ends` each group's end.
void SortByGroup(std::uint32_t groups, std::vector<std::uint32_t>* slot,
                 std::vector<std::uint32_t>* group_ends) {
  std::vector<std::uint32_t>& ends = *group_ends;
  ends.assign(groups, 0);
  for (const std::uint32_t g : *slot) ++ends[g];
  std::uint32_t total = 0;
  for (std::uint32_t& end : ends) end = total += end;
  // Walking the groups' starts up from each group's start.
  std::vector<std::uint32_t> next(groups);
  for (std::uint32_t g = 0; g < groups; ++g) next[g] = g == 0 ? 0 : ends[g - 1];
  for (std::uint32_t& s : *slot) s = next[s]++;
}

}  // namespace

void ColourContacts(std::span<const Contact> contacts, std::span<const BodyInfo> infos,
                    std::vector<std::uint64_t>* body_marks, std::vector<std::uint32_t>* slot,
                    std::vector<std::uint32_t>* group_ends) {
  constexpr int kColours = kSharedColour + 1;
  std::vector<std::uint64_t>& taken = *body_marks;
  taken.assign(infos.size(), 0);
  slot->resize(contacts.size());
  int colours = 0;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const BodyIndex a = contacts[i].a, b = contacts[i].b;
    // A body with every colour taken shares the last one, which is solved on one thread.
    const int colour = std::min(std::countr_one(taken[a] | taken[b]), kColours - 1);
    const std::uint64_t bit = std::uint64_t{1} << colour;
    if (!HasInfiniteMass(infos[a])) taken[a] |= bit;
    if (!HasInfiniteMass(infos[b])) taken[b] |= bit;
    (*slot)[i] = static_cast<std::uint32_t>(colour);
    colours = std::max(colours, colour + 1);
  }
  SortByGroup(static_cast<std::uint32_t>(colours), slot, group_ends);
}

void StripContacts(std::span<const Contact> contacts, std::span<const BodyInfo> infos,
                   std::span<const BodyState> states, Vec2 across, int strips,
                   std::vector<std::uint64_t>* body_marks, std::vector<std::uint32_t>* slot,
                   std::vector<std::uint32_t>* group_ends) {
  // The span of the moving bodies in contact, along `across`.
  double lo = 0.0, hi = 0.0;
  bool any = false;
  for (const Contact& c : contacts) {
    for (const BodyIndex b : {c.a, c.b}) {
      if (HasInfiniteMass(infos[b])) continue;
      const double x = Dot(states[b].position, across);
      lo = any ? std::min(lo, x) : x;
      hi = any ? std::max(hi, x) : x;
      any = true;
    }
  }
  const double scale = hi > lo ? strips / (hi - lo) : 0.0;
  // body_marks[b]: body b's strip, for the moving bodies of a contact.
  std::vector<std::uint64_t>& strip_of = *body_marks;
  strip_of.resize(infos.size());
  for (const Contact& c : contacts) {
    for (const BodyIndex b : {c.a, c.b}) {
      const double s = (Dot(states[b].position, across) - lo) * scale;
      const auto last = static_cast<std::uint64_t>(strips - 1);
      strip_of[b] = s < strips - 1.0 ? (s > 0.0 ? static_cast<std::uint64_t>(s) : 0) : last;
    }
  }
  const StripGroups groups(strips);
  slot->resize(contacts.size());
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const BodyIndex a = contacts[i].a, b = contacts[i].b;
    const bool moves_a = !HasInfiniteMass(infos[a]), moves_b = !HasInfiniteMass(infos[b]);
    std::uint32_t group = groups.far;
    if (moves_a && moves_b) {
      const auto sa = static_cast<std::uint32_t>(strip_of[a]), sb = static_cast<std::uint32_t>(strip_of[b]);
      if (sa == sb) {
        group = sa;
      } else if (sa + 1 == sb || sb + 1 == sa) {
        group = groups.Edge(std::min(sa, sb));
      }
    } else if (moves_a || moves_b) {
      group = static_cast<std::uint32_t>(strip_of[moves_a ? a : b]);
    }
    (*slot)[i] = group;
  }
  SortByGroup(groups.far + 1, slot, group_ends);
}

}  // namespace engine::detail
