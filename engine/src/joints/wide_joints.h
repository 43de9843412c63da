// Revolute joints laid out for the wide solver: blocks of four joints' point rows, each field
// four doubles side by side, in colour order. Internal to the engine.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "joints/joint_table.h"
#include "parallel/worker_pool.h"
#include "solver/contact_order.h"
#include "solver/wide_constraints.h"

namespace engine::detail {

struct JointWork;

/// Fewer joints that fit the lanes than this stay with the others in slot order. Colour order
/// changes the order of the arithmetic, and a chain converges far better link after link: the
/// heavy chain 1000:1 and every asset scene keep their slot order and their bits. The turning
/// strips' threshold (SubstepSolver::kMinStripContacts), for the same reason.
inline constexpr std::size_t kMinWideJoints = 256;

/// Four revolute joints' point rows, field by field. A lane past its colour's end is padding:
/// zero masses, arms and effective mass on body 0, so it computes nothing that is written.
struct alignas(32) JointBlock {
  std::int32_t a[kBlockLanes];
  std::int32_t b[kBlockLanes];
  double inv_mass_a[kBlockLanes];
  double inv_mass_b[kBlockLanes];
  double inv_inertia_a[kBlockLanes];
  double inv_inertia_b[kBlockLanes];
  // JointWork's frames where the bodies are now (LoadFrames): the arms from each centre of
  // mass to the anchor, the anchors' separation b − a, the drift the rows aim to cancel.
  double arm_a_x[kBlockLanes];
  double arm_a_y[kBlockLanes];
  double arm_b_x[kBlockLanes];
  double arm_b_y[kBlockLanes];
  double separation_x[kBlockLanes];
  double separation_y[kBlockLanes];
  double drift_x[kBlockLanes];
  double drift_y[kBlockLanes];
  // The point's 2×2 effective mass K and 1 / det K, once per frame instead of once per pass.
  double k11[kBlockLanes];
  double k12[kBlockLanes];
  double k22[kBlockLanes];
  double inv_det[kBlockLanes];
  double impulse_x[kBlockLanes];  ///< the accumulated point impulse (JointImpulses::point)
  double impulse_y[kBlockLanes];
};

/// The joints that fit the lanes (Fits) in blocks. Each is given the lowest colour that no
/// joint before it (in slot order, so in id order) has on either of its moving bodies; a colour's
/// joints share no moving body, so solving four side by side gives the bits of solving them one
/// after another, and threads may share a colour (ForEachGroup). Joints past the last colour
/// (kSharedColour) may share a body: they go one to a block, one after another. The greedy
/// colouring Box2D v3 uses for its wide solver (Catto, "Solver2D", 2024).
struct WideJoints {
  static constexpr std::uint32_t kNotWide = ~0u;

  std::vector<JointBlock> blocks;
  ContactOrder order;                  ///< the colours' ends, in blocks
  std::vector<std::uint32_t> lane_of;  ///< per JointWork: block · 4 + lane, or kNotWide
  std::vector<std::uint32_t> work_of;  ///< per block lane: its JointWork, or kNotWide (padding)

  /// A revolute joint between two bodies with neither motor nor limits: its only rows are the
  /// point's. (The angle rows, springs and other joints stay one at a time.)
  static bool Fits(const JointWork& w, const Joint& j);
  /// Colours the works that fit and lays them out, with their impulses from `table`. Returns
  /// how many went into lanes (none when fewer than kMinWideJoints fit).
  std::size_t Pack(std::span<const JointWork> work, const JointTable& table, std::size_t body_count);
  /// Copies each lane's arms and separation from its JointWork and works out its K (shared
  /// among `pool`'s threads block by block).
  void LoadFrames(std::span<const JointWork> work, WorkerPool& pool);
  /// Copies each lane's drift from its JointWork.
  void LoadDrift(std::span<const JointWork> work, WorkerPool& pool);
  /// The accumulated impulses back to the joints (the warm start of the next step, snapshots).
  void UnpackImpulses(std::span<const JointWork> work, JointTable* table) const;
  void Clear();
};

}  // namespace engine::detail
