// The contacts laid out for the wide solver: blocks of four constraints, each field four doubles
// side by side (structure of arrays), in colour order, or turning ones in strips. Internal to the engine.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "engine/contact.h"
#include "parallel/worker_pool.h"
#include "solver/body_cut.h"
#include "solver/contact_order.h"
#include "solver/substep_constraint.h"

namespace engine::detail {

/// How many constraints a block holds: the widest lanes solved (AVX2, four doubles). Fixed, so
/// the layout and the order never depend on the processor: narrower lanes take a block in parts.
inline constexpr int kBlockLanes = 4;

/// Four LinearConstraints, field by field. A lane past its group's end is padding: zero masses
/// and impulses on body 0, so it computes nothing that is written.
struct alignas(32) LinearBlock {
  std::int32_t a[kBlockLanes];
  std::int32_t b[kBlockLanes];
  double normal_x[kBlockLanes];
  double normal_y[kBlockLanes];
  double inv_mass_a[kBlockLanes];
  double inv_mass_b[kBlockLanes];
  double normal_mass[kBlockLanes];
  double base_separation[kBlockLanes];
  double normal_impulse[kBlockLanes];
  double tangent_impulse[kBlockLanes];
  double friction[kBlockLanes];
};

/// The constraints of a colour order (ContactOrder::ByColour) in blocks. A colour whose contacts
/// share no moving body fills its blocks four at a time: the lanes of a block, like the
/// constraints of the colour, touch different moving bodies, so solving them side by side gives
/// the bits of solving them one after another. Constraints that may share a body (the colour the
/// colouring ran out at) go one to a block, so they stay one after another.
struct WideConstraints {
  std::vector<LinearBlock> blocks;
  /// The same groups as the colour order's, in blocks: what ForEachGroup shares among threads.
  ContactOrder order;
  /// Where constraint j of the colour order went: block lane_of[j] / 4, lane lane_of[j] % 4.
  std::vector<std::uint32_t> lane_of;
  /// Per block, the body its first constraint moves and that constraint's a where a is held
  /// fixed (kNoBody where a moves), as BodyCut takes them; and the cut (CutByBodies).
  std::vector<BodyIndex> lead_body, lead_fixed;
  BodyCut body_cut;

  /// Lays out `constraints`, stored in `colours`' order, in blocks: Layout, then PackBlocks of all.
  void Pack(std::span<const LinearConstraint> constraints, const ContactOrder& colours);
  /// Sizes the blocks for `colours`' groups (and `order`, `lane_of`, the leads).
  void Layout(const ContactOrder& colours);
  /// The first constraint of the colour order `colours` that block `block` of its layout holds
  /// (the constraints' count for blocks.size()): blocks [b, e) hold the constraints
  /// [FirstConstraint(b), FirstConstraint(e)), padding aside.
  std::uint32_t FirstConstraint(std::uint32_t block, const ContactOrder& colours) const;
  /// Fills blocks [begin, end) of the layout from the constraints: each writes only its own
  /// block, lead and constraints' lane_of, so parts may be filled on different threads.
  void PackBlocks(std::span<const LinearConstraint> constraints, const ContactOrder& colours, std::uint32_t begin,
                  std::uint32_t end);
  /// Writes each contact's impulses from the lane that solved its constraint (contact i's is
  /// constraint slot[i] of the colour order), as StoreImpulses does from the constraints: read
  /// straight from the blocks, without copying them back to the constraints first (that copy and
  /// its read cost 200 kcyc a step of the 4 000-circle pour on one thread, this 124).
  /// `pool`: threads to share the contacts among.
  void StoreImpulses(std::span<const std::uint32_t> slot, std::span<Contact> contacts,
                     WorkerPool* pool = nullptr) const;
  /// Cuts the groups among `threads` threads by the bodies they move (BodyCut), once packed.
  void CutByBodies(std::size_t body_count, int threads) {
    body_cut.Cut(order, lead_body, lead_fixed, body_count, threads);
  }
};

/// One point of four turning contacts, field by field (SubstepPoint's fields).
struct alignas(32) TurningPointLanes {
  double base_separation[kBlockLanes];
  double normal_mass[kBlockLanes];
  double tangent_mass[kBlockLanes];
  double normal_impulse[kBlockLanes];
  double tangent_impulse[kBlockLanes];
  double anchor_a_x[kBlockLanes];
  double anchor_a_y[kBlockLanes];
  double anchor_b_x[kBlockLanes];
  double anchor_b_y[kBlockLanes];
  /// The least normal speed the point may take this substep (its gap over the substep, or 0),
  /// worked out by the substep's first velocity pass from the moves and read by the others:
  /// the moves change only between substeps.
  double min_normal_speed[kBlockLanes];
};

/// The second points of four turning contacts, with what the block solver reads of both
/// (SolveTwoPoints): K = J·M⁻¹·Jᵀ of the two normals (NormalMass), its determinant and the
/// reciprocals the solve multiplies by, fixed for the step (the anchors are), so worked out as
/// the blocks are packed instead of in every velocity pass. Zero in a lane with one point.
struct alignas(32) TurningSecondLanes : TurningPointLanes {
  double k11[kBlockLanes];
  double k12[kBlockLanes];
  double k22[kBlockLanes];
  double det[kBlockLanes];      ///< k11·k22 − k12·k12
  double inv_det[kBlockLanes];  ///< 1 / det
  double inv_k11[kBlockLanes];  ///< 1 / k11
  double inv_k22[kBlockLanes];  ///< 1 / k22
};

/// Four SubstepConstraints whose bodies can turn (`angular`), field by field, with their first
/// points; their second points are kept apart (WideTurningConstraints::second_points). Padding
/// lanes are zero throughout, on body 0.
struct alignas(32) TurningBlock {
  std::int32_t a[kBlockLanes];
  std::int32_t b[kBlockLanes];
  double two_points[kBlockLanes];  ///< 1 where the contact has two points, 0 where one
  double normal_x[kBlockLanes];
  double normal_y[kBlockLanes];
  double inv_mass_a[kBlockLanes];
  double inv_mass_b[kBlockLanes];
  double inv_inertia_a[kBlockLanes];
  double inv_inertia_b[kBlockLanes];
  double friction[kBlockLanes];
  TurningPointLanes first;  ///< each lane's first point
};

/// The turning constraints of a colour order in blocks as WideConstraints lays them out, or of a
/// strip order (ContactOrder::InStrips), a strip to a lane:
/// lane l of the k-th block of a set holds the k-th contact of its strip. Strips share no moving
/// body and each keeps its contact order, so solving four strips side by side gives the bits of
/// solving them one after another. Four sets of blocks, as groups for ForEachGroup's strip mode
/// (two strips: the first two sets go side by side, then the third, then the last):
/// the even strips; the odd strips; the even edges then the odd edges (within either, no two
/// share a strip); the far contacts, one to a block, in order.
struct WideTurningConstraints {
  std::vector<TurningBlock> blocks;
  /// Per block, its lanes' second points (zero in a lane with one). Apart from the blocks, so
  /// that the passes over circles, which have one point, never fetch these lines: a third of the
  /// bytes (with them in the blocks, the turning 4 000-circle pour's warm start took 1.27 times as
  /// long, its push-out 1.33, its solve 1.06). A block whose lanes all have one point is not
  /// written here at all (a pile of circles packed 3.6 % of its step, most of it here): its
  /// passes do not read it, or, beside a twin block that has two, read it and keep none of it.
  std::vector<TurningSecondLanes> second_points;
  ContactOrder order;                ///< the four sets' ends, in blocks (strips = 2)
  /// In a strip order: where the odd edges start within the third set, and whether the even
  /// edges and the odd ones share no moving body (as good as always: an even edge and an odd one
  /// meet only in a strip one or two bodies wide), so that they may go side by side too.
  std::uint32_t odd_edges_begin = 0;
  bool edges_apart = false;
  std::vector<std::uint32_t> lane_of;  ///< as WideConstraints::lane_of
  /// As WideConstraints' (in a colour order only).
  std::vector<BodyIndex> lead_body, lead_fixed;
  BodyCut body_cut;

