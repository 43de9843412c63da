// What the world answers about itself between steps.
#pragma once

#include "engine/ids.h"
#include "engine/math.h"

namespace engine {

/// Where a ray first meets a body.
struct RayHit {
  BodyId body;
  Vec2 point;       ///< on the body's outline
  Vec2 normal;      ///< the outline's outward normal there
  double fraction;  ///< of the way from the ray's start to its end, in [0, 1]
};

}  // namespace engine
