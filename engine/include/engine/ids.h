// The ids the API hands out.
#pragma once

#include <cstdint>
#include <limits>

namespace engine {

/// A body's slot in the world's arrays. Bodies are stepped, dumped and hashed in slot order; a
/// world whose bodies were never destroyed has them in creation (scene) order, slot 0 first.
using BodyIndex = std::uint32_t;
inline constexpr BodyIndex kNoBody = std::numeric_limits<BodyIndex>::max();

/// A handle to a body: its slot and the slot's generation, which goes up each time a body in
/// that slot is destroyed. An id kept after its body was destroyed is stale: the world detects
/// it (World::IsValid) even once the slot holds another body. A fresh world's bodies have
/// generation 0, so `BodyId{3}` is the fourth body created.
struct BodyId {
  BodyIndex index = kNoBody;
  std::uint32_t generation = 0;
  friend constexpr bool operator==(BodyId, BodyId) = default;
};

}  // namespace engine

namespace engine {

/// A handle to a joint, as BodyId is to a body: its slot and that slot's generation. Joints are
/// solved in slot order; a fresh world's joints have generation 0, `JointId{2}` the third made.
struct JointId {
  std::uint32_t index = std::numeric_limits<std::uint32_t>::max();
  std::uint32_t generation = 0;
  friend constexpr bool operator==(JointId, JointId) = default;
};

}  // namespace engine

namespace engine {

/// A handle to a soft body (World::CreateSoftBody), as BodyId is to a body. Soft bodies are
/// stepped, hashed and dumped in slot order; a fresh world's have generation 0.
struct SoftBodyId {
  std::uint32_t index = std::numeric_limits<std::uint32_t>::max();
  std::uint32_t generation = 0;
  friend constexpr bool operator==(SoftBodyId, SoftBodyId) = default;
};

/// A handle to an emitter of effect particles (World::CreateEmitter).
struct EmitterId {
  std::uint32_t index = std::numeric_limits<std::uint32_t>::max();
  std::uint32_t generation = 0;
  friend constexpr bool operator==(EmitterId, EmitterId) = default;
};

}  // namespace engine
