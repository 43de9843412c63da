// Direct solve of the contacts of islands that hold a large mass ratio, with rotation on: a heavy
// body on light ones needs more Gauss-Seidel passes than any step can afford (their convergence
// slows with the ratio), so these islands get their contact impulses from an exact solve of the
// complementarity problem instead, after the passes. Internal.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "engine/body.h"
#include "engine/contact.h"
#include "engine/spring.h"
#include "engine/world_def.h"
#include "body_pair.h"
#include "solver/substep_passes.h"
#include "union_find.h"

namespace engine::detail {

/// A direct solve applies to an island (bodies linked by contacts between turning pairs, static
/// bodies excluded) that holds a contact across which one body is at least this many times
/// heavier than the other. Box2D's manual (Limitations) says stacking degrades past 10:1; below
/// it Gauss-Seidel holds a rotating column of three boxes within 0.5 mm.
inline constexpr double kDirectMassRatio = 10.0;

/// Islands with more rows than this are left to Gauss-Seidel: the factor is dense, and 60
/// random piles with mass ratios up to 1000:1 took 2 times Gauss-Seidel's time with this limit,
/// 10 times with 128 (docs/solver.md). One row per contact point and one friction row per
/// contact: a column of n boxes on the ground has 3n.
inline constexpr int kDirectMaxRows = 96;

/// The solver's working state for the islands of one step; reused from step to step.
struct DirectSolver {
  /// A normal row of one point (`point` ≥ 0) or the friction row of a whole contact (−1): in 2D
  /// the friction rows of a face's two points are the same row (and two equal rows make the
  /// problem singular), so a contact has one, at the points' mean anchor, within μ times the sum
  /// of its normal impulses.
  struct Row {
    std::uint32_t constraint;
    std::int32_t point;
    std::uint32_t first_normal;  ///< friction rows: the island row of the contact's first normal
  };
  struct Island {
    std::uint32_t first_row;    ///< rows [first_row, first_row + rows): normals, then friction
    std::uint32_t normal_rows;
    std::uint32_t rows;
    std::size_t matrix;         ///< offset of its K = J·M⁻¹·Jᵀ (rows × rows) in `matrix`
    std::uint32_t first_body;   ///< its moving bodies: bodies[first_body, first_body + body_count)
    std::uint32_t body_count;
  };
  /// An island's K row by row as its non-zeros (columns ascending), for products with K.
  struct Sparse {
    const std::uint32_t* begin;  ///< per row of the island, into column and value
    const std::uint32_t* end;
    const std::uint32_t* column;
    const double* value;
  };
  std::vector<Row> rows;
  std::vector<Island> islands;
  std::vector<double> matrix;
  std::vector<std::uint32_t> sparse_begin, sparse_end, sparse_column;  ///< per row; island columns
  std::vector<double> sparse_value;
  std::vector<std::uint32_t> bodies;
  /// Per row: free, or held at its lower or upper bound. Kept from substep to substep, so that a
  /// solve usually starts from the right guess and reuses its factor.
  std::vector<std::uint8_t> bound;
  std::vector<std::uint8_t> push_bound;  ///< the same for the push-out (normal rows)
  /// Per friction row: the limit its last answer was found with.
  std::vector<double> last_limit;
  /// Cholesky factors of the free rows, one slot per island for the velocities and one for the
  /// push-out, kept from substep to substep and updated row by row as the free rows change.
  std::vector<std::vector<double>> factor;
  std::vector<std::vector<std::uint32_t>> factor_rows;
  std::vector<std::uint8_t> factor_valid;
  std::vector<std::uint8_t> in_factor;  ///< scratch: per row of the island being solved
  /// The contacts (body pairs, in pair order) solved directly this step and the step before.
  std::vector<BodyPair> pairs, previous_pairs;
  std::vector<std::uint8_t> direct_contact;  ///< per constraint of this step
  // Scratch.
  UnionFind linked;  ///< bodies linked by contacts between turning pairs
  std::vector<std::uint8_t> flagged;
  std::vector<double> x, q, lo, hi, limit, rhs, centred, previous;
  std::vector<BodyState> saved;
};

/// Whether a contact between turning bodies joins two of which one is at least kDirectMassRatio
/// times the other's mass: its island takes the direct solve.
bool IsHeavyPair(const SubstepConstraint& sc, std::span<const BodyInfo> infos);

/// Finds the islands that need a direct solve (at most kDirectMaxRows rows) and builds their
/// effective-mass matrices for this step; false when there are none. A contact solved directly
/// last step and left to Gauss-Seidel now loses its warm-start impulses. `any_heavy`: whether
/// any constraint is a heavy pair (IsHeavyPair), as preparing them found (ConstraintKinds).
bool PrepareDirectSolve(std::span<SubstepConstraint> constraints, std::span<const BodyInfo> infos,
                        DirectSolver* solver, bool any_heavy);

/// After the Gauss-Seidel passes of a substep: replaces the impulses of each prepared island's
/// contacts with the exact answer, so that no contact approaches (beyond what its gap allows)
/// and friction holds within Coulomb's cone. An island whose solve fails (its pivoting runs
/// past its budget) keeps what Gauss-Seidel gave it this substep.
void SolveDirect(DirectSolver* solver, std::span<SubstepConstraint> constraints,
                 std::span<BodyState> states, const StepStart& start, double inv_h);

/// After Gauss-Seidel's push-out (PushOut): replaces each prepared island's push impulses with
/// the exact answer of its push-out problem (the same K, normal rows only), so that a light body
/// caught in overlap between a heavy one and the ground is not pushed through the ground.
void PushOutDirect(DirectSolver* solver, std::span<SubstepConstraint> constraints,
                   std::span<const BodyState> states, const StepStart& start, PushVelocities push,
                   double push_out_rate, double max_push_out_speed, double linear_slop);

}  // namespace engine::detail
