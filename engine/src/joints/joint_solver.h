// The joints' passes, run inside either contact solver: rigid rows solved with the contacts
// (warm started, Gauss-Seidel), errors pushed out through the contacts' push velocities (a split
// impulse: it never adds energy), springs as one implicit-or-symplectic impulse per substep.
// Internal to the engine; docs/joints.md explains the choices.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "engine/body.h"
#include "engine/world_def.h"
#include "joints/joint_direct.h"
#include "joints/joint_table.h"
#include "joints/wide_joints.h"
#include "parallel/worker_pool.h"
#include "solver/substep_passes.h"
#include "solver/wide_passes.h"

namespace engine::detail {

/// The fraction of a joint's remaining error pushed out per push pass. Equality rows have no
/// slop and nothing to keep quiet, so they take more than the contacts' per-substep share.
inline constexpr double kJointPushFraction = 0.5;

/// A spring whose ω·h is at most this is integrated symplectically (explicit in position, so
/// its energy neither drains nor grows: an undamped 1 Hz spring keeps its amplitude); stiffer,
/// implicitly (stable at any stiffness, with some numerical damping). docs/joints.md.
inline constexpr double kExplicitSpringLimit = 0.5;

/// Fewer joints than this have their frames and drifts worked out on one thread: handing the
/// work out and back costs microseconds.
inline constexpr std::uint32_t kMinParallelJoints = 2048;

/// One acting joint in the current substep: its bodies' inverse masses and where its frames are.
struct JointWork {
  std::uint32_t slot;
  JointType type;
  BodyIndex a, b;           ///< a: kNoBody for a target joint
  double ma, mb, ia, ib;    ///< inverse masses and inertias (0 for static, kinematic, no turning)
  // The joint's frames on its bodies (Joint's), here so the per-substep passes read one array.
  Vec2 local_a, local_b, local_axis;
  double reference_angle;
  Vec2 ra, rb;              ///< from each centre of mass to the anchor, world axes
  Vec2 separation;          ///< anchor_b − anchor_a
  double angle;             ///< angle_b − angle_a − reference
  Vec2 axis;                ///< prismatic: the unit axis, world
  double push_lower, push_upper;  ///< the limits' push impulses this push pass (≥ 0)
  /// What the substep's motion adds to each row's error beyond its linear part J·v·h (the arms
  /// turning, the anchors passing each other): the rows aim to cancel it, so a body swinging on
  /// a joint ends each substep on its circle instead of drifting out and being pulled back,
  /// which drained a pendulum's energy (docs/joints.md, "Curvature").
  Vec2 drift_point;         ///< revolute, weld: the separation's; prismatic: x across the axis
  double drift_axis;        ///< prismatic: along the axis; distance: of the length
};

/// The 2×2 effective mass of a point shared by two bodies: K = (mA + mB)·I + iA·[rA]ᵀ[rA] + ….
struct Mat22 {
  double k11, k12, k22;
};
Mat22 PointMass(const JointWork& w);

class JointSolver {
 public:
  /// Per step: the acting joints with a moving body, in slot order. False when there are none.
  /// Where bodies turn and at least kMinWideJoints fit the lanes (WideJoints::Fits), those go in
  /// colour order, solved in SIMD lanes as wide as `def.substep_features.lanes` allows (the
  /// same bits at every width) and shared among `pool`'s threads; the others stay in slot order
  /// after them.
  bool Prepare(JointTable* table, std::span<const BodyState> states, std::span<const BodyInfo> infos,
               std::span<const std::uint8_t> moving, const WorldDef& def, WorkerPool& pool);
  /// Per (sub)step of length h, after the free motion: the frames where the bodies are now, the
  /// springs' impulses, then the warm start. `aim_at_drift`: the rows aim to cancel the drift of
  /// the substep's curved motion (PredictDrift); that is a correction of order h², for small
  /// steps only: over a whole 1/60 s step it made a whipping chain blow up.
  void Begin(std::span<BodyState> states, double h, bool aim_at_drift);
  /// One Gauss-Seidel pass over the rigid rows (run before each contact pass).
  void Solve(std::span<BodyState> states, double inv_h);
  /// After the passes: each small island's equality rows made exact (JointDirect).
  void SolveDirect(std::span<BodyState> states, double inv_h) { SolveDirect(states, nullptr, inv_h); }
  /// After the bodies moved: `passes` Gauss-Seidel passes that push the joints' errors out
  /// (kJointPushFraction of each per pass) through the push velocities.
  void PushOut(std::span<const BodyState> states, PushVelocities push, double inv_h, int passes);
  /// After the step's last push-out: the impulses the lanes accumulated back to the joints.
  void End();
  /// Marks both bodies of every solved joint (the integrators move those by h·v).
  void MarkBodies(std::vector<std::uint8_t>* pushed) const;
  /// Per body: 1 if a joint solved this step holds it.
  std::span<const std::uint8_t> Joined() const { return joined_; }

 private:
  void UpdateFrames(std::span<const BodyState> states);
  void PrepareDirect(std::span<const BodyInfo> infos);
  /// The velocities (push null; rate = 1/h) or the push velocities (rate: the push-out's) of
  /// each direct island, solved.
  void SolveDirect(std::span<BodyState> states, PushVelocities* push, double rate);
  /// Each row's drift (JointWork::drift_*) over a (sub)step of h at the current velocities.
  void PredictDrift(std::span<BodyState> states, double h);
  BodyState& StateA(const JointWork& w, std::span<BodyState> states);
  /// Where work `i`'s accumulated point impulse lives now: its joint's, or its lane's.
  std::pair<double*, double*> PointImpulse(std::uint32_t i);
  /// Calls pass(blocks, count) over the joint lanes, colour by colour, shared among the threads.
  template <typename Pass>
  void ForEachJointBlock(Pass&& pass);

  JointTable* table_ = nullptr;
  std::vector<JointWork> work_;
  double h_ = 0.0;
  JointDirect direct_;
  std::vector<std::uint8_t> joined_;
  std::vector<BodyIndex> joined_bodies_;  ///< the bodies joined_ marks, in index order
  std::vector<Rot> rotations_;            ///< per joined body: its rotation (UpdateFrames)
  WideJoints wide_;
  const WidePasses* wide_passes_ = nullptr;  ///< null: every joint one at a time
  const WidePasses* rotation_lanes_ = nullptr;  ///< the joined bodies' rotations (UpdateFrames)
  std::vector<std::uint32_t> scalar_works_;  ///< the works not in lanes, in slot order
  WorkerPool* pool_ = nullptr;
  BodyState ground_;  ///< what a target joint's missing body A reads and (with zero mass) writes
};

}  // namespace engine::detail
