// A pass over the contact constraints, group by group, with each large group shared among the
// pool's threads. Internal to the engine.
#pragma once

#include <array>
#include <cassert>
#include <chrono>
#include <cstdint>
#include <span>
#include <utility>

#include "engine/world_def.h"
#include "parallel/balanced_cuts.h"
#include "parallel/spin_barrier.h"
#include "parallel/worker_pool.h"
#include "solver/body_cut.h"
#include "solver/contact_order.h"

namespace engine::detail {

/// Groups smaller than this go to one thread: the threads' meeting between groups (about a
/// microsecond) would cost more than sharing saves.
inline constexpr std::uint32_t kMinSharedGroup = 256;
/// Fewer constraints than this are all solved on one thread: handing each pass out and back
/// costs microseconds, and a pour of 1 000 circles (2 000 contacts) ran 1.26 times slower on
/// two threads than on one when it was shared (bench_threads).
inline constexpr std::uint32_t kMinSharedConstraints = 4096;

/// The stretches a pass over `order`'s groups (not strips) goes through, in order: each group
/// that is shared among the threads (below order.parallel_groups, so it shares no moving body,
/// and of at least kMinSharedGroup constraints), and each run of the other groups between them,
/// which goes whole to the first thread. Calls stretch(begin, end, shared, last) on each.
template <typename Stretch>
void ForEachStretch(const ContactOrder& order, std::uint32_t per_unit, Stretch&& stretch) {
  const std::size_t groups = order.group_ends.size();
  const auto shared = [&](std::size_t g, std::uint32_t begin) {
    return g < order.parallel_groups && std::uint64_t{order.group_ends[g] - begin} * per_unit >= kMinSharedGroup;
  };
  std::uint32_t begin = 0;
  std::size_t g = 0;
  while (g < groups) {
    const bool is_shared = shared(g, begin);
    std::uint32_t end = order.group_ends[g++];
    if (!is_shared) {
      while (g < groups && !shared(g, end)) end = order.group_ends[g++];
    }
    stretch(begin, end, is_shared, g == groups);
    begin = end;
  }
}

/// Thread `thread`'s part of [begin, end) cut into `threads` parts of as many units each.
inline std::pair<std::uint32_t, std::uint32_t> EvenPart(std::uint32_t begin, std::uint32_t end, int thread,
                                                        int threads) {
  const std::uint64_t size = end - begin;
  return {static_cast<std::uint32_t>(begin + size * thread / threads),
          static_cast<std::uint32_t>(begin + size * (thread + 1) / threads)};
}

/// Whether ForEachGroup calls its pass once, over all of `order`'s constraints on the calling
/// thread: one thread, or too few constraints to share.
inline bool GroupsStayOnOneThread(const WorkerPool& pool, const ContactOrder& order, std::uint32_t per_unit = 1) {
  const std::uint32_t total = order.group_ends.empty() ? 0 : order.group_ends.back();
  return pool.Threads() == 1 || std::uint64_t{total} * per_unit < kMinSharedConstraints;
}

/// Calls part(begin, end) on the ranges of units that ForEachGroup gives each thread, on that
/// thread, with no wait between groups: for work on the units that has no order, done by the
/// thread that will next read what it writes (a unit's data then stays in that core's cache).
/// With `cuts`, each shared group is cut where the threads took alike last call instead of in
/// the middle (BalancedCuts, learned from each thread's time in the call); a thread then
/// writes a few units more or less than it will read.
template <typename Part>
void ForEachThreadsShare(WorkerPool& pool, const ContactOrder& order, Part&& part, std::uint32_t per_unit = 1,
                         BalancedCuts* cuts = nullptr) {
  const std::uint32_t total = order.group_ends.empty() ? 0 : order.group_ends.back();
  const int threads = pool.Threads();
  if (GroupsStayOnOneThread(pool, order, per_unit) || order.strips > 0) {
    part(std::uint32_t{0}, total);
    return;
  }
  // With `cuts`: where thread t's part of every shared group begins, as a share of the group
  // (kScale: all of it), and how long each thread took.
  constexpr std::size_t kScale = std::size_t{1} << 20;
  const auto parts = static_cast<std::size_t>(threads);
  std::array<std::size_t, kMaxThreads + 1> at{};
  std::array<double, kMaxThreads> seconds{};
  if (cuts) {
    for (std::size_t t = 0; t <= parts; ++t) at[t] = cuts->Cut(t, parts, kScale);
  }
  pool.RunOnAll([&](int thread) {
    const auto start = std::chrono::steady_clock::now();
    const auto t = static_cast<std::size_t>(thread);
    ForEachStretch(order, per_unit, [&](std::uint32_t begin, std::uint32_t end, bool shared, bool /*last*/) {
      if (shared && cuts) {
        const auto cut = [&](std::size_t k) {
          return static_cast<std::uint32_t>(begin + std::uint64_t{end - begin} * at[k] / kScale);
        };
        part(cut(t), cut(t + 1));
      } else if (shared) {
        const auto [first, past] = EvenPart(begin, end, thread, threads);
        part(first, past);
      } else if (thread == 0) {
        part(begin, end);
      }
    });
    if (cuts) seconds[t] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  });
  if (cuts) cuts->Learn(std::span(at).first(parts + 1), std::span(seconds).first(parts));
}

/// Calls pass(begin, end) on ranges of the constraints [0, order.group_ends.back()) so that
/// every group is done before the next starts. In strip order, each strip goes whole to one
/// thread, side by side, then each even edge, then each odd one, and the rest to the first.
/// Otherwise each shared stretch (ForEachStretch) is cut into one range per thread, and the
/// others go whole to the first thread. Since no two constraints in a shared group touch the same
/// moving body, the arithmetic on each body is that of the constraints in storage order, the
/// same bits with any number of threads.
/// `per_unit`: how many constraints one unit of `order` holds (the wide solver's blocks hold 4).
template <typename Pass>
void ForEachGroup(WorkerPool& pool, const ContactOrder& order, Pass&& pass, std::uint32_t per_unit = 1) {
  const std::uint32_t total = order.group_ends.empty() ? 0 : order.group_ends.back();
  const int threads = pool.Threads();
  if (GroupsStayOnOneThread(pool, order, per_unit)) {
    pass(std::uint32_t{0}, total);
    return;
  }
  if (order.strips > 0) {  // each strip (then edge) whole to one thread, then the rest
    const StripGroups groups(static_cast<int>(order.strips));
    const auto run = [&](std::uint32_t g) { pass(g == 0 ? 0 : order.group_ends[g - 1], order.group_ends[g]); };
    SpinBarrier barrier(threads);
    pool.RunOnAll([&](int thread) {
      const std::uint32_t phases[] = {0, groups.strips, groups.strips + groups.even_edges, groups.far};
      for (int phase = 0; phase < 3; ++phase) {
        for (std::uint32_t g = phases[phase] + thread; g < phases[phase + 1]; g += threads) run(g);
        barrier.Wait();
      }
      if (thread == 0) run(groups.far);
    });
    return;
  }
  SpinBarrier barrier(threads);
  pool.RunOnAll([&](int thread) {
    ForEachStretch(order, per_unit, [&](std::uint32_t begin, std::uint32_t end, bool shared, bool last) {
      if (!shared) {
        if (thread == 0) pass(begin, end);
      } else {
        const auto [first, past] = EvenPart(begin, end, thread, threads);
        pass(first, past);
      }
      if (!last) barrier.Wait();  // the pool's own hand-back ends the last stretch
    });
  });
}

/// As ForEachGroup in a colour order, each group shared as `cut` gives (BodyCut: by the
/// bodies its units move; its groups and threads must be `order`'s and `pool`'s): every group is
/// done before the next starts, and a run of groups that go whole to the first thread goes as one.
template <typename Pass>
void ForEachGroupByBodies(WorkerPool& pool, const ContactOrder& order, const BodyCut& cut, Pass&& pass,
                          std::uint32_t per_unit = 1) {
  const std::uint32_t total = order.group_ends.empty() ? 0 : order.group_ends.back();
  const int threads = pool.Threads();
  if (GroupsStayOnOneThread(pool, order, per_unit)) {
    pass(std::uint32_t{0}, total);
    return;
  }
  assert(order.strips == 0 && cut.Threads() == threads && cut.Groups() == order.group_ends.size());
  SpinBarrier barrier(threads);
  pool.RunOnAll([&](int thread) {
    const std::size_t groups = cut.Groups();
    for (std::size_t g = 0; g < groups;) {
      if (cut.Whole(g)) {
        const std::uint32_t begin = g == 0 ? 0 : order.group_ends[g - 1];
        while (g < groups && cut.Whole(g)) ++g;
        if (thread == 0) pass(begin, order.group_ends[g - 1]);
      } else {
        for (const BodyCut::Range& range : cut.Part(g, thread)) pass(range.begin, range.end);
        ++g;
      }
      if (g < groups) barrier.Wait();  // the pool's own hand-back ends the last group
    }
  });
}

}  // namespace engine::detail
