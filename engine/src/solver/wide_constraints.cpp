// Packing the colour-ordered constraints into blocks of four lanes, and back.
#include "solver/wide_constraints.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <utility>

#include "solver/substep_passes.h"

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

// The body constraint c moves that BodyCut cuts by, and its a where a is held fixed (else kNoBody).
template <typename Constraint>
void SetLead(const Constraint& c, BodyIndex* body, BodyIndex* fixed) {
  const bool a_fixed = c.inv_mass_a == 0.0;
  *body = a_fixed ? c.b : c.a;
  *fixed = a_fixed ? c.a : kNoBody;
}

// Lane `lane` of a turning block: its pair and first point.
void PutLane(const SubstepConstraint& c, TurningBlock* block, int lane) {
  block->a[lane] = static_cast<std::int32_t>(c.a);
  block->b[lane] = static_cast<std::int32_t>(c.b);
  block->two_points[lane] = c.point_count == 2 ? 1.0 : 0.0;
  block->normal_x[lane] = c.normal.x;
  block->normal_y[lane] = c.normal.y;
  block->inv_mass_a[lane] = c.inv_mass_a;
  block->inv_mass_b[lane] = c.inv_mass_b;
  block->inv_inertia_a[lane] = c.inv_inertia_a;
  block->inv_inertia_b[lane] = c.inv_inertia_b;
  block->friction[lane] = c.friction;
  const SubstepPoint& p = c.points[0];
  TurningPointLanes& lanes = block->first;
  lanes.base_separation[lane] = p.base_separation;
  lanes.normal_mass[lane] = p.normal_mass;
  lanes.tangent_mass[lane] = p.tangent_mass;
  lanes.normal_impulse[lane] = p.normal_impulse;
  lanes.tangent_impulse[lane] = p.tangent_impulse;
  lanes.anchor_a_x[lane] = p.anchor_a.x;
  lanes.anchor_a_y[lane] = p.anchor_a.y;
  lanes.anchor_b_x[lane] = p.anchor_b.x;
  lanes.anchor_b_y[lane] = p.anchor_b.y;
}

// Lane `lane` of a block's second points (zero for a one-point contact), with the block
// solver's K.
void PutSecondLane(const SubstepConstraint& c, TurningSecondLanes* second, int lane) {
  const bool two = c.point_count == 2;
  const SubstepPoint none{};  // a one-point contact's second point: zero
  const SubstepPoint& p = two ? c.points[1] : none;
  second->base_separation[lane] = p.base_separation;
  second->normal_mass[lane] = p.normal_mass;
  second->tangent_mass[lane] = p.tangent_mass;
  second->normal_impulse[lane] = p.normal_impulse;
  second->tangent_impulse[lane] = p.tangent_impulse;
  second->anchor_a_x[lane] = p.anchor_a.x;
  second->anchor_a_y[lane] = p.anchor_a.y;
  second->anchor_b_x[lane] = p.anchor_b.x;
  second->anchor_b_y[lane] = p.anchor_b.y;
  // The block solver's K and what it divides by, as SolveTwoPoints works them out.
  const TwoPointMass k = two ? NormalMass(c, c.points[0], c.points[1], c.inv_mass_a, c.inv_mass_b, c.inv_inertia_a,
                                          c.inv_inertia_b)
                             : TwoPointMass{};
  const double det = k.k11 * k.k22 - k.k12 * k.k12;
  second->k11[lane] = k.k11;
  second->k12[lane] = k.k12;
  second->k22[lane] = k.k22;
  second->det[lane] = det;
  second->inv_det[lane] = two ? 1.0 / det : 0.0;
  second->inv_k11[lane] = two ? 1.0 / k.k11 : 0.0;
  second->inv_k22[lane] = two ? 1.0 / k.k22 : 0.0;
}

// A block's second points, once its lanes are in: written only where a lane has two points
// (WideTurningConstraints::second_points says why). `lanes[l]`: the constraint in lane l, null
// for padding.
void PutSecondLanes(const std::array<const SubstepConstraint*, kBlockLanes>& lanes, const TurningBlock& block,
                    TurningSecondLanes* second) {
  bool any_two = false;
  for (int l = 0; l < kBlockLanes; ++l) any_two = any_two || block.two_points[l] != 0.0;
  if (!any_two) return;
  const SubstepConstraint padding{};
  for (int l = 0; l < kBlockLanes; ++l) {
    const auto lane = static_cast<std::size_t>(l);
    PutSecondLane(lanes[lane] ? *lanes[lane] : padding, second, l);
  }
}

// How many blocks runs side by side take: as many as the longest has constraints.
std::uint32_t LongestRun(ConstraintRuns runs) {
  std::uint32_t longest = 0;
  for (const auto& [begin, end] : runs) longest = std::max(longest, end - begin);
  return longest;
}

