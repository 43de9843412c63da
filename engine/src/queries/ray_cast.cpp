// World's ray casts: a ray is a circle of radius 0 cast from its start to its end
// (queries/cast.h), and a body it starts inside is not entered.
#include "queries/cast.h"
#include "require.h"
#include "world_impl.h"

namespace engine {

std::optional<RayHit> World::RayCast(Vec2 from, Vec2 to, const std::optional<Filter>& filter) const {
  detail::Require(IsFinite(from) && IsFinite(to), "RayCast: the ray's ends must be finite");
  return detail::FirstHit(impl_->bodies, detail::Ray(from, to), filter);
}

std::vector<RayHit> World::RayCastAll(Vec2 from, Vec2 to, const std::optional<Filter>& filter) const {
  detail::Require(IsFinite(from) && IsFinite(to), "RayCastAll: the ray's ends must be finite");
  return detail::AllHits(impl_->bodies, detail::Ray(from, to), filter);
}

}  // namespace engine
