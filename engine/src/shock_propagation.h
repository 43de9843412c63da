// Shock propagation (Guendelman, Bridson and Fedkiw, "Nonconvex Rigid Bodies with Stacking",
// SIGGRAPH 2003): contacts visited from the ground up with the lower body held fixed, so that a
// stack cannot sink whatever its mass ratios. Internal to the engine.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "engine/world.h"
#include "substep_solver.h"

namespace engine::detail {

/// Builds each body's `level` (graph distance through contacts from a static body: static
/// bodies 0, bodies touching nothing static the highest) and the `order` of the constraints by
/// their lower level, breadth-first in body-id order.
void BuildShockOrder(std::span<const SubstepConstraint> constraints, std::span<const BodyInfo> infos,
                     std::vector<std::uint32_t>* level, std::vector<std::uint32_t>* order);

/// One pass in that order over the supporting contacts (normal within 45° of `up`, the unit
/// vector against gravity): no contact within the slop may approach faster than its gap allows
/// this substep; the lower body of a pair is held fixed, bodies on one level share the impulse
/// by mass. Leaves the accumulated impulses alone: this pass only keeps stacks from sinking, so
/// it acts only where a pair approaches faster than allowed by more than `tolerance` (m/s).
void PropagateShock(std::span<const std::uint32_t> level, std::span<const std::uint32_t> order,
                    std::span<const SubstepConstraint> constraints, std::span<BodyState> states,
                    const StepStart& start, double inv_h, double linear_slop, Vec2 up,
                    double tolerance);

}  // namespace engine::detail