// Writes blocks [first, first + the longest run) so that lane l of the k-th holds the k-th
// constraint of `runs[l]` (ranges of the strip order, at most four) and every other lane is
// padding; returns where they end. Block by block, every lane: the storage is kept from step to
// step, not zeroed first.
std::size_t PlaceSideBySide(std::span<const SubstepConstraint> constraints, ConstraintRuns runs, std::size_t first,
                            WideTurningConstraints* wide) {
  assert(runs.size() <= static_cast<std::size_t>(kBlockLanes));
  const std::uint32_t longest = LongestRun(runs);
  const SubstepConstraint padding{};  // zero, on body 0
  for (std::uint32_t k = 0; k < longest; ++k) {
    const std::size_t block = first + k;
    std::array<const SubstepConstraint*, kBlockLanes> in_lanes{};
    for (int l = 0; l < kBlockLanes; ++l) {
      const auto lane = static_cast<std::size_t>(l);
      if (lane < runs.size() && runs[lane].first + k < runs[lane].second) {
        const std::uint32_t j = runs[lane].first + k;
        in_lanes[lane] = &constraints[j];
        PutLane(constraints[j], &wide->blocks[block], l);
        wide->lane_of[j] = static_cast<std::uint32_t>(block * kBlockLanes + lane);
      } else {
        PutLane(padding, &wide->blocks[block], l);
      }
    }
    PutSecondLanes(in_lanes, wide->blocks[block], &wide->second_points[block]);
  }
  return first + longest;
}

// Sizes `blocks` for the groups of a colour order and writes their ends, in blocks, to `order`:
// a colour that shares no moving body four to a block, any other one to a block.
template <typename Block>
void LayoutColours(const ContactOrder& colours, ContactOrder* order, std::vector<Block>* blocks,
                   std::vector<std::uint32_t>* lane_of) {
  assert(colours.strips == 0);
  order->group_ends.clear();
  order->strips = 0;
  order->parallel_groups = colours.parallel_groups;
  std::uint32_t begin = 0, block_count = 0;
  for (std::size_t g = 0; g < colours.group_ends.size(); ++g) {
    const std::uint32_t end = colours.group_ends[g];
    const std::uint32_t lanes = g < colours.parallel_groups ? kBlockLanes : 1;
    block_count += (end - begin + lanes - 1) / lanes;
    order->group_ends.push_back(block_count);
    begin = end;
  }
  // Sized without zeroing: the packing writes every lane, padding too.
  blocks->resize(block_count);
  lane_of->resize(colours.group_ends.empty() ? 0 : colours.group_ends.back());
}

// Fills blocks [begin, end) of a colour layout (LayoutColours), lane by lane through
// put(constraint, block, lane): block k of group g holds the group's constraints from its
// (k − the group's first block) × lanes on, padding past the group's end. Then finish(block,
// the constraints in its lanes, null for padding).
template <typename Constraint, typename Put, typename Finish>
void PackColours(std::span<const Constraint> constraints, const ContactOrder& colours, const ContactOrder& order,
                 std::uint32_t begin, std::uint32_t end, Put&& put, Finish&& finish,
                 std::vector<std::uint32_t>* lane_of) {
  for (std::size_t g = 0; g < order.group_ends.size(); ++g) {
    const std::uint32_t group_begin = g == 0 ? 0 : order.group_ends[g - 1];
    const std::uint32_t group_end = order.group_ends[g];
    if (group_end <= begin) continue;
    if (group_begin >= end) break;
    const std::uint32_t first = g == 0 ? 0 : colours.group_ends[g - 1];
    const std::uint32_t last = colours.group_ends[g];
    const std::uint32_t lanes = g < colours.parallel_groups ? kBlockLanes : 1;
    for (std::uint32_t k = std::max(begin, group_begin); k < std::min(end, group_end); ++k) {
      const std::uint32_t j0 = first + (k - group_begin) * lanes;
      const std::uint32_t filled = std::min(lanes, last - j0);
      std::array<const Constraint*, kBlockLanes> in_lanes{};
      for (std::uint32_t lane = 0; lane < filled; ++lane) {
        put(constraints[j0 + lane], k, static_cast<int>(lane));
        in_lanes[lane] = &constraints[j0 + lane];
        (*lane_of)[j0 + lane] = k * kBlockLanes + lane;
      }
      for (std::uint32_t lane = filled; lane < kBlockLanes; ++lane) {
        put(Constraint{}, k, static_cast<int>(lane));  // padding: zero, on body 0
      }
      finish(k, in_lanes);
    }
  }
}

}  // namespace

bool WideTurningConstraints::Fits(std::span<const SubstepConstraint> constraints, const ContactOrder& order) {
  return Fits(order, std::ranges::all_of(constraints, [](const SubstepConstraint& c) { return c.angular; }));
}

