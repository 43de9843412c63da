// AnyImpact: the impact pass's first look, shared among threads, says whether ResolveImpacts would
// bounce any pair; when it says no, ResolveImpacts changes nothing (no velocity, no lag).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstring>
#include <span>
#include <vector>

#include "engine/world_def.h"
#include "parallel/worker_pool.h"
#include "solver/impact.h"
#include "solver/substep_constraint.h"
#include "solver/substep_passes.h"

namespace {

// A row of `count` unit balls on a static floor (body 0), each resting on it (touching, closing
// at 1 cm/s: far below the restitution threshold), with contact `striking` (if any) closing at
// 3 m/s instead, which the pass must bounce.
struct Row {
  std::vector<engine::BodyState> states;
  std::vector<engine::Vec2> accelerations;
  std::vector<engine::LinearConstraint> constraints;
  std::vector<engine::Contact> contacts;
  std::vector<std::uint32_t> slot;
};

constexpr std::size_t kNone = static_cast<std::size_t>(-1);

Row MakeRow(std::size_t count, std::size_t striking) {
  Row row;
  row.states.push_back({});  // the floor
  row.accelerations.push_back({});
  for (std::size_t i = 0; i < count; ++i) {
    engine::BodyState s;
    s.position = {2.0 * static_cast<double>(i), 0.5};
    s.velocity = {0.0, i == striking ? -3.0 : -0.01};
    row.states.push_back(s);
    row.accelerations.push_back({0.0, -9.81});
    engine::LinearConstraint c{};
    c.a = 0;
    c.b = static_cast<engine::BodyIndex>(i + 1);
    c.normal = {0.0, 1.0};
    c.inv_mass_a = 0.0;
    c.inv_mass_b = 1.0;
    c.normal_mass = 1.0;
    c.base_separation = 0.0;
    row.constraints.push_back(c);
    engine::Contact contact{};
    contact.a = c.a;
    contact.b = c.b;
    contact.manifold.normal = c.normal;  // one point, where the ball touches the floor
    contact.manifold.point_count = 1;
    contact.manifold.points[0].point = {s.position.x, 0.0};
    contact.manifold.points[0].depth = 0.0;
    contact.restitution = 0.5;
    contact.friction = 0.3;
    row.contacts.push_back(contact);
  }
  // The constraints stored in reverse, as a colour order may store them: contact i at slot[i].
  std::reverse(row.constraints.begin(), row.constraints.end());
  for (std::size_t i = 0; i < count; ++i) row.slot.push_back(static_cast<std::uint32_t>(count - 1 - i));
  return row;
}

// The settings the solver steps with (its automatic substeps filled in).
engine::WorldDef Settings() {
  engine::WorldDef def;
  def.substeps = 4;
  return def;
}

// Each contact's restitution, as the solver writes them apart for AnyImpact.
std::vector<double> RestitutionsOf(const Row& row) {
  std::vector<double> restitutions;
  for (const engine::Contact& c : row.contacts) restitutions.push_back(c.restitution);
  return restitutions;
}

bool AnyImpactOn(const Row& row, int threads, std::span<const double> restitutions) {
  engine::detail::WorkerPool pool(threads);
  return engine::detail::AnyImpact<engine::LinearConstraint>(row.constraints, row.slot, row.contacts, restitutions,
                                                             row.states, row.accelerations, Settings(), &pool);
}

}  // namespace

