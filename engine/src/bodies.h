// The bodies' storage: what every step writes, what it only reads, and counts the step's skips
// read. Indexed by BodyId (scene order). Internal to the engine.
#pragma once

#include <cstddef>
#include <vector>

#include "engine/body.h"

namespace engine::detail {

struct Bodies {
  std::vector<BodyState> states;
  std::vector<BodyInfo> infos;
  std::vector<Vec2> start_positions;  ///< each body's centre when the current step began
  std::size_t damped = 0;             ///< bodies with linear or angular damping
  std::size_t turnable = 0;           ///< bodies free to turn (finite inertia)

  void MarkStepStart() {
    start_positions.resize(states.size());
    for (std::size_t i = 0; i < states.size(); ++i) start_positions[i] = states[i].position;
  }
};

/// kg: the given mass, or density × area.
double BodyMass(const BodyDef& def);

/// What a step reads of a body made from `def` (preconditions checked): mass and inertia from
/// the shape, infinite inertia (0 inverse) without rotation.
BodyInfo MakeBodyInfo(const BodyDef& def, bool rotation);

}  // namespace engine::detail
