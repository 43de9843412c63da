// Body ids in test messages ("{3, 1}": slot 3, generation 1), so CHECK(a == b) and INFO(id) print.
#pragma once

#include <ostream>

#include "engine/ids.h"

namespace engine {

inline std::ostream& operator<<(std::ostream& out, BodyId id) {
  return out << '{' << id.index << ", " << id.generation << '}';
}

}  // namespace engine
