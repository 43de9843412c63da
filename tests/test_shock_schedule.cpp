// ShockSchedule: shock propagation shared among threads gives the bits of the one-thread pass,
// on a pile whose rows cross the bands' borders.
#include <catch2/catch.hpp>
#include <cstring>
#include <vector>

#include "parallel/worker_pool.h"
#include "solver/shock_propagation.h"
#include "solver/shock_schedule.h"
#include "solver/substep_constraint.h"

namespace {

// A pile of `columns` × `rows` unit bodies on a static floor (body 0), each standing on the one
// below and leaning on the one below-right (a diagonal contact, so rows cross from column to
// column and from band to band), all sinking at speeds that differ body to body.
struct Pile {
  std::vector<engine::BodyInfo> infos;
  std::vector<engine::BodyState> states;
  std::vector<engine::Vec2> start_positions;
  std::vector<engine::LinearConstraint> constraints;
};

Pile MakePile(int columns, int rows) {
  Pile pile;
  engine::BodyInfo floor;
  floor.is_static = true;
  pile.infos.push_back(floor);
  pile.states.push_back({});
  engine::BodyInfo body;
  body.mass = 1.0;
  body.inv_mass = 1.0;
  const auto id = [&](int c, int r) { return static_cast<engine::BodyIndex>(1 + r * columns + c); };
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < columns; ++c) {
      pile.infos.push_back(body);
      engine::BodyState s;
      s.position = {1.0 * c, 0.5 + 1.0 * r};
      // Sinking, faster in some columns than others, with a little sideways motion.
      s.velocity = {0.01 * ((c * 7 + r * 3) % 5 - 2), -0.1 - 0.05 * ((c * 13 + r * 11) % 7)};
      pile.states.push_back(s);
    }
  }
  for (const engine::BodyState& s : pile.states) pile.start_positions.push_back(s.position);
  const auto contact = [&](engine::BodyIndex a, engine::BodyIndex b, engine::Vec2 normal) {
    engine::LinearConstraint c{};
    c.a = a;
    c.b = b;
    c.normal = normal;
    c.inv_mass_a = pile.infos[a].inv_mass;
    c.inv_mass_b = pile.infos[b].inv_mass;
    c.base_separation = 0.0;
    pile.constraints.push_back(c);
  };
  const double d = 0.7071067811865476;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < columns; ++c) {
      contact(r == 0 ? 0 : id(c, r - 1), id(c, r), {0.0, 1.0});
      if (r > 0 && c + 1 < columns) contact(id(c + 1, r - 1), id(c, r), {-d, d});
    }
  }
  return pile;
}

// `planned_at`: where the schedule was planned before (the pile moved by it), as in a scene
// that moves between steps; its bins then start from that span.
std::vector<engine::BodyState> Propagate(const Pile& pile, int threads, std::size_t* waits,
                                         const engine::Vec2* planned_at = nullptr) {
  std::vector<engine::detail::ShockRow> rows;
  engine::detail::ShockScratch scratch;
  engine::detail::BuildShockRows<engine::LinearConstraint>(pile.constraints, pile.infos, {0.0, 1.0}, &scratch,
                                                           &rows);
  engine::detail::WorkerPool pool(threads);
  engine::detail::ShockSchedule schedule;
  if (planned_at) {
    std::vector<engine::Vec2> moved = pile.start_positions;
    for (engine::Vec2& p : moved) p += *planned_at;
    schedule.Plan(rows, moved, pile.states.size(), threads);
  }
  schedule.Plan(rows, pile.start_positions, pile.states.size(), threads);
  *waits = schedule.WaitCount();
  std::vector<engine::BodyState> states = pile.states;
  for (int substep = 0; substep < 4; ++substep) {
    schedule.Run(pool, rows, states, pile.start_positions, 240.0, 0.005);
  }
  return states;
}

bool SameBits(const std::vector<engine::BodyState>& x, const std::vector<engine::BodyState>& y) {
  return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(engine::BodyState)) == 0;
}

}  // namespace

TEST_CASE("shock propagation shared among threads gives the one-thread bits", "[parallel][solver]") {
  const Pile pile = MakePile(60, 40);  // 4 680 rows: past kMinSharedShockRows
  std::size_t waits = 0;
  const std::vector<engine::BodyState> one = Propagate(pile, 1, &waits);
  CHECK(waits == 0);
  // The pass did something: every column sank and was held up.
  CHECK(!SameBits(one, pile.states));
  for (const int threads : {2, 3, 4}) {
    CAPTURE(threads);
    const std::vector<engine::BodyState> shared = Propagate(pile, threads, &waits);
    // The diagonal rows cross every border at every level: the bands had to wait for each other.
    CHECK(waits >= static_cast<std::size_t>(threads - 1));
    CHECK(SameBits(shared, one));
  }
}

TEST_CASE("shock bands planned again where the pile moved far, or a little, are shared the same",
          "[parallel][solver]") {
  // The bands' bins start from the span the last call's rows had: rows far outside it are binned
  // again over their own, so the bands still share the pile out and wait at its borders.
  const Pile pile = MakePile(60, 40);
  std::size_t waits = 0;
  const std::vector<engine::BodyState> one = Propagate(pile, 1, &waits);
  for (const engine::Vec2 moved : {engine::Vec2{1000.0, 0.0}, engine::Vec2{-1000.0, 5.0}, engine::Vec2{0.3, 0.0}}) {
    for (const int threads : {2, 3}) {
      CAPTURE(threads, moved.x);
      const std::vector<engine::BodyState> shared = Propagate(pile, threads, &waits, &moved);
      CHECK(waits >= static_cast<std::size_t>(threads - 1));
      CHECK(SameBits(shared, one));
    }
  }
}

TEST_CASE("a pile held by shock propagation stops sinking onto its floor", "[solver]") {
  // The independent expectation: every body rests on the floor through its column, so after the
  // pass no supporting contact approaches (vn >= 0 along every vertical row, base separation 0).
  const Pile pile = MakePile(60, 40);
  std::size_t waits = 0;
  const std::vector<engine::BodyState> states = Propagate(pile, 2, &waits);
  for (const engine::LinearConstraint& c : pile.constraints) {
    if (c.normal.x != 0.0) continue;
    const double vn = (states[c.b].velocity.y - states[c.a].velocity.y);
    CHECK(vn >= -1e-12);
  }
}

TEST_CASE("shock rows written and sorted on threads are one thread's rows", "[parallel][solver]") {
  const Pile pile = MakePile(60, 40);  // 4 680 constraints: past kMinSharedContacts
  std::vector<engine::detail::ShockRow> one;
  engine::detail::ShockScratch scratch;
  engine::detail::BuildShockRows<engine::LinearConstraint>(pile.constraints, pile.infos, {0.0, 1.0}, &scratch, &one);
  REQUIRE(one.size() > 4096);
  for (const int threads : {1, 2, 3}) {
    CAPTURE(threads);
    engine::detail::WorkerPool pool(threads);
    engine::detail::ShockScratch shared_scratch;
    engine::detail::BuildShockLevels<engine::LinearConstraint>(pile.constraints, pile.infos, &shared_scratch);
    engine::detail::WriteShockRows<engine::LinearConstraint>(pile.constraints, {0.0, 1.0}, &shared_scratch, &pool);
    std::vector<engine::detail::ShockRow> shared;
    engine::detail::SortShockRows(&shared_scratch, &shared, &pool);  // in runs, whichever thread takes one
    REQUIRE(shared.size() == one.size());
    CHECK(std::memcmp(shared.data(), one.data(), one.size() * sizeof(engine::detail::ShockRow)) == 0);
  }
}
