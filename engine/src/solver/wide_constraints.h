// The axis-aligned contacts laid out for the wide solver: blocks of four constraints, each field
// four doubles side by side (structure of arrays), in colour order. Internal to the engine.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

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

  /// Lays out `constraints`, stored in `colours`' order, in blocks.
  void Pack(std::span<const LinearConstraint> constraints, const ContactOrder& colours);
  /// Copies the impulses back to the constraints Pack read, for the passes after the substeps.
  void UnpackImpulses(std::span<LinearConstraint> constraints) const;
};

/// Sets `pushed` to 1 for both bodies of every constraint with a positive normal impulse (as
/// MarkPushed); padding lanes carry none.
void MarkPushedWide(std::span<const LinearBlock> blocks, std::size_t body_count,
                    std::vector<std::uint8_t>* pushed);

}  // namespace engine::detail
