// Helpers for joint tests: joints in a line each, and what a joint's error is.
#pragma once

#include <algorithm>
#include <span>

#include "engine/world.h"

namespace testing {

inline engine::JointDef Revolute(engine::BodyId a, engine::BodyId b, engine::Vec2 anchor) {
  engine::JointDef def;
  def.type = engine::JointType::kRevolute;
  def.body_a = a;
  def.body_b = b;
  def.anchor = anchor;
  return def;
}

inline engine::JointDef Distance(engine::BodyId a, engine::BodyId b, engine::Vec2 anchor_a, engine::Vec2 anchor_b) {
  engine::JointDef def;
  def.type = engine::JointType::kDistance;
  def.body_a = a;
  def.body_b = b;
  def.anchor = anchor_a;
  def.anchor_b = anchor_b;
  return def;
}

/// The largest distance between a joint's two anchor points, over `ids`: how far the joints
/// have come apart (revolute and weld joints hold their anchors together).
inline double LargestAnchorGap(const engine::World& world, std::span<const engine::JointId> ids) {
  double gap = 0.0;
  for (const engine::JointId id : ids) {
    const engine::JointFrame f = world.Joint(id);
    gap = std::max(gap, engine::Length(f.anchor_b - f.anchor_a));
  }
  return gap;
}

}  // namespace testing
