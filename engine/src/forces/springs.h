// The world's springs. Internal to the engine.
#pragma once

#include <vector>

#include "engine/spring.h"

namespace engine::detail {

struct Springs {
  std::vector<SpringDef> all;
  /// The springs that pull at all (stiffness or damping not 0), in the order added: the only ones
  /// the force evaluations, waking and sleep see, so a spring with nothing to pull costs nothing.
  std::vector<SpringDef> acting;
};

}  // namespace engine::detail
