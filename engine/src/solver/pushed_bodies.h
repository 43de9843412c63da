// Which bodies a contact pushed this (sub)step: the integrators move those by h·v exactly
// (MoveBodies). Internal to the engine.
#pragma once

#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

#include "engine/world_def.h"
#include "solver/substep_constraint.h"

namespace engine::detail {

/// Sets `pushed` to 1 for both bodies of every constraint with a positive normal impulse; leaves
/// it empty for semi-implicit Euler, which moves every body by h·v anyway.
template <typename Constraint>
void MarkPushed(std::span<const Constraint> constraints, Integrator integrator, std::size_t body_count,
                std::vector<std::uint8_t>* pushed) {
  pushed->clear();
  if (integrator == Integrator::kSemiImplicitEuler) return;
  pushed->assign(body_count, 0);
  for (const Constraint& c : constraints) {
    if constexpr (std::is_same_v<Constraint, LinearConstraint>) {
      if (c.normal_impulse > 0.0) (*pushed)[c.a] = (*pushed)[c.b] = 1;
    } else {
      for (int k = 0; k < c.point_count; ++k) {
        if (c.points[k].normal_impulse > 0.0) (*pushed)[c.a] = (*pushed)[c.b] = 1;
      }
    }
  }
}

}  // namespace engine::detail
