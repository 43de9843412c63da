// ShockSchedule: shock propagation shared among threads gives the bits of the one-thread pass,
// on a pile whose rows cross the bands' borders, its bodies numbered up the pile or across it;
// each row goes to the band whose share of the bodies holds the body it moves.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstring>
#include <vector>

#include "move_measure.h"
#include "parallel/worker_pool.h"
#include "solver/body_cut.h"
#include "solver/shock_propagation.h"
#include "solver/shock_schedule.h"
#include "solver/substep_passes.h"
#include "solver/substep_constraint.h"

namespace {

using testing::MeasureMoves;
using testing::MeasureMovesIn;

// A pile of `columns` × `rows` unit bodies on a static floor (body 0), each standing on the one
// below and leaning on the one below-right (a diagonal contact, so rows cross from column to
// column and from band to band), all sinking at speeds that differ body to body. Numbered row
// by row (up the pile, as a pour is built) or, `by_columns`, column by column (across it).
struct Pile {
  std::vector<engine::BodyInfo> infos;
  std::vector<engine::BodyState> states;
  std::vector<engine::Vec2> start_positions;
  std::vector<engine::LinearConstraint> constraints;
};

Pile MakePile(int columns, int rows, bool by_columns = false) {
  Pile pile;
  engine::BodyInfo floor;
  floor.is_static = true;
  pile.infos.push_back(floor);
  pile.states.push_back({});
  engine::BodyInfo body;
  body.mass = 1.0;
  body.inv_mass = 1.0;
  const auto id = [&](int c, int r) {
    return static_cast<engine::BodyIndex>(1 + (by_columns ? c * rows + r : r * columns + c));
  };
  for (int k = 0; k < rows * columns; ++k) {  // in id order
    const int r = by_columns ? k % rows : k / columns, c = by_columns ? k / rows : k % columns;
    pile.infos.push_back(body);
    engine::BodyState s;
    s.position = {1.0 * c, 0.5 + 1.0 * r};
    // Sinking, faster in some columns than others, with a little sideways motion.
    s.velocity = {0.01 * ((c * 7 + r * 3) % 5 - 2), -0.1 - 0.05 * ((c * 13 + r * 11) % 7)};
    pile.states.push_back(s);
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

// `planned_before`: the schedule is planned once for other rows first (its scratch kept).
std::vector<engine::BodyState> Propagate(const Pile& pile, int threads, std::size_t* waits,
                                         const Pile* planned_before = nullptr) {
  std::vector<engine::detail::ShockRow> rows;
  engine::detail::ShockScratch scratch;
  engine::detail::BuildShockRows<engine::LinearConstraint>(pile.constraints, pile.infos, {0.0, 1.0}, &scratch,
                                                           &rows);
  engine::detail::WorkerPool pool(threads);
  engine::detail::ShockSchedule schedule;
  if (planned_before) {
    std::vector<engine::detail::ShockRow> other;
    engine::detail::ShockScratch other_scratch;
    engine::detail::BuildShockRows<engine::LinearConstraint>(planned_before->constraints, planned_before->infos,
                                                             {0.0, 1.0}, &other_scratch, &other);
    schedule.Plan(other, planned_before->states.size(), threads);
  }
  schedule.Plan(rows, pile.states.size(), threads);
  *waits = schedule.WaitCount();
  // Each row in the band whose share of the bodies holds the body it moves (the upper one).
  const engine::detail::BodyShares shares(pile.states.size(), threads);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const engine::BodyIndex moved = rows[r].inv_mass_b != 0.0 ? rows[r].b : rows[r].a;
    const int share = shares.Of(moved);
    REQUIRE(schedule.BandOf(r) == static_cast<std::uint32_t>(share));
  }
  std::vector<engine::BodyState> states = pile.states;
  std::vector<engine::Vec2> moved(states.size());  // the pass moves no centre: made once
  MeasureMoves(states, pile.start_positions, moved);
  for (int substep = 0; substep < 4; ++substep) schedule.Run(pool, rows, states, moved, 240.0, 0.005);
  return states;
}

// The waits ShockSchedule must find, by the plain scan over every row: before a row that reads a
// body another band's earlier row wrote, or writes a body another band's earlier row touched,
// one wait on that band's latest such row, unless an earlier wait on that band covers it.
std::size_t WaitsOfEveryRow(const std::vector<engine::detail::ShockRow>& rows, std::size_t body_count, int bands) {
  constexpr std::uint32_t kNone = ~std::uint32_t{0};
  const auto count = static_cast<std::size_t>(bands);
  std::vector<std::uint32_t> band(rows.size());
  std::vector<std::uint64_t> touched(body_count, 0), written(body_count, 0);
  const engine::detail::BodyShares shares(body_count, bands);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const engine::detail::ShockRow& row = rows[r];
    band[r] = static_cast<std::uint32_t>(shares.Of(row.inv_mass_b != 0.0 ? row.b : row.a));
    const std::uint64_t bit = std::uint64_t{1} << band[r];
    touched[row.a] |= bit;
    touched[row.b] |= bit;
    if (row.inv_mass_a != 0.0) written[row.a] |= bit;
    if (row.inv_mass_b != 0.0) written[row.b] |= bit;
  }
  std::vector<std::uint32_t> last_write(body_count, kNone), last_touch(body_count * count, kNone);
  std::vector<std::uint32_t> covered(count * count, kNone);
  std::size_t waits = 0;
  for (std::uint32_t r = 0; r < rows.size(); ++r) {
    const engine::detail::ShockRow& row = rows[r];
    const engine::BodyIndex bodies[2] = {row.a, row.b};
    const bool writes[2] = {row.inv_mass_a != 0.0, row.inv_mass_b != 0.0};
    std::vector<std::uint32_t> need(count, kNone);
    const auto need_row = [&](std::uint32_t other_row) {
      if (other_row == kNone || band[other_row] == band[r]) return;
      std::uint32_t& n = need[band[other_row]];
      if (n == kNone || other_row > n) n = other_row;
    };
    for (int k = 0; k < 2; ++k) {
      const std::uint64_t t = touched[bodies[k]];
      if (written[bodies[k]] == 0 || (t & (t - 1)) == 0) continue;  // one band alone touches it
      need_row(last_write[bodies[k]]);
      if (writes[k]) {
        for (std::size_t other = 0; other < count; ++other) need_row(last_touch[bodies[k] * count + other]);
      }
      last_touch[bodies[k] * count + band[r]] = r;
    }
    for (std::size_t other = 0; other < count; ++other) {
      std::uint32_t& c = covered[band[r] * count + other];
      if (need[other] == kNone || (c != kNone && need[other] <= c)) continue;
      c = need[other];
      ++waits;
    }
    for (int k = 0; k < 2; ++k) {
      if (writes[k]) last_write[bodies[k]] = r;
    }
  }
  return waits;
}

bool SameBits(const std::vector<engine::BodyState>& x, const std::vector<engine::BodyState>& y) {
  return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(engine::BodyState)) == 0;
}

}  // namespace

