// Packing the colour-ordered constraints into blocks of four lanes, and back.
#include "solver/wide_constraints.h"

#include <cassert>

namespace engine::detail {

namespace {

void PutLane(const LinearConstraint& c, LinearBlock* block, int lane) {
  block->a[lane] = static_cast<std::int32_t>(c.a);
  block->b[lane] = static_cast<std::int32_t>(c.b);
  block->normal_x[lane] = c.normal.x;
  block->normal_y[lane] = c.normal.y;
  block->inv_mass_a[lane] = c.inv_mass_a;
  block->inv_mass_b[lane] = c.inv_mass_b;
  block->normal_mass[lane] = c.normal_mass;
  block->base_separation[lane] = c.base_separation;
  block->normal_impulse[lane] = c.normal_impulse;
  block->tangent_impulse[lane] = c.tangent_impulse;
  block->friction[lane] = c.friction;
}

}  // namespace

void WideConstraints::Pack(std::span<const LinearConstraint> constraints, const ContactOrder& colours) {
  assert(colours.strips == 0);
  blocks.clear();
  lane_of.resize(constraints.size());
  order.group_ends.clear();
  order.strips = 0;
  order.parallel_groups = colours.parallel_groups;
  std::uint32_t begin = 0;
  for (std::size_t g = 0; g < colours.group_ends.size(); ++g) {
    const std::uint32_t end = colours.group_ends[g];
    const int lanes = g < colours.parallel_groups ? kBlockLanes : 1;
    for (std::uint32_t j = begin; j < end; ++j) {
      const int lane = static_cast<int>((j - begin) % static_cast<std::uint32_t>(lanes));
      if (lane == 0) blocks.push_back(LinearBlock{});  // zero: padding until filled
      PutLane(constraints[j], &blocks.back(), lane);
      lane_of[j] = static_cast<std::uint32_t>((blocks.size() - 1) * kBlockLanes) + static_cast<std::uint32_t>(lane);
    }
    order.group_ends.push_back(static_cast<std::uint32_t>(blocks.size()));
    begin = end;
  }
}

void WideConstraints::UnpackImpulses(std::span<LinearConstraint> constraints) const {
  for (std::size_t j = 0; j < constraints.size(); ++j) {
    const LinearBlock& block = blocks[lane_of[j] / kBlockLanes];
    const std::uint32_t lane = lane_of[j] % kBlockLanes;
    constraints[j].normal_impulse = block.normal_impulse[lane];
    constraints[j].tangent_impulse = block.tangent_impulse[lane];
  }
}

void MarkPushedWide(std::span<const LinearBlock> blocks, std::size_t body_count,
                    std::vector<std::uint8_t>* pushed) {
  pushed->assign(body_count, 0);
  for (const LinearBlock& block : blocks) {
    for (int lane = 0; lane < kBlockLanes; ++lane) {
      if (block.normal_impulse[lane] > 0.0) (*pushed)[block.a[lane]] = (*pushed)[block.b[lane]] = 1;
    }
  }
}

}  // namespace engine::detail
