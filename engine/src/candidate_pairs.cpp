// Speculative margins, the pair budget's quotas, and the broad phase over the grown bounds.
#include "candidate_pairs.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "store_whole.h"

namespace engine::detail {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Moving farther than this fraction of its size in one step makes a body fast (Box2D's default
// safety factor is the same half).
constexpr double kFastFraction = 0.5;

// The pair budget (PairCollector, docs/limits.md): a body keeps every pair charged to it, that
// is every pair with a body at least as wide as itself, up to its quota. Solid circles or
// squares of one size can give a body at most 8 such pairs (a 3 by 3 block: the diagonal ones
// through the bounding boxes), so 16 is twice what they need; squares turned 45° meet 12, but
// their bounding boxes have twice their area, which doubles the quota (below). A box also
// carries up to two bodies at least as wide per unit of its aspect along each long side: 4 more
// per unit of aspect, up to PairQuota::kMaxQuota. The collector grows the quota with the box the
// broad phase is given, grown by the speculative margin or turned (PairQuota::area).
constexpr double kPairQuota = 16;
constexpr double kPairQuotaPerAspect = 4;

// Fewer bodies than this have their bounds found on one thread.
constexpr std::uint32_t kMinSharedBounds = 2048;

// How far a body may reach within a step, m: contacts within it are speculative. `fall`: how
// far gravity alone carries a body in the step, |g|·dt·dt (found once a step, not per body).
double SpeculativeMargin(const WorldDef& def, double fall, const BodyState& state, const BodyInfo& info,
                         const BodyGeometry* geometry, bool awake) {
  const double speculative = 0.5 * kSpeculativeSlops * def.linear_slop;
  if (!awake) return speculative;
  // The farthest a body can travel in this step under gravity, and then some; a turning body's
  // outline also sweeps |ω|·r. Contacts within that reach are speculative: the solver lets the
  // bodies close the gap and no more, at any speed (continuous collision, Catto's speculative
  // contacts), and the impact pass places the bounce at the moment of impact.
  const double dt = def.dt;
  const Shape& shape = info.shape;
  const double motion = Length(state.velocity) * dt + fall;
  const double outer = shape.type == ShapeType::kCircle ? shape.radius
                       : shape.type == ShapeType::kBox  ? Length(shape.half_extents)
                                                        : geometry->reach;
  const double turning = info.inv_inertia != 0.0 ? std::abs(state.angular_velocity) * outer * dt : 0.0;
  // A body moving farther in a step than half its size is fast. With continuous collision off
  // (and the body no bullet) a fast body is tested only where it is, as a discrete engine does:
  // it may tunnel. Slow bodies are the same either way, so a scene without fast bodies does
  // not change at all.
  const double size = shape.type == ShapeType::kCircle ? 2.0 * shape.radius
                      : shape.type == ShapeType::kBox  ? 2.0 * std::min(shape.half_extents.x, shape.half_extents.y)
                                                       : geometry->thickness;
  const bool fast = motion + turning > kFastFraction * size;
  if (fast && !def.continuous && !info.bullet) return speculative;
  double margin = motion + speculative;
  if (info.inv_inertia != 0.0) margin += turning;
  return margin;
}

}  // namespace

namespace {

// A circle's bounds, or an unturned box's.
AABB UnturnedBounds(const Shape& shape, Vec2 centre) {
  const Vec2 half = shape.type == ShapeType::kCircle ? Vec2{shape.radius, shape.radius} : shape.half_extents;
  return {centre - half, centre + half};
}

}  // namespace

AABB BodyBounds(const Shape& shape, const BodyState& state) {
  if (shape.type == ShapeType::kBox && state.angle != 0.0) {
    return TurnedBoxBounds(state.position, shape.half_extents, MakeRot(state.angle));
  }
  return UnturnedBounds(shape, state.position);
}

PairQuota QuotaOf(const Shape& shape, bool is_static) {
  constexpr double kMax = PairQuota::kMaxQuota;
  if (shape.type == ShapeType::kCircle) {
    const double d = 2.0 * shape.radius;
    return {is_static ? kInfinity : d, static_cast<std::uint32_t>(kPairQuota), d * d};
  }
  const Vec2 h = shape.half_extents;
  const double aspect = std::max(h.x, h.y) / std::min(h.x, h.y);
  const double quota = std::min(kMax, kPairQuota + kPairQuotaPerAspect * std::ceil(aspect - 1.0));
  return {is_static ? kInfinity : 2.0 * std::min(h.x, h.y), static_cast<std::uint32_t>(quota), 4.0 * h.x * h.y};
}

Shape QuotaShape(const Bodies& bodies, BodyIndex index) {
  const BodyGeometry* geometry = bodies.geometries[index].get();
  if (!geometry) return bodies.infos[index].shape;
  constexpr double kLeast = 0.0005;
  Shape box;
  box.type = ShapeType::kBox;
  box.half_extents = {std::max(kLeast, geometry->half_size.x), std::max(kLeast, geometry->half_size.y)};
  return box;
}

void CandidatePairs::Find(const WorldDef& def, bool speculative, const Bodies& bodies,
                          std::span<const std::uint8_t> awake, WorkerPool& pool) {
  const std::size_t n = bodies.states.size();
  bounds_.resize(n);
  margins_.resize(n);
  box_turns_.resize(n);
  const bool parts = bodies.with_parts > 0;
  const double fall = Length(def.gravity) * def.dt * def.dt;
  pool.ParallelFor(static_cast<std::uint32_t>(n), kMinSharedBounds, [&](BodyIndex id) {
    const BodyGeometry* geometry = parts ? bodies.geometries[id].get() : nullptr;
    const BodyInfo& info = bodies.infos[id];
    const BodyState& state = bodies.states[id];
    margins_[id] = speculative ? SpeculativeMargin(def, fall, state, info, geometry, awake[id] != 0) : 0.0;
    const Vec2 grow{margins_[id], margins_[id]};
    AABB b;
    if (!IsSimpleShape(info.shape.type)) {
      b = PiecesBounds(*bodies.geometries[id], state);
    } else if (info.shape.type == ShapeType::kBox && state.angle != 0.0) {
      StoreRot(&box_turns_[id], state.angle);  // kept for the narrow phase
      b = TurnedBoxBounds(state.position, info.shape.half_extents, box_turns_[id]);
    } else {
      // An unturned box's turn is MakeRot's answer at ±0, made without the call.
      if (info.shape.type == ShapeType::kBox) box_turns_[id] = Rot{1.0, state.angle};
      b = UnturnedBounds(info.shape, state.position);
    }
    bounds_[id] = {b.lower - grow, b.upper + grow};
  });
  // The pair budget bounds what bodies piled up cost; elsewhere every pair is kept.
  const auto quotas = def.pair_budget ? std::span<const PairQuota>(quotas_) : std::span<const PairQuota>();
  packed_ = bodies.inactive != 0;
  if (!packed_) {
    broad_phase_.FindPairs(def.broad_phase, bounds_, &pairs_, quotas, &pool);
  } else {
    FindAmongEnabled(def, bodies.enabled, quotas, pool);
  }
  if (bodies.filtered > 0) {
    std::erase_if(pairs_, [&](BodyPair p) { return !ShouldCollide(bodies.filters[p.a], bodies.filters[p.b]); });
  }
  // A moving kinematic body meets static and kinematic bodies with nothing to solve (neither
  // has mass): no contact, unless a sensor wants to see it. (Static pairs, resting, drop out
  // with the sleepers.)
  if (bodies.kinematic > 0) {
    std::erase_if(pairs_, [&](BodyPair p) {
      const BodyInfo& a = bodies.infos[p.a];
      const BodyInfo& b = bodies.infos[p.b];
      return HasInfiniteMass(a) && HasInfiniteMass(b) && !a.is_sensor && !b.is_sensor;
    });
  }
}

void CandidatePairs::FindAmongEnabled(const WorldDef& def, std::span<const std::uint8_t> enabled,
                                      std::span<const PairQuota> quotas, WorkerPool& pool) {
  packed_slots_.clear();
  packed_bounds_.clear();
  packed_quotas_.clear();
  for (BodyIndex id = 0; id < enabled.size(); ++id) {
    if (!enabled[id]) continue;
    packed_slots_.push_back(id);
    packed_bounds_.push_back(bounds_[id]);
    if (!quotas.empty()) packed_quotas_.push_back(quotas[id]);
  }
  broad_phase_.FindPairs(def.broad_phase, packed_bounds_, &pairs_, packed_quotas_, &pool);
  // Slots grow with the packed index, so the pairs stay sorted.
  for (BodyPair& p : pairs_) p = {packed_slots_[p.a], packed_slots_[p.b]};
}

}  // namespace engine::detail
