// Force generators, each a short loop; the ones a scene does not use cost nothing.
#include "forces/force_model.h"

#include <cmath>

namespace engine::detail {

namespace {

// The length of a body's outline seen along `direction` (unit), m: what a 2D fluid pushes on.
double ProjectedLength(const BodyInfo& info, const BodyGeometry* geometry, const BodyState& state, Vec2 direction) {
  if (info.shape.type == ShapeType::kCircle) return 2.0 * info.shape.radius;
  if (geometry) return PiecesWidth(*geometry, state, direction);
  const double angle = state.angle;
  const Vec2 across = InvRotate(MakeRot(angle), LeftPerp(direction));
  return 2.0 * (std::abs(across.x) * info.shape.half_extents.x + std::abs(across.y) * info.shape.half_extents.y);
}

}  // namespace

// F = −½·ρ·C_d·L·|v|·v (per metre of depth), the drag of a body much faster than creep, as the
// rate ½·ρ·C_d·L·|v| / m that multiplies −v.
double ForceModel::QuadraticDragRate(const BodyState& s, std::size_t body) const {
  const BodyInfo& info = infos[body];
  const double speed = Length(s.velocity);
  if (speed == 0.0) return 0.0;
  const BodyGeometry* geometry = geometries.empty() ? nullptr : geometries[body].get();
  const double length = ProjectedLength(info, geometry, s, s.velocity / speed);
  const double c = 0.5 * def.fluid_density * info.drag_coefficient * length;
  return c * speed * info.inv_mass;
}

double ForceModel::DragRate(const BodyState& state, std::size_t body) const {
  const BodyInfo& info = infos[body];
  double rate = info.linear_damping;
  if (def.fluid_density != 0.0) rate += QuadraticDragRate(state, body);
  return rate;
}

void ForceModel::Evaluate(std::span<const BodyState> states, std::span<Vec2> linear,
                          std::span<double> angular) const {
  const std::size_t n = states.size();
  for (std::size_t i = 0; i < n; ++i) {
    linear[i] = moving[i] == kAwake ? def.gravity : Vec2{};
    angular[i] = 0.0;
  }

  for (std::size_t i = 0; i < n && (damping || def.fluid_density != 0.0); ++i) {
    if (moving[i] != kAwake) continue;
    const BodyInfo& info = infos[i];
    const BodyState& s = states[i];
    if (info.linear_damping != 0.0) linear[i] -= info.linear_damping * s.velocity;
    if (rotation && info.angular_damping != 0.0) angular[i] -= info.angular_damping * s.angular_velocity;
    if (def.fluid_density != 0.0) linear[i] -= QuadraticDragRate(s, i) * s.velocity;
  }

  for (std::size_t i = 0; i < applied_forces.size(); ++i) {
    if (moving[i] != kAwake) continue;
    linear[i] += infos[i].inv_mass * applied_forces[i];
    if (rotation) angular[i] += infos[i].inv_inertia * applied_torques[i];
  }

  if (def.gravitational_constant != 0.0) {
    // Every pair of dynamic bodies, in id order: a_i += G·m_j·(r_j − r_i)/|r|³. Disabled
    // bodies and free slots pull nothing.
    auto pulls = [&](std::size_t i) { return !infos[i].is_static && (enabled.empty() || enabled[i]); };
    for (std::size_t i = 0; i < n; ++i) {
      if (!pulls(i)) continue;
      for (std::size_t j = i + 1; j < n; ++j) {
        if (!pulls(j)) continue;
        const Vec2 d = states[j].position - states[i].position;
        const double r2 = LengthSquared(d);
        if (r2 == 0.0) continue;
        const Vec2 pull = (def.gravitational_constant / (r2 * std::sqrt(r2))) * d;
        if (moving[i] == kAwake) linear[i] += infos[j].mass * pull;
        if (moving[j] == kAwake) linear[j] -= infos[i].mass * pull;
      }
    }
  }

  for (const Spring& spring : springs) {
    const BodyState& a = states[spring.body_a];
    const Vec2 ra = Rotate(MakeRot(a.angle), spring.local_a);
    const Vec2 pa = a.position + ra;
    const Vec2 va = a.velocity + Cross(a.angular_velocity, ra);
    Vec2 pb = spring.local_b, vb, rb;
    if (spring.body_b) {
      const BodyState& b = states[*spring.body_b];
      rb = Rotate(MakeRot(b.angle), spring.local_b);
      pb = b.position + rb;
      vb = b.velocity + Cross(b.angular_velocity, rb);
    }
    const Vec2 d = pb - pa;
    const double length = Length(d);
    if (length == 0.0) continue;  // no direction to pull in
    const Vec2 dir = d / length;
    // Positive tension pulls A towards B and B towards A.
    const double tension = spring.stiffness * (length - spring.rest_length) + spring.damping * Dot(vb - va, dir);
    const Vec2 force = tension * dir;
    const BodyInfo& ia = infos[spring.body_a];
    if (moving[spring.body_a] == kAwake) {
      linear[spring.body_a] += ia.inv_mass * force;
      angular[spring.body_a] += ia.inv_inertia * Cross(ra, force);
    }
    if (spring.body_b && moving[*spring.body_b] == kAwake) {
      const BodyInfo& ib = infos[*spring.body_b];
      linear[*spring.body_b] -= ib.inv_mass * force;
      angular[*spring.body_b] -= ib.inv_inertia * Cross(rb, force);
    }
  }
}

}  // namespace engine::detail
