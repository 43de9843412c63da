// The world's springs, by body slot. Internal to the engine.
#pragma once

#include <optional>
#include <vector>

#include "engine/ids.h"
#include "engine/math.h"
#include "engine/spring.h"

namespace engine::detail {

/// A SpringDef with its bodies' ids turned into slots.
struct Spring {
  BodyIndex body_a = 0;
  Vec2 local_a;
  std::optional<BodyIndex> body_b;
  Vec2 local_b;
  double rest_length = 0.0;
  double stiffness = 0.0;
  double damping = 0.0;
};

struct Springs {
  std::vector<SpringDef> all;  ///< as added, minus those of destroyed bodies
  /// The springs that pull at all (stiffness or damping not 0) between enabled bodies, in the
  /// order added: the only ones the force evaluations, waking and sleep see, so a spring with
  /// nothing to pull costs nothing.
  std::vector<Spring> acting;
};

}  // namespace engine::detail
