// World's shape cast: a circle or box moving without turning, against every body it may meet
// (queries/cast.h). A body it starts overlapping is met at once.
#include "queries/cast.h"
#include "queries/query.h"
#include "world_impl.h"

namespace engine {

std::optional<RayHit> World::ShapeCast(const Shape& shape, Vec2 position, double angle, Vec2 translation,
                                       const std::optional<Filter>& filter) const {
  detail::RequireQueryShape(shape, position, angle, "ShapeCast: the shape needs a positive finite size and a finite placement");
  detail::Require(IsFinite(translation), "ShapeCast: the translation must be finite");
  const detail::Cast cast{shape, position, angle, translation, true};
  return detail::FirstHit(impl_->bodies, cast, filter);
}

}  // namespace engine
