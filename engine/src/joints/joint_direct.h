// Direct solve of the joints' rigid rows, island by island: a heavy body on a chain of light
// links needs more Gauss-Seidel passes than a step can afford (a 50 kg weight on ten 50 g links
// sank 20 cm in them), so after the passes each small island's equality rows are made exact by
// one solve of K·Δλ = −residual, K = J·M⁻¹·Jᵀ. Internal to the engine.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "engine/body.h"
#include "joints/joint_table.h"
#include "union_find.h"

namespace engine::detail {

struct JointWork;

/// Islands with more rows than this stay with Gauss-Seidel alone: the factor is dense (a chain
/// of 40 links has 80 rows; a 100 × 100 grid of joints, 20 000).
inline constexpr int kJointDirectMaxRows = 96;

/// One equality row: velocity Dot(d, v_b − v_a) + arm_b·ω_b − arm_a·ω_a.
struct JointRow {
  std::uint32_t work;       ///< the joint's JointWork
  Vec2 d;
  double arm_a, arm_b;
  double error;             ///< the row's position error now (for the push-out)
  double drift;             ///< JointWork's drift for the row
  double* impulse;          ///< the joint's accumulated impulse for this row
};

/// The rows of the islands solved directly this step, and the scratch of the solves.
struct JointDirect {
  struct Island {
    std::uint32_t first_row, rows;
  };
  std::vector<Island> islands;
  std::vector<std::uint32_t> island_works;  ///< the joints, grouped by island
  std::vector<std::uint32_t> island_starts; ///< per island: into island_works (one past the end last)
  std::vector<JointRow> rows;
  std::vector<double> matrix, residual;
  std::vector<std::uint8_t> dependent;      ///< per row of the island being solved
  UnionFind linked;
  std::vector<std::uint32_t> root_island;   ///< scratch: island by union-find root
  std::vector<std::uint32_t> island_of, counts, fill;  ///< scratch: per joint, per island
};

}  // namespace engine::detail
