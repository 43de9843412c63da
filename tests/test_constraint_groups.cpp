// ForEachGroup: every unit once, group after group, and a shared group cut where the threads'
// parts cost the same when the units' work is given; ForEachThreadsShare: the same shares.
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

#include "parallel/worker_pool.h"
#include "solver/constraint_groups.h"

namespace {

struct Call {
  std::uint32_t begin, end;
  std::uint64_t started, finished;  ///< ticks of one counter shared by every call
  std::thread::id thread;
};

// Groups of 1000, 600, 50 and 40 units (blocks of four constraints): the first two are shared,
// the third too small to share, the last past the colouring (may share a body).
engine::detail::ContactOrder FourGroups() {
  engine::detail::ContactOrder order;
  order.group_ends = {1000, 1600, 1650, 1690};
  order.parallel_groups = 3;
  return order;
}

std::vector<Call> RunGroups(int threads, std::span<const std::uint8_t> extra_work) {
  engine::detail::WorkerPool pool(threads);
  std::atomic<std::uint64_t> tick{0};
  std::mutex mutex;
  std::vector<Call> calls;
  engine::detail::ForEachGroup(
      pool, FourGroups(),
      [&](std::uint32_t begin, std::uint32_t end) {
        const std::uint64_t started = tick++;
        const std::uint64_t finished = tick++;
        const std::lock_guard<std::mutex> lock(mutex);
        calls.push_back({begin, end, started, finished, std::this_thread::get_id()});
      },
      4, extra_work);
  return calls;
}

std::size_t GroupOf(std::uint32_t unit) {
  const std::vector<std::uint32_t> ends = FourGroups().group_ends;
  return static_cast<std::size_t>(std::upper_bound(ends.begin(), ends.end(), unit) - ends.begin());
}

}  // namespace

TEST_CASE("ForEachGroup visits every unit once, group after group, on 1 to 3 threads", "[parallel][solver]") {
  std::vector<std::uint8_t> work(1690, 0);
  for (std::uint32_t unit = 0; unit < 400; ++unit) work[unit] = 4;  // a heavy start, as a pile's bottom
  for (const bool weighted : {false, true}) {
    for (const int threads : {1, 2, 3}) {
      INFO("threads " << threads << (weighted ? ", weighted" : ""));
      const std::vector<Call> calls = RunGroups(threads, weighted ? std::span<const std::uint8_t>(work) : std::span<const std::uint8_t>());
      std::vector<int> visits(1690, 0);
      for (const Call& c : calls) {
        if (c.begin == c.end) continue;
        // On threads, a call stays within one group (but the unshared tail run on the first);
        // one thread takes everything in one call.
        if (threads > 1 && c.begin < 1600) CHECK(GroupOf(c.begin) == GroupOf(c.end - 1));
        for (std::uint32_t unit = c.begin; unit < c.end; ++unit) ++visits[unit];
      }
      CHECK(std::all_of(visits.begin(), visits.end(), [](int v) { return v == 1; }));
      // Every call on an earlier group ended before any call on a later one began.
      for (const Call& early : calls) {
        for (const Call& late : calls) {
          if (early.begin == early.end || late.begin == late.end) continue;
          if (GroupOf(early.begin) < GroupOf(late.begin)) CHECK(early.finished < late.started);
        }
      }
    }
  }
}

TEST_CASE("ForEachGroup cuts a shared group where the threads' parts cost the same", "[parallel][solver]") {
  std::vector<std::uint8_t> work(1690, 0);
  for (std::uint32_t unit = 0; unit < 400; ++unit) work[unit] = 4;
  const auto cost = [&](std::uint32_t begin, std::uint32_t end, bool weighted) {
    std::uint64_t total = 0;
    for (std::uint32_t unit = begin; unit < end; ++unit) {
      total += weighted ? engine::detail::kUnitWork + work[unit] : 1;
    }
    return total;
  };
  for (const bool weighted : {false, true}) {
    for (const int threads : {2, 3}) {
      INFO("threads " << threads << (weighted ? ", weighted" : ""));
      const std::vector<Call> calls = RunGroups(threads, weighted ? std::span<const std::uint8_t>(work) : std::span<const std::uint8_t>());
      // Group 0 (units 0-999): one part per thread; the heaviest unit costs kUnitWork + 4.
      std::vector<std::uint64_t> parts;
      std::vector<std::thread::id> owners;
      for (const Call& c : calls) {
        if (c.begin >= 1000 || c.begin == c.end) continue;
        parts.push_back(cost(c.begin, c.end, weighted));
        owners.push_back(c.thread);
      }
      REQUIRE(parts.size() == static_cast<std::size_t>(threads));
      std::sort(owners.begin(), owners.end());
      CHECK(std::adjacent_find(owners.begin(), owners.end()) == owners.end());  // one part a thread
      const std::uint64_t total = cost(0, 1000, weighted);
      const std::uint64_t unit_at_most = weighted ? engine::detail::kUnitWork + 4 : 1;
      for (const std::uint64_t part : parts) {
        CHECK(part + unit_at_most >= total / threads);
        CHECK(part <= total / threads + unit_at_most);
      }
    }
  }
}

TEST_CASE("ForEachThreadsShare gives each thread the units ForEachGroup gives it, every unit once",
          "[parallel][solver]") {
  for (const int threads : {1, 2, 3}) {
    CAPTURE(threads);
    // Which thread ForEachGroup (no extra work) hands each unit to, by the calls it makes.
    const std::vector<Call> grouped = RunGroups(threads, {});
    std::vector<std::thread::id> grouped_by(1690);
    for (const Call& call : grouped) {
      for (std::uint32_t unit = call.begin; unit < call.end; ++unit) grouped_by[unit] = call.thread;
    }
    // The same pool's threads, for ForEachThreadsShare (a thread's id stays with its chunk).
    engine::detail::WorkerPool pool(threads);
    std::mutex mutex;
    std::vector<int> visits(1690, 0);
    std::vector<std::thread::id> shared_by(1690);
    engine::detail::ForEachThreadsShare(
        pool, FourGroups(),
        [&](std::uint32_t begin, std::uint32_t end) {
          const std::lock_guard<std::mutex> lock(mutex);
          for (std::uint32_t unit = begin; unit < end; ++unit) {
            ++visits[unit];
            shared_by[unit] = std::this_thread::get_id();
          }
        },
        4);
    CHECK(std::all_of(visits.begin(), visits.end(), [](int v) { return v == 1; }));
    // Threads are told apart by where they start: the first unit of each thread's share in
    // ForEachGroup and here must go to corresponding threads, unit for unit. Map ForEachGroup's
    // thread ids to this pool's through the first units, then compare every unit.
    std::vector<std::pair<std::thread::id, std::thread::id>> map;
    bool consistent = true;
    for (std::uint32_t unit = 0; unit < 1690; ++unit) {
      const auto found =
          std::find_if(map.begin(), map.end(), [&](const auto& m) { return m.first == grouped_by[unit]; });
      if (found == map.end()) {
        map.emplace_back(grouped_by[unit], shared_by[unit]);
      } else {
        consistent = consistent && found->second == shared_by[unit];
      }
    }
    CHECK(consistent);
    CHECK(map.size() == static_cast<std::size_t>(threads));  // every thread had a share
  }
}
