// A substep's push-out move carried into the next free step (FreeStep's `carried`) gives the
// bits of moving by the push first (MoveByPush) and then taking the free step, whichever forces
// act, on one thread or two.
#include <catch2/catch.hpp>
#include <cstring>
#include <vector>

#include "forces/force_model.h"
#include "integrate.h"
#include "parallel/worker_pool.h"
#include "solver/substep_passes.h"

namespace {

// Bodies enough that both passes share them among two threads (past 2048), every tenth static.
struct Bodies {
  std::vector<engine::BodyInfo> infos;
  std::vector<engine::BodyState> states;
  std::vector<std::uint8_t> moving;
  std::vector<engine::Vec2> push;
  std::vector<double> angular_push;
};

Bodies MakeBodies(std::size_t count) {
  Bodies b;
  for (std::size_t i = 0; i < count; ++i) {
    engine::BodyInfo info;
    const bool fixed = i % 10 == 0;
    info.is_static = fixed;
    info.mass = fixed ? 0.0 : 1.0 + 0.01 * static_cast<double>(i % 7);
    info.inv_mass = fixed ? 0.0 : 1.0 / info.mass;
    info.linear_damping = i % 3 == 0 ? 0.5 : 0.0;
    b.infos.push_back(info);
    engine::BodyState s;
    const double k = static_cast<double>(i);
    s.position = {0.37 * k, 1.0 + 0.11 * static_cast<double>(i % 13)};
    s.velocity = fixed ? engine::Vec2{} : engine::Vec2{0.3 - 0.01 * static_cast<double>(i % 61), -0.7};
    s.angle = 0.001 * k;
    s.angular_velocity = fixed ? 0.0 : 0.2 * static_cast<double>(i % 5);
    b.states.push_back(s);
    b.moving.push_back(fixed ? engine::detail::kResting : engine::detail::kAwake);
    // Overlapping bodies get pushed; others not.
    b.push.push_back(fixed || i % 4 == 0 ? engine::Vec2{} : engine::Vec2{0.05 * static_cast<double>(i % 9), 0.1});
    b.angular_push.push_back(fixed ? 0.0 : 0.02 * static_cast<double>(i % 3));
  }
  return b;
}

}  // namespace

TEST_CASE("a push carried into the next free step moves bodies as a push-out move before it", "[solver][parallel]") {
  using engine::Integrator;
  const double h = 1.0 / 240.0;
  for (const Integrator integrator : {Integrator::kSemiImplicitEuler, Integrator::kExplicitEuler,
                                      Integrator::kVelocityVerlet}) {
    for (const bool drag : {false, true}) {  // drag: forces beyond gravity, the free step's general path
      for (const bool rotation : {false, true}) {
        for (const int threads : {1, 2}) {
          INFO("integrator " << static_cast<int>(integrator) << ", drag " << drag << ", rotation " << rotation
                             << ", threads " << threads);
          engine::WorldDef def;
          def.rotation = rotation;
          const Bodies start = MakeBodies(3000);
          const engine::detail::ForceModel forces{.def = def,
                                                  .infos = start.infos,
                                                  .springs = {},
                                                  .moving = start.moving,
                                                  .applied_forces = {},
                                                  .applied_torques = {},
                                                  .rotation = rotation,
                                                  .damping = drag};
          REQUIRE(forces.BeyondGravity() == drag);
          engine::detail::WorkerPool pool(threads);

          Bodies first = start;  // MoveByPush, then FreeStep
          engine::detail::FreeMotion first_motion;
          engine::detail::MoveByPush(first.states, {first.push, first.angular_push}, rotation, h, &pool);
          engine::detail::FreeStep(integrator, forces, first.states, h, &first_motion, &pool);

          Bodies carried = start;  // FreeStep with the push carried into it
          engine::detail::FreeMotion carried_motion;
          const engine::detail::PushVelocities push{carried.push, carried.angular_push};
          engine::detail::FreeStep(integrator, forces, carried.states, h, &carried_motion, &pool, &push);

          REQUIRE(std::memcmp(first.states.data(), carried.states.data(),
                              first.states.size() * sizeof(engine::BodyState)) == 0);
          REQUIRE(first_motion.drift == carried_motion.drift);
          REQUIRE(first_motion.velocity == carried_motion.velocity);
          for (std::size_t i = 0; i < start.states.size(); ++i) {
            // Moved by h·push exactly (free steps leave positions alone), pushes spent.
            REQUIRE(carried.states[i].position == start.states[i].position + start.push[i] * h);
            REQUIRE(carried.states[i].angle ==
                    (rotation ? start.states[i].angle + start.angular_push[i] * h : start.states[i].angle));
            REQUIRE(carried.push[i] == engine::Vec2{});
            REQUIRE(carried.angular_push[i] == 0.0);
          }
        }
      }
    }
  }
}
