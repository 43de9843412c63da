// BodyCut: each group's units go to the thread whose share of the bodies holds the body they
// move, a unit for unit match with that rule; ForEachGroupByBodies: every unit once, on the
// thread the cut gives it, group after group.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <map>
#include <thread>
#include <vector>

#include "group_calls.h"
#include "parallel/worker_pool.h"
#include "solver/body_cut.h"
#include "solver/constraint_groups.h"

namespace {

using engine::BodyIndex;
using engine::kNoBody;
using engine::detail::BodyCut;
using engine::detail::ContactOrder;

constexpr std::size_t kBodies = 1000;

// Units in the order a colour order's blocks have: within a group by (a, b), so a run of units
// whose a is fixed body 0 (their leads, b, across all the bodies), then units whose a moves
// (lead a), then fixed body 600's (leads b above it), then moving ones again.
// Group 0: 700 units of those four runs; group 1: 5 units (too few to share); group 2: 400
// moving units; group 3: 30 units past the colouring (they may share a body).
struct Units {
  ContactOrder order;
  std::vector<BodyIndex> lead_body, lead_fixed;
};

Units MakeUnits() {
  Units u;
  const auto add = [&](BodyIndex body, BodyIndex fixed) {
    u.lead_body.push_back(body);
    u.lead_fixed.push_back(fixed);
  };
  for (BodyIndex b = 1; b < kBodies; b += 10) add(b, 0);           // 100: a = fixed body 0
  for (BodyIndex a = 1; a < 600; a += 2) add(a, kNoBody);          // 300: a moves
  for (BodyIndex b = 601; b < kBodies; b += 4) add(b, 600);        // 100: a = fixed body 600
  for (BodyIndex a = 601; a < 1000; a += 2) add(a, kNoBody);       // 200: a moves
  u.order.group_ends.push_back(static_cast<std::uint32_t>(u.lead_body.size()));
  for (BodyIndex a = 100; a < 105; ++a) add(a, kNoBody);
  u.order.group_ends.push_back(static_cast<std::uint32_t>(u.lead_body.size()));
  for (BodyIndex a = 0; a < 800; a += 2) add(a + 1, kNoBody);
  u.order.group_ends.push_back(static_cast<std::uint32_t>(u.lead_body.size()));
  for (BodyIndex a = 0; a < 30; ++a) add(900 - a, kNoBody);
  u.order.group_ends.push_back(static_cast<std::uint32_t>(u.lead_body.size()));
  u.order.parallel_groups = 3;
  return u;
}

// The thread whose share of the bodies holds `body`, as ForEachIndex cuts them.
int ShareOf(BodyIndex body, int threads) {
  for (int t = threads - 1; t > 0; --t) {
    if (body >= kBodies * static_cast<std::size_t>(t) / static_cast<std::size_t>(threads)) return t;
  }
  return 0;
}

}  // namespace

TEST_CASE("BodyCut gives each unit to the thread whose share holds the body it moves", "[parallel][solver]") {
  const Units units = MakeUnits();
  for (const int threads : {1, 2, 3}) {
    CAPTURE(threads);
    BodyCut cut;
    cut.Cut(units.order, units.lead_body, units.lead_fixed, kBodies, threads);
    REQUIRE(cut.Groups() == 4);
    CHECK_FALSE(cut.Whole(0));
    CHECK(cut.Whole(1));  // too few units
    CHECK_FALSE(cut.Whole(2));
    CHECK(cut.Whole(3));  // may share a body
    std::uint32_t begin = 0;
    for (std::size_t g = 0; g < 4; ++g) {
      CAPTURE(g);
      const std::uint32_t end = units.order.group_ends[g];
      std::vector<int> owner(end - begin, -1);
      for (int t = 0; t < threads; ++t) {
        for (const BodyCut::Range& range : cut.Part(g, t)) {
          REQUIRE(range.begin >= begin);
          REQUIRE(range.end <= end);
          REQUIRE(range.begin < range.end);
          for (std::uint32_t unit = range.begin; unit < range.end; ++unit) {
            REQUIRE(owner[unit - begin] == -1);  // once
            owner[unit - begin] = t;
          }
        }
      }
      for (std::uint32_t unit = begin; unit < end; ++unit) {
        CAPTURE(unit);
        const int expected = cut.Whole(g) ? 0 : ShareOf(units.lead_body[unit], threads);
        CHECK(owner[unit - begin] == expected);
      }
      // One range a thread for each run of one kind of lead (group 0 has four runs).
      if (!cut.Whole(g)) {
        for (int t = 0; t < threads; ++t) CHECK(cut.Part(g, t).size() <= (g == 0 ? 4u : 1u));
      }
      begin = end;
    }
  }
}