TEST_CASE("shock propagation shared among threads gives the one-thread bits", "[parallel][solver]") {
  for (const bool by_columns : {false, true}) {
    CAPTURE(by_columns);
    const Pile pile = MakePile(60, 40, by_columns);  // 4 680 rows: past kMinSharedShockRows
    std::size_t waits = 0;
    const std::vector<engine::BodyState> one = Propagate(pile, 1, &waits);
    CHECK(waits == 0);
    // The pass did something: every column sank and was held up.
    CHECK(!SameBits(one, pile.states));
    for (const int threads : {2, 3, 4}) {
      CAPTURE(threads);
      const std::vector<engine::BodyState> shared = Propagate(pile, threads, &waits);
      // Rows cross every border between shares: the bands had to wait for each other.
      CHECK(waits >= static_cast<std::size_t>(threads - 1));
      CHECK(SameBits(shared, one));
    }
  }
}

TEST_CASE("shock bands that wait work out their rows' gaps meanwhile, to the one-thread bits", "[parallel][solver]") {
  // A band waiting for the rows below its own works out the gaps of the rows ahead of it (how
  // fast each pair may close, from the moves alone) and takes them from there. Gaps that differ
  // row to row: separations from 8 mm of overlap (past the slop: those rows never push) to 8 mm
  // apart, and centres moved since the step's start by up to 2 mm.
  Pile pile = MakePile(60, 40);
  for (std::size_t i = 0; i < pile.constraints.size(); ++i) {
    pile.constraints[i].base_separation = 0.002 * static_cast<double>(static_cast<int>(i * 37 % 9) - 4);
  }
  for (std::size_t b = 1; b < pile.start_positions.size(); ++b) {
    pile.start_positions[b].y -= 0.001 * static_cast<double>(static_cast<int>(b * 13 % 5) - 2);
  }
  std::size_t waits = 0;
  const std::vector<engine::BodyState> one = Propagate(pile, 1, &waits);
  // The gaps differ: some rows are past the slop, some may close, some have room to fall.
  std::vector<engine::detail::ShockRow> rows;
  engine::detail::ShockScratch scratch;
  engine::detail::BuildShockRows<engine::LinearConstraint>(pile.constraints, pile.infos, {0.0, 1.0}, &scratch,
                                                           &rows);
  std::vector<engine::Vec2> moved(pile.states.size());
  MeasureMoves(pile.states, pile.start_positions, moved);
  std::size_t dead = 0, room = 0;
  for (const engine::detail::ShockRow& row : rows) {
    const engine::detail::ShockGap gap = engine::detail::GapOf(row, moved, 240.0, 0.005);
    dead += gap.live ? 0 : 1;
    room += gap.live && gap.min_vn < 0.0 ? 1 : 0;
  }
  CHECK(dead > rows.size() / 10);
  CHECK(room > rows.size() / 10);
  for (const int threads : {2, 3, 4}) {
    CAPTURE(threads);
    const std::vector<engine::BodyState> shared = Propagate(pile, threads, &waits);
    CHECK(waits >= static_cast<std::size_t>(threads - 1));
    CHECK(SameBits(shared, one));
  }
}

