// Deep piles at the default settings: resting circles overlap less than a centimetre, however
// tall the rain that made the pile, with or without rotation (issue 20), and PileHeightInBodies
// counts bodies.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <vector>

#include "bench/stress_scenes.h"
#include "engine/world.h"
#include "solver/substep_solver.h"
#include "world_builders.h"

namespace {

// The deepest overlap between two circles of radius `r`, from their centres alone.
double MaxCircleOverlap(const engine::World& world, double r) {
  std::vector<engine::Vec2> centres;
  for (const engine::BodyId id : world.BodyIds()) {
    if (world.Info(id).shape.type == engine::ShapeType::kCircle) centres.push_back(world.State(id).position);
  }
  std::sort(centres.begin(), centres.end(), [](engine::Vec2 p, engine::Vec2 q) { return p.x < q.x; });
  double worst = 0.0;
  for (std::size_t i = 0; i < centres.size(); ++i) {
    for (std::size_t j = i + 1; j < centres.size() && centres[j].x - centres[i].x < 2 * r; ++j) {
      worst = std::max(worst, 2 * r - engine::Length(centres[j] - centres[i]));
    }
  }
  return worst;
}

// A column of 14 × 215 circles of radius 0.25 m (124 m, thirteen times as tall as wide) falls
// into a box as wide as it, and the pile, about 140 circles deep, is left 12 s to settle: it must
// be at rest, with no two circles overlapping by 1 cm.
void CheckTallRainSettles(const engine::WorldDef& def) {
  engine::World world(def);
  const double r = 0.25, width = 9.2;
  stress::AddContainer(world, width, 160.0);
  stress::AddCirclePour(world, 3000, r, width - 0.1);
  for (int s = 0; s < 12 * 60; ++s) world.Step();
  double fastest = 0.0;
  for (const engine::BodyId id : world.BodyIds()) fastest = std::max(fastest, engine::Length(world.State(id).velocity));
  const double overlap = MaxCircleOverlap(world, r);
  INFO("fastest " << fastest << " m/s, overlap " << overlap << " m");
  CHECK(fastest < 0.05);  // at rest
  CHECK(overlap < 0.01);
}

}  // namespace

TEST_CASE("a tall rain of 3 000 circles settles with under 1 cm of overlap", "[solver][stability]") {
  // With one velocity pass per substep (before SubstepSolver::kDeepPile) it ended with 2.8 cm of
  // overlap, 77 pairs over 1 cm.
  CheckTallRainSettles(engine::WorldDef{});  // the defaults: axis-aligned, 4 substeps
}

TEST_CASE("a tall rain of 3 000 turning circles settles with under 1 cm of overlap", "[solver][stability][rotation]") {
  // With rotation on (8 substeps of 4 passes). A bounce's lag used to move a body after the step
  // into the pile under it: the pile pressed 44 cm deep into itself in the first seconds (circles
  // 50 cm across) and still held 20 cm of overlap at 12 s. Lags that would close another contact
  // past the slop are left out (SubstepSolver::DropClosingLags).
  engine::WorldDef def;
  def.rotation = true;
  CheckTallRainSettles(def);
}

TEST_CASE("PileHeightInBodies: a column of n touching circles is n - 1 bodies tall", "[solver]") {
  // Circles of radius 0.5 stacked centre over centre, 1 m apart: the span of their centres is
  // n − 1 m and the mean spacing 1 m.
  engine::World world{engine::WorldDef{}};
  world.CreateBody(testing::Floor());
  for (int i = 0; i < 10; ++i) world.CreateBody(testing::Circle({0.0, 0.5 + i}, 0.5));
  world.Step();
  std::vector<engine::BodyInfo> infos;
  std::vector<engine::BodyState> states;
  for (const engine::BodyId id : world.BodyIds()) {
    infos.push_back(world.Info(id));
    states.push_back(world.State(id));
  }
  const double height = engine::detail::PileHeightInBodies(world.Contacts(), infos, states, {0.0, 1.0});
  CHECK(height == Approx(9.0).epsilon(0.01));
  // Sideways, the column has no extent.
  CHECK(engine::detail::PileHeightInBodies(world.Contacts(), infos, states, {1.0, 0.0}) == Approx(0.0).margin(1e-6));
}