TEST_CASE("ForEachGroupByBodies runs each unit once on the thread the cut gives it, group after group",
          "[parallel][solver]") {
  Units units = MakeUnits();
  // Blocks of four constraints: 1 135 units hold enough constraints (4 540) to be shared.
  for (const int threads : {1, 2, 3}) {
    CAPTURE(threads);
    engine::detail::WorkerPool pool(threads);
    BodyCut cut;
    cut.Cut(units.order, units.lead_body, units.lead_fixed, kBodies, threads);
    testing::GroupCalls recorder;
    engine::detail::ForEachGroupByBodies(pool, units.order, cut, recorder.Pass(), 4);
    const std::vector<testing::GroupCall>& calls = recorder.Calls();
    const std::uint32_t total = units.order.group_ends.back();
    std::vector<int> visits(total, 0);
    for (const testing::GroupCall& c : calls) {
      for (std::uint32_t unit = c.begin; unit < c.end; ++unit) ++visits[unit];
    }
    CHECK(std::all_of(visits.begin(), visits.end(), [](int v) { return v == 1; }));
    if (threads == 1) {
      CHECK(calls.size() == 1);  // all in one call
      continue;
    }
    const auto group_of = [&](std::uint32_t unit) {
      const auto& ends = units.order.group_ends;
      return static_cast<std::size_t>(std::upper_bound(ends.begin(), ends.end(), unit) - ends.begin());
    };
    // Each call is one of the cut's ranges (or the whole groups 1 and 3 on the calling thread),
    // and each of the cut's threads is one thread of the pool.
    std::map<int, std::thread::id> thread_of;
    for (const testing::GroupCall& c : calls) {
      const std::size_t g = group_of(c.begin);
      if (cut.Whole(g)) {
        CHECK(c.thread == std::this_thread::get_id());
        CHECK(group_of(c.end - 1) == g);  // groups 1 and 3 are not next to each other
        continue;
      }
      int owner = -1;
      for (int t = 0; t < threads; ++t) {
        for (const BodyCut::Range& range : cut.Part(g, t)) {
          if (range.begin == c.begin && range.end == c.end) owner = t;
        }
      }
      REQUIRE(owner >= 0);
      if (thread_of.count(owner) == 0) thread_of[owner] = c.thread;
      CHECK(thread_of[owner] == c.thread);
    }
    CHECK(thread_of[0] == std::this_thread::get_id());
    for (const auto& [t, id] : thread_of) {
      for (const auto& [u, other] : thread_of) CHECK((t == u) == (id == other));
    }
    // Every call on an earlier group ended before any call on a later one began.
    for (const testing::GroupCall& early : calls) {
      for (const testing::GroupCall& late : calls) {
        if (group_of(early.begin) < group_of(late.begin)) CHECK(early.finished < late.started);
      }
    }
  }
}

TEST_CASE("BodyShares names the thread whose part of the bodies ForEachIndex runs them on", "[parallel][solver]") {
  for (const int threads : {1, 2, 3, 5}) {
    engine::detail::WorkerPool pool(threads);
    for (const std::size_t bodies : {std::size_t{1}, std::size_t{7}, std::size_t{10}, std::size_t{4003}}) {
      CAPTURE(threads, bodies);
      std::vector<std::thread::id> ran_on(bodies);
      engine::detail::ForEachIndex(&pool, bodies, 0, [&](std::uint32_t i) { ran_on[i] = std::this_thread::get_id(); });
      std::map<int, std::thread::id> thread_of_share;
      const engine::detail::BodyShares shares(bodies, threads);
      for (std::size_t body = 0; body < bodies; ++body) {
        const int share = shares.Of(static_cast<BodyIndex>(body));
        REQUIRE(share >= 0);
        REQUIRE(share < threads);
        // Shares in body order, each [ShareBegin(t), ShareBegin(t + 1)).
        CHECK(engine::detail::ShareBegin(bodies, threads, share) <= body);
        CHECK(body < engine::detail::ShareBegin(bodies, threads, share + 1));
        if (thread_of_share.count(share) == 0) thread_of_share[share] = ran_on[body];
        CHECK(thread_of_share[share] == ran_on[body]);
      }
      for (const auto& [t, id] : thread_of_share) {
        for (const auto& [u, other] : thread_of_share) CHECK((t == u) == (id == other));
      }
      if (thread_of_share.count(0)) CHECK(thread_of_share[0] == std::this_thread::get_id());
    }
  }
}
