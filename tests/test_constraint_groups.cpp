// ForEachGroup: every unit once, group after group, a shared group in even parts;
// ForEachThreadsShare: the same shares, or learned ones.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

#include "group_calls.h"
#include "parallel/worker_pool.h"
#include "solver/constraint_groups.h"

namespace {

using Call = testing::GroupCall;

// Groups of 1000, 600, 50 and 40 units (blocks of four constraints): the first two are shared,
// the third too small to share, the last past the colouring (may share a body).
engine::detail::ContactOrder FourGroups() {
  engine::detail::ContactOrder order;
  order.group_ends = {1000, 1600, 1650, 1690};
  order.parallel_groups = 3;
  return order;
}

std::vector<Call> RunGroups(int threads) {
  engine::detail::WorkerPool pool(threads);
  testing::GroupCalls calls;
  engine::detail::ForEachGroup(pool, FourGroups(), calls.Pass(), 4);
  return calls.Calls();
}

std::size_t GroupOf(std::uint32_t unit) {
  const std::vector<std::uint32_t> ends = FourGroups().group_ends;
  return static_cast<std::size_t>(std::upper_bound(ends.begin(), ends.end(), unit) - ends.begin());
}

}  // namespace

TEST_CASE("ForEachGroup visits every unit once, group after group, on 1 to 3 threads", "[parallel][solver]") {
  for (const int threads : {1, 2, 3}) {
    INFO("threads " << threads);
    const std::vector<Call> calls = RunGroups(threads);
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
    if (threads == 1) continue;
    // Group 0 (units 0-999): one part per thread, as many units each (to one).
    std::vector<std::uint32_t> sizes;
    for (const Call& c : calls) {
      if (c.begin < 1000 && c.end > c.begin) sizes.push_back(c.end - c.begin);
    }
    REQUIRE(sizes.size() == static_cast<std::size_t>(threads));
    for (const std::uint32_t size : sizes) CHECK(size + 1 >= 1000u / static_cast<std::uint32_t>(threads));
  }
}

TEST_CASE("ForEachThreadsShare gives each thread the units ForEachGroup gives it, every unit once",
          "[parallel][solver]") {
  for (const int threads : {1, 2, 3}) {
    CAPTURE(threads);
    // Which thread ForEachGroup hands each unit to, by the calls it makes.
    const std::vector<Call> grouped = RunGroups(threads);
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

TEST_CASE("ForEachThreadsShare with learned cuts cuts each shared group where they say, every unit once",
          "[parallel][solver]") {
  engine::detail::WorkerPool pool(2);
  engine::detail::BalancedCuts cuts;
  // A call whose second part (units [512, 1024) of 1024) took three times the first's time: the
  // cut moves half way from the middle to where the parts would cost alike, 512 + 512/3 of 1024,
  // so the first thread takes 7/12 of each shared group.
  const std::size_t before[] = {0, 512, 1024};
  const double seconds[] = {1.0, 3.0};
  cuts.Learn(before, seconds);
  const double first_share = (0.5 + (512.0 + 512.0 / 3.0) / 1024.0) / 2.0;
  REQUIRE(first_share == Approx(7.0 / 12.0));
  const std::thread::id caller = std::this_thread::get_id();  // the pool's thread 0
  std::mutex mutex;
  std::vector<int> visits(1690, 0);
  std::vector<std::uint8_t> by_caller(1690, 0);
  engine::detail::ForEachThreadsShare(
      pool, FourGroups(),
      [&](std::uint32_t begin, std::uint32_t end) {
        const bool on_caller = std::this_thread::get_id() == caller;
        {
          const std::lock_guard<std::mutex> lock(mutex);
          for (std::uint32_t unit = begin; unit < end; ++unit) {
            ++visits[unit];
            by_caller[unit] = on_caller ? 1 : 0;
          }
        }
        // The other thread takes far longer: the cuts learn to give the caller more.
        if (!on_caller) std::this_thread::sleep_for(std::chrono::milliseconds(50));
      },
      4, &cuts);
  CHECK(std::all_of(visits.begin(), visits.end(), [](int v) { return v == 1; }));
  // The caller's units: the first 7/12 of each shared group (1000 and 600 units), the share
  // held to 2^-20 below (⌊2^20 · 7/12⌋ = 611 669), and the two groups that go whole to the first
  // thread.
  const auto caller_units = [&](std::uint32_t begin, std::uint32_t end) {
    return static_cast<std::uint32_t>(std::count(by_caller.begin() + begin, by_caller.begin() + end, 1));
  };
  CHECK(caller_units(0, 1000) == 583);  // ⌊1000 · 611 669 / 2^20⌋ = ⌊583.33⌋
  CHECK(std::all_of(by_caller.begin(), by_caller.begin() + 583, [](std::uint8_t c) { return c == 1; }));
  CHECK(caller_units(1000, 1600) == 349);  // ⌊600 · 611 669 / 2^20⌋ = ⌊349.9997⌋
  CHECK(std::all_of(by_caller.begin() + 1000, by_caller.begin() + 1349, [](std::uint8_t c) { return c == 1; }));
  CHECK(caller_units(1600, 1690) == 90);
  // And the call's own times moved the cut further the caller's way.
  CHECK(cuts.Cut(1, 2, 1 << 20) > static_cast<std::size_t>(first_share * (1 << 20)));
}