bool WideTurningConstraints::Fits(const ContactOrder& order, bool all_angular) {
  const bool by_colour = order.strips == 0 && order.parallel_groups > 0;
  const bool in_strips = order.strips > 0 && order.strips <= 2 * static_cast<std::uint32_t>(kBlockLanes);
  return (by_colour || in_strips) && all_angular;
}

bool ShareMovingBody(std::span<const SubstepConstraint> constraints, ConstraintRuns one, ConstraintRuns two,
                     std::vector<BodyIndex>* scratch) {
  // The moving bodies of `one`'s constraints, sorted, then a look for each of `two`'s: the edges
  // between strips hold a few hundred constraints, fewer than marks over every body would take.
  std::vector<BodyIndex>& moving = *scratch;
  moving.clear();
  for (const auto& [begin, end] : one) {
    for (std::uint32_t j = begin; j < end; ++j) {
      if (constraints[j].inv_mass_a != 0.0) moving.push_back(constraints[j].a);
      if (constraints[j].inv_mass_b != 0.0) moving.push_back(constraints[j].b);
    }
  }
  std::sort(moving.begin(), moving.end());
  const auto in_one = [&](BodyIndex body) { return std::binary_search(moving.begin(), moving.end(), body); };
  for (const auto& [begin, end] : two) {
    for (std::uint32_t j = begin; j < end; ++j) {
      if (constraints[j].inv_mass_a != 0.0 && in_one(constraints[j].a)) return true;
      if (constraints[j].inv_mass_b != 0.0 && in_one(constraints[j].b)) return true;
    }
  }
  return false;
}

void WideTurningConstraints::Pack(std::span<const SubstepConstraint> constraints,
                                  const ContactOrder& contact_order) {
  assert(Fits(constraints, contact_order));
  if (contact_order.strips == 0) {  // a colour order
    Layout(contact_order);
    PackBlocks(constraints, contact_order, 0, static_cast<std::uint32_t>(blocks.size()));
    return;
  }
  const StripGroups groups(static_cast<int>(contact_order.strips));
  const auto range = [&](std::uint32_t g) {
    const std::vector<std::uint32_t>& ends = contact_order.group_ends;
    return std::pair<std::uint32_t, std::uint32_t>{g == 0 ? 0 : ends[g - 1], ends[g]};
  };
  const auto runs_of = [&](std::uint32_t first, std::uint32_t end, std::uint32_t step) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> runs;
    for (std::uint32_t g = first; g < end; g += step) runs.push_back(range(g));
    return runs;
  };
  // The even strips, then the odd ones: each set a group, the two side by side on two threads.
  // Then the even edges, then the odd ones, in one group; then the rest, one to a block, in order.
  const auto even = runs_of(0, groups.strips, 2), odd = runs_of(1, groups.strips, 2);
  const auto even_edges = runs_of(groups.strips, groups.strips + groups.even_edges, 1);
  const auto odd_edges = runs_of(groups.strips + groups.even_edges, groups.far, 1);
  const auto [far_begin, far_end] = range(groups.far);
  blocks.resize(std::size_t{LongestRun(even)} + LongestRun(odd) + LongestRun(even_edges) + LongestRun(odd_edges) +
                (far_end - far_begin));
  second_points.resize(blocks.size());
  lane_of.resize(constraints.size());
  order.group_ends.clear();
  order.parallel_groups = 0;
  order.strips = 2;
  std::size_t next = PlaceSideBySide(constraints, even, 0, this);
  order.group_ends.push_back(static_cast<std::uint32_t>(next));
  next = PlaceSideBySide(constraints, odd, next, this);
  order.group_ends.push_back(static_cast<std::uint32_t>(next));
  next = PlaceSideBySide(constraints, even_edges, next, this);
  odd_edges_begin = static_cast<std::uint32_t>(next);
  next = PlaceSideBySide(constraints, odd_edges, next, this);
  order.group_ends.push_back(static_cast<std::uint32_t>(next));
  edges_apart = !ShareMovingBody(constraints, even_edges, odd_edges, &moving_bodies);
  for (std::uint32_t j = far_begin; j < far_end; ++j) {
    const std::pair<std::uint32_t, std::uint32_t> one[] = {{j, j + 1}};
    next = PlaceSideBySide(constraints, one, next, this);
  }
  order.group_ends.push_back(static_cast<std::uint32_t>(next));
  assert(next == blocks.size());
}

void WideTurningConstraints::Layout(const ContactOrder& colours) {
  LayoutColours(colours, &order, &blocks, &lane_of);
  second_points.resize(blocks.size());
  lead_body.resize(blocks.size());
  lead_fixed.resize(blocks.size());
}