TEST_CASE("shock propagation's branching and branch-free forms give the same bits", "[solver]") {
  // Every third body rising: rows that push and rows that do not, changing often along them.
  Pile pile = MakePile(30, 20);
  for (std::size_t i = 1; i < pile.states.size(); i += 3) pile.states[i].velocity.y = 0.2;
  std::vector<engine::detail::ShockRow> rows;
  engine::detail::ShockScratch scratch;
  engine::detail::BuildShockRows<engine::LinearConstraint>(pile.constraints, pile.infos, {0.0, 1.0}, &scratch,
                                                           &rows);
  const std::vector<engine::Vec2> moved(pile.states.size());  // no centre has moved since the start
  // The pass by hand, from its definition: a row within the slop that closes faster than its gap
  // allows is stopped there, its held body left alone; and how often pushing changes along them.
  const double inv_h = 240.0, slop = 0.005;
  std::vector<engine::BodyState> by_hand = pile.states;
  std::size_t changes = 0;
  bool last = false;
  for (const engine::detail::ShockRow& row : rows) {
    engine::BodyState& a = by_hand[row.a];
    engine::BodyState& b = by_hand[row.b];
    const double s = row.base_separation + engine::Dot(moved[row.b] - moved[row.a], row.normal);
    const double min_vn = -std::max(s, 0.0) * inv_h;
    const double vn = engine::Dot(b.velocity - a.velocity, row.normal);
    const bool pushed = s >= -slop && vn < min_vn;
    if (pushed) {
      const double impulse = (min_vn - vn) / (row.inv_mass_a + row.inv_mass_b);
      if (row.inv_mass_a != 0.0) a.velocity -= (impulse * row.inv_mass_a) * row.normal;
      if (row.inv_mass_b != 0.0) b.velocity += (impulse * row.inv_mass_b) * row.normal;
    }
    changes += pushed != last ? 1 : 0;
    last = pushed;
  }
  CHECK(5 * changes >= rows.size());  // often enough that the solver would take the branch-free form
  for (const bool branch_free : {false, true}) {
    CAPTURE(branch_free);
    std::vector<engine::BodyState> states = pile.states;
    CHECK(engine::detail::PropagateShock(rows, states, moved, inv_h, slop, branch_free) == changes);
    CHECK(SameBits(states, by_hand));
  }
}

TEST_CASE("shock bands planned again for other rows are planned afresh", "[parallel][solver]") {
  // The plan's scratch is kept between steps: a plan for a smaller pile first leaves nothing
  // behind that the next one reads.
  const Pile pile = MakePile(60, 40);
  const Pile smaller = MakePile(50, 45, true);
  std::size_t waits = 0;
  const std::vector<engine::BodyState> one = Propagate(pile, 1, &waits);
  for (const int threads : {2, 3}) {
    CAPTURE(threads);
    const std::vector<engine::BodyState> shared = Propagate(pile, threads, &waits, &smaller);
    CHECK(waits >= static_cast<std::size_t>(threads - 1));
    CHECK(SameBits(shared, one));
  }
}

