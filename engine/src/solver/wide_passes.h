// The wide solver's passes over blocks of axis-aligned contacts (WideConstraints), compiled for
// each width of SIMD lanes and chosen when the step runs. Internal to the engine.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/body.h"
#include "joints/wide_joints.h"
#include "solver/wide_constraints.h"

namespace engine::detail {

/// A run of turning blocks (WideTurningConstraints) and their second points.
struct TurningRun {
  TurningBlock* blocks;
  TurningSecondLanes* seconds;
  std::size_t count;
};

/// Blocks [first, first + count) of a colour order (`wide`), colour by colour: each colour's part
/// cut in two halves worked on side by side, twin(one, two), as no two of its blocks share a
/// moving body; a group past the colours (its blocks may share one) or a single block goes
/// through pass(first, count). Where the processor has AVX-512, a Twin is one 512-bit vector:
/// half the instructions of the two blocks one after the other (wide_twin.inl).
template <typename TwinPass, typename Pass>
void ColourHalves(WideTurningConstraints& wide, std::uint32_t first, std::size_t count, TwinPass&& twin,
                  Pass&& pass) {
  const std::span<const std::uint32_t> ends = wide.order.group_ends;
  const std::uint32_t end = first + static_cast<std::uint32_t>(count);
  // The first group that ends past `first`.
  auto g = static_cast<std::size_t>(std::upper_bound(ends.begin(), ends.end(), first) - ends.begin());
  for (std::uint32_t begin = first; begin < end; ++g) {
    const std::uint32_t stop = std::min(ends[g], end);
    const std::size_t n = stop - begin;
    if (g < wide.order.parallel_groups && n >= 2) {
      const std::size_t half = n / 2;
      twin(TurningRun{wide.blocks.data() + begin, wide.second_points.data() + begin, half},
           TurningRun{wide.blocks.data() + begin + half, wide.second_points.data() + begin + half, n - half});
    } else {
      pass(begin, n);
    }
    begin = stop;
  }
}

/// One width's passes. Each does, lane by lane, exactly the arithmetic of its one-at-a-time
/// counterpart in substep_passes.cpp (WarmStartAll, SolveContacts, PushOut for LinearConstraint
/// and for angular SubstepConstraints) or joint_solver.cpp (a revolute joint's point),
/// so every width gives the same bits: lane-wise IEEE operations round as scalar ones do, and
/// the blocks of a colour touch different moving bodies. Raw pointers, not spans: the AVX2
/// passes live in a file compiled for AVX2, which must not emit any inline function that other
/// files could link to.
struct WidePasses {
  int lanes;  ///< 1, 2 (SSE2) or 4 (AVX2)
  void (*warm_start)(LinearBlock* blocks, std::size_t count, BodyState* states);
  // `moved`: each body's move since the step's start (MeasureMoves), made from the positions now.
  void (*solve)(LinearBlock* blocks, std::size_t count, BodyState* states, const Vec2* moved, double inv_h);
  void (*push_out)(LinearBlock* blocks, std::size_t count, const Vec2* moved, Vec2* push, double push_out_rate,
                   double max_push_out_speed, double linear_slop);
  // The same for turning contacts (angular SubstepConstraints), `seconds` the blocks' second
  // points (WideTurningConstraints::second_points, from the same block on), `turned` each body's
  // rotation since the step's start (null where no body's turn moves its points: the anchors
  // stay fixed); `block_solve` as SubstepPlan's. `first_pass`: the substep's first velocity pass,
  // which works out each point's least normal speed from the moves (TurningPointLanes::
  // min_normal_speed); the later ones read it, and need no `moved` or `turned`.
  void (*turning_warm_start)(TurningBlock* blocks, TurningSecondLanes* seconds, std::size_t count, BodyState* states);
  void (*turning_solve)(TurningBlock* blocks, TurningSecondLanes* seconds, std::size_t count, BodyState* states,
                        const Vec2* moved, const Rot* turned, double inv_h, bool block_solve, bool first_pass);
  // turning_warm_start and turning_solve over two runs that share no moving body (the even and
  // the odd strips, or a colour's two halves), worked on side by side (wide_twin.inl): the bits of
  // one run after the other.
  void (*turning_warm_start_twin)(TurningRun one, TurningRun two, BodyState* states);
  void (*turning_solve_twin)(TurningRun one, TurningRun two, BodyState* states, const Vec2* moved, const Rot* turned,
                             double inv_h, bool block_solve, bool first_pass);
  void (*turning_push_out)(TurningBlock* blocks, TurningSecondLanes* seconds, std::size_t count, const Vec2* moved,
                           const Rot* turned, Vec2* push, double* push_angular, double push_out_rate,
                           double max_push_out_speed, double linear_slop);
  // turning_push_out over two runs that share no moving body, side by side.
  void (*turning_push_out_twin)(TurningRun one, TurningRun two, const Vec2* moved, const Rot* turned, Vec2* push,
                                double* push_angular, double push_out_rate, double max_push_out_speed,
                                double linear_slop);
  // Revolute joints' point rows (JointSolver's warm start, Solve and PushOut for them).
  void (*joint_warm_start)(JointBlock* blocks, std::size_t count, BodyState* states);
  void (*joint_solve)(JointBlock* blocks, std::size_t count, BodyState* states, double inv_h);
  void (*joint_push_out)(JointBlock* blocks, std::size_t count, Vec2* push, double* push_angular, double rate);
  // Each listed body's rotation: rotations[bodies[k]] = MakeRot(angles[bodies[k] · stride]), with
  // ComputeCosSin's bits, for k < count (wide_cos_sin.inl).
  void (*rotations)(const double* angles, std::size_t stride, const BodyIndex* bodies, std::size_t count,
                    Rot* rotations);
};

/// The widest lanes this processor runs: 4 with AVX2, 2 on any other x86-64, 1 elsewhere.
int WidestLanes();

/// The passes for `lanes` (1, 2 or 4), or for the widest this processor has when it lacks those
/// or `lanes` is 0.
const WidePasses& WidePassesFor(int lanes);

// Each width's passes, defined in its own file.
const WidePasses& WidePasses1();
const WidePasses& WidePasses2();  ///< x86-64 only (BALLBOX_WIDE_X86)
const WidePasses& WidePasses4();  ///< x86-64 only; call only where the processor has AVX2
/// WidePasses4 built with AVX-512VL's 32 registers: the same bits. x86-64 only; call only where
/// the processor has AVX-512F and AVX-512VL (HasEvexRegisters).
const WidePasses& WidePasses4Evex();
/// Whether this processor runs WidePasses4Evex (false off x86-64).
bool HasEvexRegisters();
/// Every build of the passes this processor runs, narrowest first: 1 lane, 2 and 4 where it has
/// them, and WidePasses4Evex after WidePasses4 where it has those (WidePassesFor hands out the
/// last of each width).
std::vector<const WidePasses*> RunnableWidePasses();

}  // namespace engine::detail