void WideTurningConstraints::PackBlocks(std::span<const SubstepConstraint> constraints, const ContactOrder& colours,
                                        std::uint32_t begin, std::uint32_t end) {
  const auto put = [&](const SubstepConstraint& c, std::uint32_t block, int lane) {
    PutLane(c, &blocks[block], lane);
    if (lane == 0) SetLead(c, &lead_body[block], &lead_fixed[block]);  // lane 0 is never padding
  };
  const auto finish = [&](std::uint32_t block, const std::array<const SubstepConstraint*, kBlockLanes>& in_lanes) {
    PutSecondLanes(in_lanes, blocks[block], &second_points[block]);
  };
  PackColours(constraints, colours, order, begin, end, put, finish, &lane_of);
}

void WideTurningConstraints::StoreImpulses(std::span<const std::uint32_t> slot, std::span<Contact> contacts,
                                           WorkerPool* pool) const {
  ForEachIndex(pool, contacts.size(), kMinSharedContacts, [&](std::uint32_t i) {
    const std::uint32_t b = lane_of[slot[i]] / kBlockLanes, lane = lane_of[slot[i]] % kBlockLanes;
    const bool two_points = blocks[b].two_points[lane] != 0.0;
    for (int k = 0; k < 2; ++k) {
      const bool held = k == 0 || two_points;
      const TurningPointLanes& point = k == 0 ? blocks[b].first : second_points[b];
      contacts[i].normal_impulse[k] = held ? point.normal_impulse[lane] : 0.0;
      contacts[i].tangent_impulse[k] = held ? point.tangent_impulse[lane] : 0.0;
    }
  });
}

void WideConstraints::Pack(std::span<const LinearConstraint> constraints, const ContactOrder& colours) {
  Layout(colours);
  PackBlocks(constraints, colours, 0, static_cast<std::uint32_t>(blocks.size()));
}

void WideConstraints::Layout(const ContactOrder& colours) {
  LayoutColours(colours, &order, &blocks, &lane_of);
  lead_body.resize(blocks.size());
  lead_fixed.resize(blocks.size());
}

std::uint32_t WideConstraints::FirstConstraint(std::uint32_t block, const ContactOrder& colours) const {
  const std::vector<std::uint32_t>& block_ends = order.group_ends;
  const auto g = static_cast<std::size_t>(std::upper_bound(block_ends.begin(), block_ends.end(), block) -
                                          block_ends.begin());
  if (g == block_ends.size()) return block_ends.empty() ? 0 : colours.group_ends.back();
  const std::uint32_t group_block = g == 0 ? 0 : block_ends[g - 1];
  const std::uint32_t group_first = g == 0 ? 0 : colours.group_ends[g - 1];
  const std::uint32_t lanes = g < colours.parallel_groups ? kBlockLanes : 1;
  return std::min(group_first + (block - group_block) * lanes, colours.group_ends[g]);
}

void WideConstraints::PackBlocks(std::span<const LinearConstraint> constraints, const ContactOrder& colours,
                                 std::uint32_t begin, std::uint32_t end) {
  const auto put = [&](const LinearConstraint& c, std::uint32_t block, int lane) {
    PutLane(c, &blocks[block], lane);
    if (lane == 0) SetLead(c, &lead_body[block], &lead_fixed[block]);  // lane 0 is never padding
  };
  PackColours(constraints, colours, order, begin, end, put, [](std::uint32_t, const auto&) {}, &lane_of);
}

void WideConstraints::StoreImpulses(std::span<const std::uint32_t> slot, std::span<Contact> contacts,
                                    WorkerPool* pool) const {
  ForEachIndex(pool, contacts.size(), kMinSharedContacts, [&](std::uint32_t i) {
    const LinearBlock& block = blocks[lane_of[slot[i]] / kBlockLanes];
    const std::uint32_t lane = lane_of[slot[i]] % kBlockLanes;
    Contact& c = contacts[i];
    c.normal_impulse[0] = block.normal_impulse[lane];
    c.tangent_impulse[0] = block.tangent_impulse[lane];
    c.normal_impulse[1] = 0.0;
    c.tangent_impulse[1] = 0.0;
  });
}

void MarkPushedWide(const WideTurningConstraints& wide, std::size_t body_count, std::vector<std::uint8_t>* pushed) {
  pushed->assign(body_count, 0);
  for (std::size_t k = 0; k < wide.blocks.size(); ++k) {
    const TurningBlock& block = wide.blocks[k];
    for (int lane = 0; lane < kBlockLanes; ++lane) {
      // A one-point lane's second point may hold anything (PutSecondLanes).
      const bool second_pushes = block.two_points[lane] != 0.0 && wide.second_points[k].normal_impulse[lane] > 0.0;
      if (block.first.normal_impulse[lane] > 0.0 || second_pushes) {
        (*pushed)[block.a[lane]] = (*pushed)[block.b[lane]] = 1;
      }
    }
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
