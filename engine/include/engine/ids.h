// The ids the API hands out.
#pragma once

#include <cstdint>

namespace engine {

/// A body's index in creation (scene) order.
using BodyId = std::uint32_t;

}  // namespace engine
