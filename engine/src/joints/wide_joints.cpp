// Colouring the joints that fit the lanes, packing them into blocks of four, and back.
#include "joints/wide_joints.h"

#include <algorithm>
#include <bit>

#include "joints/joint_solver.h"

namespace engine::detail {

namespace {

bool Moves(double inv_mass, double inv_inertia) { return inv_mass != 0.0 || inv_inertia != 0.0; }

}  // namespace

bool WideJoints::Fits(const JointWork& w, const Joint& j) {
  return w.type == JointType::kRevolute && w.a != kNoBody && !j.def.motor && !j.def.limits;
}

void WideJoints::Clear() {
  blocks.clear();
  order.group_ends.clear();
  order.parallel_groups = 0;
  lane_of.clear();
  work_of.clear();
}

std::size_t WideJoints::Pack(std::span<const JointWork> work, const JointTable& table, std::size_t body_count) {
  Clear();
  lane_of.assign(work.size(), kNotWide);
  std::size_t fit = 0;
  for (const JointWork& w : work) fit += Fits(w, table.joints[w.slot]) ? 1 : 0;
  if (fit < kMinWideJoints) return 0;
  // Greedy colouring in slot order, a 64-bit mask of taken colours per body (ColourContacts);
  // lane_of holds each joint's colour until the blocks are laid out.
  constexpr std::uint32_t kColours = kSharedColour + 1;
  std::vector<std::uint64_t>& taken = order.body_marks;
  taken.assign(body_count, 0);
  std::vector<std::uint32_t> counts(kColours, 0);
  for (std::size_t i = 0; i < work.size(); ++i) {
    const JointWork& w = work[i];
    if (!Fits(w, table.joints[w.slot])) continue;
    const auto colour =
        std::min(static_cast<std::uint32_t>(std::countr_one(taken[w.a] | taken[w.b])), kColours - 1);
    const std::uint64_t bit = std::uint64_t{1} << colour;
    if (Moves(w.ma, w.ia)) taken[w.a] |= bit;
    if (Moves(w.mb, w.ib)) taken[w.b] |= bit;
    lane_of[i] = colour;
    ++counts[colour];
  }
  // Blocks colour by colour, each colour's joints in slot order: four to a block, one in the last.
  std::vector<std::uint32_t> first_block(kColours, 0);
  std::uint32_t total = 0;
  std::uint32_t colours = 0;
  for (std::uint32_t c = 0; c < kColours; ++c) {
    first_block[c] = total;
    const std::uint32_t per_block = c < kSharedColour ? kBlockLanes : 1;
    total += (counts[c] + per_block - 1) / per_block;
    if (counts[c] > 0) colours = c + 1;
  }
  blocks.assign(total, JointBlock{});  // zero: padding until filled
  work_of.assign(std::size_t{total} * kBlockLanes, kNotWide);
  std::vector<std::uint32_t> placed(kColours, 0);
  for (std::size_t i = 0; i < work.size(); ++i) {
    if (lane_of[i] == kNotWide) continue;
    const std::uint32_t c = lane_of[i];
    const std::uint32_t per_block = c < kSharedColour ? kBlockLanes : 1;
    const std::uint32_t n = placed[c]++;
    const std::uint32_t block = first_block[c] + n / per_block, lane = n % per_block;
    JointBlock& k = blocks[block];
    const JointWork& w = work[i];
    k.a[lane] = static_cast<std::int32_t>(w.a);
    k.b[lane] = static_cast<std::int32_t>(w.b);
    k.inv_mass_a[lane] = w.ma;
    k.inv_mass_b[lane] = w.mb;
    k.inv_inertia_a[lane] = w.ia;
    k.inv_inertia_b[lane] = w.ib;
    const Vec2 impulse = table.joints[w.slot].impulses.point;
    k.impulse_x[lane] = impulse.x;
    k.impulse_y[lane] = impulse.y;
    lane_of[i] = block * kBlockLanes + lane;
    work_of[lane_of[i]] = static_cast<std::uint32_t>(i);
  }
  for (std::uint32_t c = 0; c < colours; ++c) {
    if (counts[c] > 0) order.group_ends.push_back(c + 1 < kColours ? first_block[c + 1] : total);
  }
  order.parallel_groups =
      static_cast<std::uint32_t>(colours > kSharedColour ? order.group_ends.size() - 1 : order.group_ends.size());
  order.strips = 0;
  return fit;
}

void WideJoints::LoadFrames(std::span<const JointWork> work, WorkerPool& pool) {
  pool.ParallelFor(static_cast<std::uint32_t>(blocks.size()), kMinParallelJoints / kBlockLanes, [&](std::uint32_t i) {
    JointBlock& k = blocks[i];
    for (std::size_t lane = 0; lane < kBlockLanes; ++lane) {
      const std::uint32_t index = work_of[i * kBlockLanes + lane];
      if (index == kNotWide) continue;
      const JointWork& w = work[index];
      k.arm_a_x[lane] = w.ra.x;
      k.arm_a_y[lane] = w.ra.y;
      k.arm_b_x[lane] = w.rb.x;
      k.arm_b_y[lane] = w.rb.y;
      k.separation_x[lane] = w.separation.x;
      k.separation_y[lane] = w.separation.y;
      // Solve22's determinant, in its order. A joint in lanes has a moving body, so
      // K ≥ its inverse mass · I and the determinant is positive.
      const auto [k11, k12, k22] = PointMass(w);
      const double det = k11 * k22 - k12 * k12;
      k.k11[lane] = k11;
      k.k12[lane] = k12;
      k.k22[lane] = k22;
      k.inv_det[lane] = det > 0.0 ? 1.0 / det : 0.0;
    }
  });
}

void WideJoints::LoadDrift(std::span<const JointWork> work, WorkerPool& pool) {
  pool.ParallelFor(static_cast<std::uint32_t>(blocks.size()), kMinParallelJoints / kBlockLanes, [&](std::uint32_t i) {
    JointBlock& k = blocks[i];
    for (std::size_t lane = 0; lane < kBlockLanes; ++lane) {
      const std::uint32_t index = work_of[i * kBlockLanes + lane];
      if (index == kNotWide) continue;
      k.drift_x[lane] = work[index].drift_point.x;
      k.drift_y[lane] = work[index].drift_point.y;
    }
  });
}

void WideJoints::UnpackImpulses(std::span<const JointWork> work, JointTable* table) const {
  for (std::size_t l = 0; l < work_of.size(); ++l) {
    if (work_of[l] == kNotWide) continue;
    const JointBlock& k = blocks[l / kBlockLanes];
    table->joints[work[work_of[l]].slot].impulses.point = {k.impulse_x[l % kBlockLanes], k.impulse_y[l % kBlockLanes]};
  }
}

}  // namespace engine::detail
