// Greedy colouring with a 64-bit mask of taken colours per body, then a stable counting sort.
#include "solver/contact_order.h"

#include <algorithm>
#include <array>
#include <bit>

#include "parallel/per_thread.h"
#include "parallel/worker_pool.h"
#include "solver/substep_passes.h"

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

void ColourContacts(std::span<const BodyPair> contacts, std::span<const BodyInfo> infos,
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
                   std::vector<std::uint32_t>* group_ends, WorkerPool* pool) {
  // The span of the moving bodies in contact, along `across`: over each thread's part of the
  // contacts, then over the parts (the least and the most are exact, whatever the parts).
  struct Span {
    double lo = 0.0, hi = 0.0;
    bool any = false;
    void Widen(double x) {
      lo = any ? std::min(lo, x) : x;
      hi = any ? std::max(hi, x) : x;
      any = true;
    }
  };
  const std::size_t parts = pool && contacts.size() >= kMinSharedContacts ? pool->Threads() : 1;
  std::vector<PerThread<Span>> spans(parts);
  const auto span_of = [&](std::size_t part) {
    Span span;  // kept apart from the shared list until done: it might alias the states
    const std::size_t end = contacts.size() * (part + 1) / parts;
    for (std::size_t i = contacts.size() * part / parts; i < end; ++i) {
      for (const BodyIndex b : {contacts[i].a, contacts[i].b}) {
        if (!HasInfiniteMass(infos[b])) span.Widen(Dot(states[b].position, across));
      }
    }
    spans[part].value = span;
  };
  if (parts == 1) {
    span_of(0);
  } else {
    pool->RunOnAll([&](int thread) { span_of(static_cast<std::size_t>(thread)); });
  }
  Span all;
  for (const auto& part : spans) {
    if (!part.value.any) continue;
    all.Widen(part.value.lo);
    all.Widen(part.value.hi);
  }
  const double lo = all.lo, hi = all.hi;
  const double scale = hi > lo ? strips / (hi - lo) : 0.0;
  // body_marks[b]: body b's strip (read for the moving bodies of a contact; worked out for every
  // body, fewer than the contacts' ends).
  std::vector<std::uint64_t>& strip_of = *body_marks;
  strip_of.resize(infos.size());
  ForEachIndex(pool, infos.size(), kMinSharedBodies, [&](std::uint32_t b) {
    const double s = (Dot(states[b].position, across) - lo) * scale;
    const auto last = static_cast<std::uint64_t>(strips - 1);
    strip_of[b] = s < strips - 1.0 ? (s > 0.0 ? static_cast<std::uint64_t>(s) : 0) : last;
  });
  const StripGroups groups(strips);
  slot->resize(contacts.size());
  ForEachIndex(pool, contacts.size(), kMinSharedContacts, [&](std::uint32_t i) {
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
  });
  SortByGroup(groups.far + 1, slot, group_ends);
}

}  // namespace engine::detail