TEST_CASE("AnyImpact says whether the impact pass bounces a pair, on any number of threads", "[solver][parallel]") {
  const std::size_t count = 5000;  // past kMinSharedContacts: shared among the threads
  // No pair striking; one in the first contact, the middle, the last (the last thread's part).
  for (const std::size_t striking : {kNone, std::size_t{0}, count / 2, count - 1}) {
    CAPTURE(striking);
    const Row row = MakeRow(count, striking);
    const bool expected = striking != kNone;
    // The restitutions are read from the list written apart, not the contacts: none bounces
    // with every one 0 there (nothing bounces without restitution).
    const std::vector<double> restitutions = RestitutionsOf(row);
    CHECK(engine::detail::AnyImpact<engine::LinearConstraint>(row.constraints, row.slot, row.contacts, restitutions,
                                                              row.states, row.accelerations, Settings()) == expected);
    const std::vector<double> none(count, 0.0);
    for (const int threads : {1, 2, 3}) {
      CAPTURE(threads);
      CHECK(AnyImpactOn(row, threads, restitutions) == expected);
      CHECK_FALSE(AnyImpactOn(row, threads, none));
    }
    // And the pass itself: with no pair striking it changes nothing and leaves no lags; with one,
    // it bounces that ball upwards and gives its contact a lag.
    std::vector<engine::BodyState> states = row.states;
    std::vector<engine::LinearConstraint> constraints = row.constraints;
    std::vector<double> lags = {1.0};  // left from an earlier step: cleared
    engine::detail::ResolveImpacts<engine::LinearConstraint>(constraints, row.slot, row.contacts, states,
                                                                     row.accelerations, Settings(), &lags);
    if (!expected) {
      CHECK(lags.empty());
      CHECK(std::memcmp(states.data(), row.states.data(), states.size() * sizeof(engine::BodyState)) == 0);
    } else {
      REQUIRE(lags.size() == count);
      CHECK(lags[striking] != 0.0);
      CHECK(states[striking + 1].velocity.y > 0.0);
      for (std::size_t i = 0; i < count; ++i) {
        if (i != striking) CHECK(states[i + 1].velocity.y == row.states[i + 1].velocity.y);
      }
    }
  }
}

TEST_CASE("the impact look taken as the constraints are prepared answers as AnyImpact", "[solver][parallel]") {
  // PrepareSubstepConstraints with an ImpactLook: each contact looked at as its constraint is
  // filled, on 1-3 threads, for balls that cannot turn (LinearConstraint) and that can
  // (SubstepConstraint, the contact's point turned into anchors).
  const std::size_t count = 5000;
  for (const bool turning : {false, true}) {
    CAPTURE(turning);
    std::vector<engine::BodyInfo> infos(count + 1);
    infos[0].is_static = true;
    for (std::size_t i = 1; i <= count; ++i) {
      infos[i].mass = infos[i].inv_mass = 1.0;
      infos[i].inertia = infos[i].inv_inertia = turning ? 2.5 : 0.0;
    }
    for (const std::size_t striking : {kNone, std::size_t{0}, count - 1}) {
      CAPTURE(striking);
      const Row row = MakeRow(count, striking);
      for (const int threads : {1, 2, 3}) {
        CAPTURE(threads);
        engine::detail::WorkerPool pool(threads);
        engine::detail::ImpactLook look{row.accelerations, Settings()};
        bool any = false;
        if (turning) {
          std::vector<engine::SubstepConstraint> constraints;
          engine::detail::PrepareSubstepConstraints(row.contacts, row.slot, infos, row.states, &constraints, &pool,
                                                    &look);
          REQUIRE(constraints[row.slot[0]].angular);
          any = engine::detail::AnyImpact<engine::SubstepConstraint>(constraints, row.slot, row.contacts,
                                                                     RestitutionsOf(row), row.states,
                                                                     row.accelerations, Settings());
        } else {
          std::vector<engine::LinearConstraint> constraints;
          engine::detail::PrepareSubstepConstraints(row.contacts, row.slot, infos, row.states, &constraints, &pool,
                                                    &look);
          any = engine::detail::AnyImpact<engine::LinearConstraint>(constraints, row.slot, row.contacts,
                                                                    RestitutionsOf(row), row.states,
                                                                    row.accelerations, Settings());
        }
        CHECK(any == (striking != kNone));
        CHECK(look.found.load() == any);
      }
    }
  }
}