TEST_CASE("shock bands move their share of the bodies once no later band touches it, to the bits of moving after",
          "[parallel][solver]") {
  // Run's `after`: each band's thread moves its share of the bodies (and measures their moves)
  // as soon as its band is done and no other band's row will touch that share again. The result
  // must be the bits of the whole pass first and the moves after it; each band's `after` runs
  // once. Gaps that differ row to row (as above), so that the moves measured matter.
  Pile pile = MakePile(60, 40);
  for (std::size_t i = 0; i < pile.constraints.size(); ++i) {
    pile.constraints[i].base_separation = 0.002 * static_cast<double>(static_cast<int>(i * 37 % 9) - 4);
  }
  std::vector<engine::detail::ShockRow> rows;
  engine::detail::ShockScratch scratch;
  engine::detail::BuildShockRows<engine::LinearConstraint>(pile.constraints, pile.infos, {0.0, 1.0}, &scratch,
                                                           &rows);
  const double h = 1.0 / 240.0;
  const auto move = [&](std::vector<engine::BodyState>& states, std::vector<engine::Vec2>& moved, std::uint32_t begin,
                        std::uint32_t end) {
    for (std::uint32_t i = begin; i < end; ++i) {
      if (pile.infos[i].is_static) continue;
      states[i].position += states[i].velocity * h;
    }
    MeasureMovesIn(states, pile.start_positions, moved, begin, end);
  };
  const auto n = static_cast<std::uint32_t>(pile.states.size());
  // One thread: the pass, then every body moved.
  std::vector<engine::BodyState> one = pile.states;
  std::vector<engine::Vec2> one_moved(n);
  MeasureMoves(one, pile.start_positions, one_moved);
  for (int substep = 0; substep < 4; ++substep) {
    engine::detail::PropagateShock(rows, one, one_moved, 240.0, 0.005, true);
    move(one, one_moved, 0, n);
  }
  for (const int threads : {2, 3, 4}) {
    CAPTURE(threads);
    engine::detail::WorkerPool pool(threads);
    engine::detail::ShockSchedule schedule;
    schedule.Plan(rows, n, threads);
    REQUIRE(schedule.SharedAmong(pool));
    std::vector<engine::BodyState> states = pile.states;
    std::vector<engine::Vec2> moved(n);
    MeasureMoves(states, pile.start_positions, moved);
    std::vector<int> calls(static_cast<std::size_t>(threads), 0);
    auto after = [&](int band) {
      ++calls[static_cast<std::size_t>(band)];
      move(states, moved, engine::detail::ShareBegin(n, threads, band), engine::detail::ShareBegin(n, threads, band + 1));
    };
    for (int substep = 0; substep < 4; ++substep) {
      schedule.Run(pool, rows, states, moved, 240.0, 0.005, engine::detail::JobRef(after));
    }
    CHECK(std::count(calls.begin(), calls.end(), 4) == threads);
    CHECK(SameBits(states, one));
    CHECK(std::memcmp(moved.data(), one_moved.data(), n * sizeof(engine::Vec2)) == 0);
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

TEST_CASE("shock bands wait where a scan of every row says, found from the rows that cross shares", "[solver]") {
  // The schedule looks only at the bodies of rows whose two bodies lie in two shares (the
  // crossings): no other body can be touched by two bands. The plain scan counts the same waits.
  for (const bool by_columns : {false, true}) {
    CAPTURE(by_columns);
    const Pile pile = MakePile(60, 40, by_columns);
    std::vector<engine::detail::ShockRow> rows;
    engine::detail::ShockScratch scratch;
    engine::detail::BuildShockRows<engine::LinearConstraint>(pile.constraints, pile.infos, {0.0, 1.0}, &scratch,
                                                             &rows);
    for (const int threads : {2, 3, 4, 7}) {
      CAPTURE(threads);
      engine::detail::ShockSchedule schedule;
      schedule.Plan(rows, pile.states.size(), threads);
      const std::size_t expected = WaitsOfEveryRow(rows, pile.states.size(), threads);
      CHECK(expected >= static_cast<std::size_t>(threads - 1));
      CHECK(schedule.WaitCount() == expected);
    }
  }
}
