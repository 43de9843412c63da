// What the world answers about itself between steps.
#pragma once

#include "engine/ids.h"
#include "engine/math.h"

namespace engine {

/// Where a ray, or a shape cast along a translation, first meets a body.
struct RayHit {
  BodyId body;
  Vec2 point;       ///< on the body's outline
  Vec2 normal;      ///< the outline's outward normal there (towards the cast shape)
  double fraction;  ///< of the way from the ray's start to its end (of the translation), in [0, 1]
};

}  // namespace engine