  /// Whether the wide passes can take these constraints: every one angular (a pair that cannot
  /// turn takes the centres' row, other arithmetic) and the order in strips or by colour.
  static bool Fits(std::span<const SubstepConstraint> constraints, const ContactOrder& order);
  /// The same, told whether every constraint is angular (`all_angular`, as preparing them
  /// found: ConstraintKinds).
  static bool Fits(const ContactOrder& order, bool all_angular);
  void Pack(std::span<const SubstepConstraint> constraints, const ContactOrder& contact_order);
  /// As WideConstraints::Layout, for a colour order (with the second points' lanes).
  void Layout(const ContactOrder& colours);
  /// As WideConstraints::PackBlocks: blocks [begin, end) of a colour order's layout, each
  /// writing only its own lanes, so that threads may fill parts side by side.
  void PackBlocks(std::span<const SubstepConstraint> constraints, const ContactOrder& colours, std::uint32_t begin,
                  std::uint32_t end);
  /// As WideConstraints::StoreImpulses (a lane with one point stores none for its second).
  void StoreImpulses(std::span<const std::uint32_t> slot, std::span<Contact> contacts,
                     WorkerPool* pool = nullptr) const;
  /// As WideConstraints::CutByBodies; a colour order only.
  void CutByBodies(std::size_t body_count, int threads) {
    body_cut.Cut(order, lead_body, lead_fixed, body_count, threads);
  }

  std::vector<BodyIndex> moving_bodies;  ///< Pack's scratch (ShareMovingBody)
};

/// Runs [first, second) of constraints.
using ConstraintRuns = std::span<const std::pair<std::uint32_t, std::uint32_t>>;

/// Whether a body that moves in one of runs `one`'s constraints moves in one of runs `two`'s
/// (a body a constraint holds fixed, inverse mass 0, is never written, so it is not shared).
/// `scratch`: kept between calls.
bool ShareMovingBody(std::span<const SubstepConstraint> constraints, ConstraintRuns one, ConstraintRuns two,
                     std::vector<BodyIndex>* scratch);

/// Sets `pushed` to 1 for both bodies of every constraint with a positive normal impulse (as
/// MarkPushed); padding lanes carry none.
void MarkPushedWide(std::span<const LinearBlock> blocks, std::size_t body_count,
                    std::vector<std::uint8_t>* pushed);
void MarkPushedWide(const WideTurningConstraints& wide, std::size_t body_count, std::vector<std::uint8_t>* pushed);

}  // namespace engine::detail
