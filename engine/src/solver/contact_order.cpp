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

// How finely StripContacts counts the contacts along the strips' direction to cut them.
constexpr int kStripBinsPerStrip = 64;

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

namespace {

// The strip of each bin, cut where the strips hold about as much of `weights` (one a bin) each,
// a strip never more than one past its neighbour's.
std::vector<std::uint8_t> CutStrips(std::span<const double> weights, int strips) {
  double total = 0.0;
  for (const double w : weights) total += w;
  std::vector<std::uint8_t> strip_of_bin(weights.size());
  double before = 0.0;  // the weight of the bins below
  int strip = 0;
  for (std::size_t bin = 0; bin < weights.size(); ++bin) {
    // The strip where the bin's middle falls, at most one past the last bin's.
    const int at = total > 0.0 ? static_cast<int>((before + 0.5 * weights[bin]) / total * strips)
                               : static_cast<int>(bin) / kStripBinsPerStrip;
    strip = std::min({std::max(strip, at), strip + 1, strips - 1});
    strip_of_bin[bin] = static_cast<std::uint8_t>(strip);
    before += weights[bin];
  }
  return strip_of_bin;
}

// The strip of each bin (bin_of: a body's bin of `bins` along the strips' direction), cut where
// the strips hold about as many contacts each: strips of equal width left three lanes in five
// busy in a pyramid of base 40, whose outer strips hold few contacts. First cut by the contact
// ends of moving bodies each bin holds; but a narrow strip loses more of its contacts to the
// edges than a wide one, so the ends are then weighed by how many of their strip's ends
// belong to contacts inside it, and cut again. Counted over runs of the contacts and then
// summed, in integers: the same cut with any number of threads.
template <typename BinOf>
std::vector<std::uint8_t> StripOfBin(std::span<const Contact> contacts, std::span<const BodyInfo> infos,
                                     std::span<const BodyState> states, const BinOf& bin_of, int bins, int strips,
                                     WorkerPool* pool) {
  // Counted in runs of the contacts (ForEachRun), each run into a row of its own, then summed.
  const auto n = static_cast<std::uint32_t>(contacts.size());
  const std::uint32_t run = RunLength(pool, n, kMinSharedContacts);
  const std::size_t runs = (n + run - 1) / run;
  const auto width = static_cast<std::size_t>(bins);
  std::vector<std::uint32_t> counts(std::max<std::size_t>(runs, 1) * width, 0);
  ForEachRun(pool, n, kMinSharedContacts, run, [&](std::uint32_t begin, std::uint32_t end) {
    std::uint32_t* count = counts.data() + std::size_t{begin / run} * width;
    for (std::uint32_t i = begin; i < end; ++i) {
      for (const BodyIndex b : {contacts[i].a, contacts[i].b}) {
        if (!HasInfiniteMass(infos[b])) ++count[bin_of(states[b])];
      }
    }
  });
  std::vector<double> weights(width);
  for (std::size_t bin = 0; bin < width; ++bin) {
    for (std::size_t r = 1; r < runs; ++r) counts[bin] += counts[r * width + bin];
    weights[bin] = counts[bin];
  }
  const std::vector<std::uint8_t> first_cut = CutStrips(weights, strips);
  // Each strip's ends, and those of them in contacts inside it: [strip][0] and [strip][1].
  const auto per_run = static_cast<std::size_t>(strips) * 2;
  std::vector<std::uint64_t> inside(std::max<std::size_t>(runs, 1) * per_run, 0);
  ForEachRun(pool, n, kMinSharedContacts, run, [&](std::uint32_t begin, std::uint32_t end) {
    std::uint64_t* row = inside.data() + std::size_t{begin / run} * per_run;
    for (std::uint32_t i = begin; i < end; ++i) {
      const BodyIndex a = contacts[i].a, b = contacts[i].b;
      const bool moves_a = !HasInfiniteMass(infos[a]), moves_b = !HasInfiniteMass(infos[b]);
      const int sa = moves_a ? first_cut[static_cast<std::size_t>(bin_of(states[a]))] : -1;
      const int sb = moves_b ? first_cut[static_cast<std::size_t>(bin_of(states[b]))] : -1;
      const bool whole = !moves_a || !moves_b || sa == sb;
      for (const int strip : {sa, sb}) {
        if (strip < 0) continue;
        row[2 * strip] += 1;
        row[2 * strip + 1] += whole ? 1 : 0;
      }
    }
  });
  for (std::size_t k = 0; k < per_run; ++k) {
    for (std::size_t r = 1; r < runs; ++r) inside[k] += inside[r * per_run + k];
  }
  for (std::size_t bin = 0; bin < width; ++bin) {
    const std::size_t strip = first_cut[bin];
    const std::uint64_t ends = inside[2 * strip], kept = inside[2 * strip + 1];
    if (ends > 0) weights[bin] *= static_cast<double>(kept) / static_cast<double>(ends);
  }
  return CutStrips(weights, strips);
}

}  // namespace

void StripContacts(std::span<const Contact> contacts, std::span<const BodyInfo> infos,
                   std::span<const BodyState> states, Vec2 across, int strips,
                   std::vector<std::uint64_t>* body_marks, std::vector<std::uint32_t>* slot,
                   std::vector<std::uint32_t>* group_ends, WorkerPool* pool) {
  // The span of the moving bodies in contact, along `across`: over runs of the contacts
  // (ForEachRun), each into a row of its own, then over the rows (the least and the most are
  // exact, whatever the runs).
  struct Span {
    double lo = 0.0, hi = 0.0;
    bool any = false;
    void Widen(double x) {
      lo = any ? std::min(lo, x) : x;
      hi = any ? std::max(hi, x) : x;
      any = true;
    }
  };
  const auto n = static_cast<std::uint32_t>(contacts.size());
  const std::uint32_t run = RunLength(pool, n, kMinSharedContacts);
  std::vector<PerThread<Span>> spans((n + run - 1) / run);
  ForEachRun(pool, n, kMinSharedContacts, run, [&](std::uint32_t begin, std::uint32_t end) {
    Span span;  // kept apart from the shared rows until done: it might alias the states
    for (std::uint32_t i = begin; i < end; ++i) {
      for (const BodyIndex b : {contacts[i].a, contacts[i].b}) {
        if (!HasInfiniteMass(infos[b])) span.Widen(Dot(states[b].position, across));
      }
    }
    spans[begin / run].value = span;
  });
  Span all;
  for (const auto& row : spans) {
    if (!row.value.any) continue;
    all.Widen(row.value.lo);
    all.Widen(row.value.hi);
  }
  const double lo = all.lo, hi = all.hi;
  // Each body's strip (body_marks[b]; worked out for every body, fewer than the contacts' ends),
  // from the bin its centre falls in along `across`.
  const int bins = strips * kStripBinsPerStrip;
  const double scale = hi > lo ? bins / (hi - lo) : 0.0;
  const auto bin_of = [lo, scale, bins, across](const BodyState& state) {
    const double s = (Dot(state.position, across) - lo) * scale;
    return s < bins - 1.0 ? (s > 0.0 ? static_cast<int>(s) : 0) : bins - 1;
  };
  const std::vector<std::uint8_t> strip_of_bin = StripOfBin(contacts, infos, states, bin_of, bins, strips, pool);
  std::vector<std::uint64_t>& strip_of = *body_marks;
  strip_of.resize(infos.size());
  ForEachIndex(pool, infos.size(), kMinSharedBodies, [&](std::uint32_t b) {
    strip_of[b] = strip_of_bin[static_cast<std::size_t>(bin_of(states[b]))];
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
