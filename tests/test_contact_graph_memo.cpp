// ContactGraphMemo: a step's contact graph is "the same" only where the pairs and every body's
// fixedness are; and a world that keeps its colour order and shock levels from step to step
// steps as a world restored from it (whose solver finds them afresh) does, also when a fixed
// body takes a moving one's slot and so leaves the pairs as they were.
#include <catch2/catch.hpp>

#include <vector>

#include "bench/stress_scenes.h"
#include "engine/world.h"
#include "solver/contact_graph_memo.h"

namespace {

using engine::BodyInfo;
using engine::BodyPair;
using engine::detail::ContactGraphMemo;

std::vector<BodyInfo> Infos(std::size_t count) {
  std::vector<BodyInfo> infos(count);
  infos[0].is_static = true;  // the ground
  return infos;
}

}  // namespace

TEST_CASE("the contact graph memo answers same only for the same pairs and fixed bodies", "[solver]") {
  ContactGraphMemo memo;
  std::vector<BodyInfo> infos = Infos(4);
  std::vector<BodyPair> pairs = {{0, 1}, {1, 2}, {2, 3}};
  // New pairs answer false twice: the first call remembers them, the second the fixed bodies.
  const auto new_pairs_kept_from_the_third_call = [&] {
    CHECK_FALSE(memo.Same(pairs, infos));
    CHECK_FALSE(memo.Same(pairs, infos));
    CHECK(memo.Same(pairs, infos));
  };
  new_pairs_kept_from_the_third_call();  // nothing remembered yet
  infos[2].inv_mass = 0.25;  // not what the graph is made of
  CHECK(memo.Same(pairs, infos));

  pairs[1] = {1, 3};
  new_pairs_kept_from_the_third_call();
  pairs.pop_back();
  new_pairs_kept_from_the_third_call();

  infos[3].is_kinematic = true;  // the same pairs, a body fixed: once false, then kept
  CHECK_FALSE(memo.Same(pairs, infos));
  CHECK(memo.Same(pairs, infos));
  infos[3].is_kinematic = false;
  infos[3].is_static = true;  // fixed either way: the same graph
  CHECK(memo.Same(pairs, infos));

  infos.push_back(BodyInfo{});  // a body more, touching nothing
  CHECK_FALSE(memo.Same(pairs, infos));
  CHECK(memo.Same(pairs, infos));

  memo.Forget();
  new_pairs_kept_from_the_third_call();
}

TEST_CASE("a pile that keeps its contacts steps as a world restored from it, a fixed body swapped in too",
          "[solver]") {
  engine::WorldDef def;
  def.sleeping = false;  // the pyramid keeps its contacts every step
  for (const int threads : {1, 2}) {
    INFO("threads " << threads);
    def.threads = threads;
    def.adapt_threads = false;  // the shared paths, even on a busy machine
    engine::World kept(def);
    stress::AddPyramid(kept, 8);
    for (int i = 0; i < 60; ++i) kept.Step();
    // A world restored from it finds its first step's order and levels afresh.
    const auto steps_as_restored = [&](int steps) {
      engine::World fresh(def);
      REQUIRE(fresh.RestoreSnapshot(kept.TakeSnapshot()));
      for (int i = 0; i < steps; ++i) {
        kept.Step();
        fresh.Step();
      }
      CHECK(kept.StateHash() == fresh.StateHash());
      CHECK_FALSE(kept.Fault().has_value());
    };
    steps_as_restored(30);
    // The top box, the last made, goes; a fixed box of its size takes its slot where it stood:
    // the same pairs, one body fixed that moved.
    const engine::BodyId top = kept.BodyIds().back();
    const engine::BodyDef fixed = stress::Ground(kept.State(top).position, {1, 1});
    kept.DestroyBody(top);
    REQUIRE(kept.CreateBody(fixed).index == top.index);
    steps_as_restored(60);
  }
}
