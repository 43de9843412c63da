// The wide solver's passes over blocks of axis-aligned contacts (WideConstraints), compiled for
// each width of SIMD lanes and chosen when the step runs. Internal to the engine.
#pragma once

#include <cstddef>
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
  // the odd strips), worked on side by side (wide_twin.inl): the bits of one run after the other.
  void (*turning_warm_start_twin)(TurningRun one, TurningRun two, BodyState* states);
  void (*turning_solve_twin)(TurningRun one, TurningRun two, BodyState* states, const Vec2* moved, const Rot* turned,
                             double inv_h, bool block_solve, bool first_pass);
  void (*turning_push_out)(TurningBlock* blocks, TurningSecondLanes* seconds, std::size_t count, const Vec2* moved,
                           const Rot* turned, Vec2* push, double* push_angular, double push_out_rate,
                           double max_push_out_speed, double linear_slop);
  // Revolute joints' point rows (JointSolver's warm start, Solve and PushOut for them).
  void (*joint_warm_start)(JointBlock* blocks, std::size_t count, BodyState* states);
  void (*joint_solve)(JointBlock* blocks, std::size_t count, BodyState* states, double inv_h);
  void (*joint_push_out)(JointBlock* blocks, std::size_t count, Vec2* push, double* push_angular, double rate);
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
