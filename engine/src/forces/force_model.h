// The forces on every body, as accelerations: gravity, springs, damping, quadratic drag and
// mutual gravitation. Internal to the engine; integrators evaluate it at their stages.
#pragma once

#include <cstdint>
#include <span>

#include <memory>

#include "body_geometry.h"
#include "engine/body.h"
#include "engine/contact.h"
#include "forces/springs.h"
#include "wakefulness.h"
#include "engine/world_def.h"

namespace engine::detail {

struct ForceModel {
 public:
  const WorldDef& def;
  std::span<const BodyInfo> infos;
  std::span<const Spring> springs;    ///< the springs that act (stiffness or damping not 0)
  std::span<const std::uint8_t> moving;  ///< per body, a Wakefulness: forces act on kAwake ones
  /// The embedder's forces and torques for this step: one per body, or empty when there are none.
  std::span<const Vec2> applied_forces;
  std::span<const double> applied_torques;
  bool rotation;                         ///< torques turn into angular acceleration
  bool damping;                          ///< some body has linear or angular damping
  /// Per body slot, 0 for a disabled body or a free slot (which pull nothing); empty: all enabled.
  std::span<const std::uint8_t> enabled = {};
  /// Per body slot, the pieces of a body made of parts (their width is what drag pushes on).
  std::span<const std::shared_ptr<const BodyGeometry>> geometries = {};

  /// Linear and angular acceleration of every body in `states` (zero for bodies not awake).
  void Evaluate(std::span<const BodyState> states, std::span<Vec2> linear,
                std::span<double> angular) const;

  /// Whether any force besides gravity acts (damping, drag, springs, gravitation).
  bool BeyondGravity() const {
    return damping || !springs.empty() || def.fluid_density != 0.0 || def.gravitational_constant != 0.0 ||
           !applied_forces.empty();
  }

  /// How fast damping and drag take a body's velocity away, 1/s: its linear acceleration from
  /// them is −rate·v.
  double DragRate(const BodyState& state, std::size_t body) const;

 private:
  double QuadraticDragRate(const BodyState& state, std::size_t body) const;
};

}  // namespace engine::detail
