// World's overlap queries: bounding boxes against a box, and shapes against a shape by the
// narrow phase's own test (touching counts, as it does for sensors).
#include "candidate_pairs.h"
#include "narrow_phase/narrow_phase.h"
#include "queries/query.h"
#include "world_impl.h"

namespace engine {

namespace {

// The radius of the circle about a shape's centre that holds it, m.
double OuterRadius(const Shape& shape) {
  return shape.type == ShapeType::kCircle ? shape.radius : Length(shape.half_extents);
}

}  // namespace

std::vector<BodyId> World::OverlapAABB(const AABB& box, const std::optional<Filter>& filter) const {
  detail::Require(box.lower.x <= box.upper.x && box.lower.y <= box.upper.y,
                  "OverlapAABB: the box's lower corner must not lie beyond its upper one");
  const detail::Bodies& bodies = impl_->bodies;
  std::vector<BodyId> found;
  for (BodyIndex slot = 0; slot < bodies.states.size(); ++slot) {
    if (!detail::IsQueried(bodies, slot, filter)) continue;
    if (Overlaps(detail::BoundsOf(bodies, slot), box)) {
      found.push_back(bodies.IdOf(slot));
    }
  }
  return found;
}

std::vector<BodyId> World::OverlapShape(const Shape& shape, Vec2 position, double angle,
                                        const std::optional<Filter>& filter) const {
  detail::RequireQueryShape(shape, position, angle,
                            "OverlapShape: the shape needs a positive finite size and a finite placement");
  const detail::Bodies& bodies = impl_->bodies;
  BodyInfo query_info;
  query_info.shape = shape;
  const BodyState query{position, {}, angle, 0.0};
  std::vector<BodyId> found;
  for (BodyIndex slot = 0; slot < bodies.states.size(); ++slot) {
    if (!detail::IsQueried(bodies, slot, filter)) continue;
    const BodyInfo& info = bodies.infos[slot];
    const BodyState& state = bodies.states[slot];
    // Far bodies are passed over by their outer circles, without turning anything; the reach is
    // grown a little so that rounding never passes over one that only just touches.
    const detail::BodyGeometry* geometry = bodies.geometries[slot].get();
    const double outer = geometry ? geometry->reach : OuterRadius(info.shape);
    const double reach = (OuterRadius(shape) + outer) * (1.0 + 1e-9);
    if (LengthSquared(state.position - position) > reach * reach) continue;
    if (detail::ShapesOverlap(query_info, query, nullptr, info, state, geometry)) found.push_back(bodies.IdOf(slot));
  }
  return found;
}

}  // namespace engine
