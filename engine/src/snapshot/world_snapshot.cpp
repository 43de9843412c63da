// Snapshots: the world's state written field by field in little-endian order, and read back
// with every count, index and order checked, so that no snapshot, however corrupt, leads to
// undefined behaviour. Layout and sizes: docs/embedding.md ("Snapshots").
#include <algorithm>
#include <bit>
#include <cmath>

#include "engine/world.h"
#include "world_impl.h"

namespace engine {

namespace {

using detail::ByteReader;
using detail::ByteWriter;
using detail::BodyGeometry;

constexpr std::uint32_t kMagic = 0x31584242;  // "BBX1"
constexpr std::uint32_t kVersion = 1;
constexpr std::uint64_t kFnvOffset = 0xcbf29ce484222325ULL;
constexpr std::uint64_t kFnvPrime = 0x100000001b3ULL;

enum SlotFlags : std::uint8_t { kAlive = 1, kEnabled = 2, kFiltered = 4, kUserData = 8, kForced = 16 };
enum InfoFlags : std::uint8_t { kStatic = 1, kKinematic = 2, kSensor = 4, kFixedRotation = 8, kBullet = 16 };

std::uint64_t Fnv(std::span<const std::uint8_t> bytes) {
  std::uint64_t hash = kFnvOffset;
  for (const std::uint8_t b : bytes) hash = (hash ^ b) * kFnvPrime;
  return hash;
}

// Every setting that changes how the world steps, so a snapshot restores only into a world that
// steps the same way.
std::uint64_t Fingerprint(const WorldDef& def) {
  std::vector<std::uint8_t> bytes;
  ByteWriter w(&bytes);
  for (const double v : {def.gravity.x, def.gravity.y, def.fluid_density, def.gravitational_constant, def.dt,
                         def.max_push_out_speed, def.restitution_threshold, def.linear_slop,
                         def.position_correction, def.sleep_speed, def.time_to_sleep, def.hit_speed}) {
    w.F64(v);
  }
  for (const int v : {static_cast<int>(def.integrator), static_cast<int>(def.broad_phase),
                      static_cast<int>(def.solver), def.substeps, def.velocity_iterations,
                      def.circle_velocity_iterations}) {
    w.U32(static_cast<std::uint32_t>(v));
  }
  const SubstepFeatures& f = def.substep_features;
  for (const bool v : {def.rotation, def.sleeping, def.continuous, def.pair_budget, def.contact_events,
                       f.impact_pass, f.shock_propagation, f.direct_solve, f.energy_limit, f.block_solver,
                       f.colour_order}) {
    w.U8(v ? 1 : 0);
  }
  return Fnv(bytes);
}

void WriteId(ByteWriter& out, BodyId id) {
  out.U32(id.index);
  out.U32(id.generation);
}

BodyId ReadId(ByteReader& in) {
  const BodyIndex index = in.U32();
  return {index, in.U32()};
}

void WriteOptional(ByteWriter& out, const std::optional<double>& v) {
  out.U8(v ? 1 : 0);
  if (v) out.F64(*v);
}

std::optional<double> ReadOptional(ByteReader& in) {
  if (!in.U8()) return std::nullopt;
  return in.F64();
}

// A joint slot: its definition, its frames and the impulses it carries.
void WriteJoint(ByteWriter& out, const detail::Joint& j) {
  const JointDef& d = j.def;
  out.U8(static_cast<std::uint8_t>(d.type));
  WriteId(out, d.body_a);
  WriteId(out, d.body_b);
  for (const Vec2 v : {d.anchor, d.anchor_b, d.axis, d.target, j.local_a, j.local_b, j.local_axis}) WriteVec(out, v);
  out.U8(d.collide ? 1 : 0);
  out.U8(d.limits ? 1 : 0);
  if (d.limits) out.F64(d.limits->lower), out.F64(d.limits->upper);
  out.U8(d.motor ? 1 : 0);
  if (d.motor) out.F64(d.motor->speed), out.F64(d.motor->max_force);
  out.U8(d.spring ? 1 : 0);
  if (d.spring) out.F64(d.spring->hertz), out.F64(d.spring->damping_ratio);
  for (const std::optional<double>& v : {d.length, d.min_length, d.max_length}) WriteOptional(out, v);
  out.F64(d.max_force);
  out.U8(j.rigid_length ? 1 : 0);
  const detail::JointImpulses& p = j.impulses;
  WriteVec(out, p.point);
  for (const double v : {j.reference_angle, j.length, j.min_length, j.max_length, p.angle, p.axial, p.lower,
                         p.upper, p.motor}) {
    out.F64(v);
  }
}

bool ReadJoint(ByteReader& in, const detail::Bodies& bodies, detail::Joint* j) {
  JointDef& d = j->def;
  const std::uint8_t type = in.U8();
  if (!in.Check(type <= static_cast<std::uint8_t>(JointType::kTarget))) return false;
  d.type = static_cast<JointType>(type);
  d.body_a = ReadId(in);
  d.body_b = ReadId(in);
  for (Vec2* v : {&d.anchor, &d.anchor_b, &d.axis, &d.target, &j->local_a, &j->local_b, &j->local_axis}) {
    *v = ReadVec(in);
  }
  d.collide = in.U8() != 0;
  if (in.U8()) d.limits = JointLimits{in.F64(), in.F64()};
  if (in.U8()) d.motor = JointMotor{in.F64(), in.F64()};
  if (in.U8()) d.spring = JointSpring{in.F64(), in.F64()};
  for (std::optional<double>* v : {&d.length, &d.min_length, &d.max_length}) *v = ReadOptional(in);
  d.max_force = in.F64();
  j->rigid_length = in.U8() != 0;
  detail::JointImpulses& p = j->impulses;
  p.point = ReadVec(in);
  for (double* v : {&j->reference_angle, &j->length, &j->min_length, &j->max_length, &p.angle, &p.axial,
                    &p.lower, &p.upper, &p.motor}) {
    *v = in.F64();
  }
  const bool target = d.type == JointType::kTarget;
  if (!in.Check(bodies.IsLive(d.body_b) && (target || (bodies.IsLive(d.body_a) && d.body_a != d.body_b)))) {
    return false;
  }
  j->b = d.body_b.index;
  j->a = target ? kNoBody : d.body_a.index;
  return true;
}

void WritePairs(ByteWriter& out, std::span<const BodyPair> pairs) {
  out.U32(static_cast<std::uint32_t>(pairs.size()));
  for (const BodyPair p : pairs) out.U32(p.a), out.U32(p.b);
}

// Pairs of live slots, strictly ascending (the merges that read them rely on the order).
bool ReadPairs(ByteReader& in, const detail::Bodies& bodies, std::vector<BodyPair>* pairs) {
  const std::uint32_t n = in.Count(8);
  pairs->clear();
  for (std::uint32_t i = 0; i < n && in.Ok(); ++i) {
    const BodyPair p{in.U32(), in.U32()};
    in.Check(p.a < p.b && p.b < bodies.alive.size() && bodies.alive[p.a] && bodies.alive[p.b] &&
             (pairs->empty() || pairs->back() < p));
    pairs->push_back(p);
  }
  return in.Ok();
}

void WriteInfo(ByteWriter& out, const BodyInfo& info) {
  out.U8(static_cast<std::uint8_t>(info.shape.type));
  out.F64(info.shape.radius);
  WriteVec(out, info.shape.half_extents);
  for (const double v : {info.mass, info.inv_mass, info.inertia, info.inv_inertia, info.linear_damping,
                         info.angular_damping, info.drag_coefficient, info.restitution, info.friction}) {
    out.F64(v);
  }
  out.U8(static_cast<std::uint8_t>((info.is_static ? kStatic : 0) | (info.is_kinematic ? kKinematic : 0) |
                                   (info.is_sensor ? kSensor : 0) | (info.fixed_rotation ? kFixedRotation : 0) |
                                   (info.bullet ? kBullet : 0)));
}

// The mass properties MakeBodyInfo gives a body of this kind in a world with or without
// rotation: anything else would break the solvers' assumptions (a body that turns in a world
// that tracks no turning, a static body with mass).
bool ConsistentMass(const BodyInfo& info, bool rotation) {
  if (HasInfiniteMass(info)) return info.mass == 0.0 && info.inv_mass == 0.0 && info.inertia == 0.0 && info.inv_inertia == 0.0;
  const bool turns = rotation && !info.fixed_rotation;
  return info.mass > 0.0 && info.inv_mass == 1.0 / info.mass && info.inertia > 0.0 &&
         info.inv_inertia == (turns ? 1.0 / info.inertia : 0.0);
}

bool ReadInfo(ByteReader& in, bool rotation, BodyInfo* info) {
  const std::uint8_t type = in.U8();
  in.Check(type <= static_cast<std::uint8_t>(ShapeType::kCompound));
  info->shape.type = static_cast<ShapeType>(type);
  info->shape.radius = in.F64();
  info->shape.half_extents = ReadVec(in);
  double* fields[] = {&info->mass, &info->inv_mass, &info->inertia, &info->inv_inertia, &info->linear_damping,
                      &info->angular_damping, &info->drag_coefficient, &info->restitution, &info->friction};
  for (double* v : fields) {
    *v = in.F64();
    in.Check(std::isfinite(*v) && *v >= 0.0);
  }
  const std::uint8_t flags = in.U8();
  info->is_static = flags & kStatic;
  info->is_kinematic = flags & kKinematic;
  info->is_sensor = flags & kSensor;
  info->fixed_rotation = flags & kFixedRotation;
  info->bullet = flags & kBullet;
  const Shape& s = info->shape;
  // A body made of parts has its size in them (ReadParts).
  const bool sized = s.type == ShapeType::kCircle ? std::isfinite(s.radius) && s.radius > 0.0
                     : s.type == ShapeType::kBox  ? IsFinite(s.half_extents) && s.half_extents.x > 0.0 &&
                                                       s.half_extents.y > 0.0
                                                  : true;
  return in.Check(sized && flags < 32 && !(info->is_static && info->is_kinematic) && ConsistentMass(*info, rotation));
}

// A body's parts, as the body was made with them: enough to build its geometry again.
void WriteParts(ByteWriter& out, const BodyGeometry& g) {
  out.F64(g.density);
  out.F64(g.friction);
  out.F64(g.restitution);
  out.U32(static_cast<std::uint32_t>(g.parts.size()));
  for (const ShapePart& p : g.parts) {
    out.U8(static_cast<std::uint8_t>(p.type));
    out.U8(static_cast<std::uint8_t>((p.loop ? 1 : 0) | (p.density ? 2 : 0) | (p.friction ? 4 : 0) |
                                     (p.restitution ? 8 : 0)));
    out.F64(p.radius);
    WriteVec(out, p.half_extents);
    out.F64(p.length);
    WriteVec(out, p.offset);
    out.F64(p.angle);
    for (const std::optional<double>& v : {p.density, p.friction, p.restitution}) {
      if (v) out.F64(*v);
    }
    out.U32(static_cast<std::uint32_t>(p.points.size()));
    for (const Vec2 v : p.points) WriteVec(out, v);
  }
}

// The parts WriteParts wrote, each checked as CreateBody checks it, and the geometry built
// from them; null (and `in` failed) for anything CreateBody would refuse.
std::shared_ptr<const BodyGeometry> ReadParts(ByteReader& in, const BodyInfo& info) {
  BodyDef def;
  def.is_static = info.is_static;
  def.density = in.F64();
  def.friction = in.F64();
  def.restitution = in.F64();
  if (!in.Check(std::isfinite(def.density) && def.density > 0.0)) return nullptr;
  def.parts.resize(in.Count(2 + 8 + 16 + 8 + 16 + 8 + 4));
  for (ShapePart& p : def.parts) {
    const std::uint8_t type = in.U8();
    const std::uint8_t flags = in.U8();
    if (!in.Check(type <= static_cast<std::uint8_t>(ShapeType::kSegments) && flags < 16)) return nullptr;
    p.type = static_cast<ShapeType>(type);
    p.loop = flags & 1;
    p.radius = in.F64();
    p.half_extents = ReadVec(in);
    p.length = in.F64();
    p.offset = ReadVec(in);
    p.angle = in.F64();
    if (flags & 2) p.density = in.F64();
    if (flags & 4) p.friction = in.F64();
    if (flags & 8) p.restitution = in.F64();
    p.points.resize(in.Count(16));
    for (Vec2& v : p.points) v = ReadVec(in);
    if (!in.Ok() || !in.Check(!CheckShapePart(p, def.is_static))) return nullptr;
  }
  const ShapeType type = def.parts.size() == 1 ? def.parts[0].type : ShapeType::kCompound;
  if (!in.Check(!def.parts.empty() && type == info.shape.type)) return nullptr;
  auto geometry = detail::MakeBodyGeometry(def);
  if (!in.Check(HasInfiniteMass(info) || geometry->mass > 0.0)) return nullptr;
  return geometry;
}

void WriteContact(ByteWriter& out, const Contact& c) {
  out.U32(c.a);
  out.U32(c.b);
  WriteVec(out, c.manifold.normal);
  out.U8(static_cast<std::uint8_t>(c.manifold.point_count));
  for (int i = 0; i < c.manifold.point_count; ++i) {
    WriteVec(out, c.manifold.points[i].point);
    out.F64(c.manifold.points[i].depth);
    out.U8(c.manifold.points[i].id);
    out.F64(c.normal_impulse[i]);
    out.F64(c.tangent_impulse[i]);
  }
  out.F64(c.restitution);
  out.F64(c.friction);
}

bool ReadContact(ByteReader& in, Contact* c) {
  c->a = in.U32();
  c->b = in.U32();
  c->manifold.normal = ReadVec(in);
  c->manifold.point_count = in.U8();
  if (!in.Check(c->manifold.point_count >= 1 && c->manifold.point_count <= 2)) return false;
  for (int i = 0; i < c->manifold.point_count; ++i) {
    c->manifold.points[i].point = ReadVec(in);
    c->manifold.points[i].depth = in.F64();
    c->manifold.points[i].id = in.U8();
    c->normal_impulse[i] = in.F64();
    c->tangent_impulse[i] = in.F64();
  }
  c->restitution = in.F64();
  c->friction = in.F64();
  return in.Ok();
}

}  // namespace

void World::Impl::Save(ByteWriter& out) const {
  out.I64(step_count);
  out.U8(fault ? 1 : 0);
  if (fault) {
    out.I64(fault->step);
    out.U32(fault->body);
    const char* const names[] = {"position", "velocity", "angle", "angular velocity"};
    out.U8(static_cast<std::uint8_t>(std::find(std::begin(names), std::end(names), std::string_view(fault->what)) -
                                     std::begin(names)));
  }
  const std::size_t n = bodies.states.size();
  out.U32(static_cast<std::uint32_t>(n));
  for (std::size_t i = 0; i < n; ++i) {
    out.U32(bodies.generations[i]);
    const bool filtered = !(bodies.filters[i] == Filter{});
    const bool forced = bodies.forces_applied;
    out.U8(static_cast<std::uint8_t>((bodies.alive[i] ? kAlive : 0) | (bodies.enabled[i] ? kEnabled : 0) |
                                     (filtered ? kFiltered : 0) | (bodies.user_data[i] ? kUserData : 0) |
                                     (forced ? kForced : 0)));
    if (!bodies.alive[i]) continue;
    WriteInfo(out, bodies.infos[i]);
    if (bodies.geometries[i]) {
      WriteParts(out, *bodies.geometries[i]);
      const detail::Bodies::PlacedOrigin& placed = bodies.placed_origins[i];
      WriteVec(out, placed.origin);
      WriteVec(out, placed.center);
      out.F64(placed.angle);
    }
    const BodyState& s = bodies.states[i];
    for (const double v : {s.position.x, s.position.y, s.velocity.x, s.velocity.y, s.angle, s.angular_velocity}) {
      out.F64(v);
    }
    out.F64(sleep.rest_time[i]);
    out.U8(sleep.awake[i]);
    out.U32(sleep.island[i]);
    if (filtered) {
      out.U64(bodies.filters[i].category_bits);
      out.U64(bodies.filters[i].mask_bits);
      out.U32(static_cast<std::uint32_t>(bodies.filters[i].group_index));
    }
    if (bodies.user_data[i]) out.U64(bodies.user_data[i]);
    if (forced) {
      WriteVec(out, bodies.applied_forces[i]);
      out.F64(bodies.applied_torques[i]);
    }
  }
  out.U32(static_cast<std::uint32_t>(bodies.free_slots.size()));
  for (const BodyIndex slot : bodies.free_slots) out.U32(slot);
  out.U32(static_cast<std::uint32_t>(springs.all.size()));
  for (const SpringDef& s : springs.all) {
    WriteId(out, s.body_a);
    out.U8(s.body_b ? 1 : 0);
    if (s.body_b) WriteId(out, *s.body_b);
    WriteVec(out, s.local_a);
    WriteVec(out, s.local_b);
    out.F64(s.rest_length);
    out.F64(s.stiffness);
    out.F64(s.damping);
  }
  const std::vector<Contact>& contacts = narrow_phase.Contacts();
  out.U32(static_cast<std::uint32_t>(contacts.size()));
  for (const Contact& c : contacts) {
    WriteContact(out, c);
    // Which pieces touch, in worlds that have bodies of parts (others' snapshots stay as they were).
    if (bodies.with_parts > 0) {
      out.U32(c.piece_a);
      out.U32(c.piece_b);
    }
  }
  contact_events.Save(out);
  sensors.Save(out);
  out.U8(static_cast<std::uint8_t>(solver.index()));
  std::visit([&](const auto& s) { s.Save(out); }, solver);
  // Joints, then particles, last, and only in worlds that ever had them (others' snapshots stay
  // as they were); a world with particles writes its joint count even when it is 0.
  const bool particles_used = particles.EverUsed() || effects.EverUsed();
  if (joints.joints.empty() && !particles_used) return;
  out.U32(static_cast<std::uint32_t>(joints.joints.size()));
  for (std::uint32_t slot = 0; slot < joints.joints.size(); ++slot) {
    out.U32(joints.generations[slot]);
    out.U8(joints.alive[slot]);
    if (joints.alive[slot]) WriteJoint(out, joints.joints[slot]);
  }
  out.U32(static_cast<std::uint32_t>(joints.free_slots.size()));
  for (const std::uint32_t slot : joints.free_slots) out.U32(slot);
  if (!particles_used) return;
  particles.Save(out);
  effects.Save(out);
}

bool World::Impl::LoadJoints(ByteReader& in) {
  const std::uint32_t count = in.Count(5);
  if (!in.Ok()) return false;
  for (std::uint32_t slot = 0; slot < count && in.Ok(); ++slot) {
    joints.Allocate();
    joints.generations[slot] = in.U32();
    joints.alive[slot] = in.U8();
    if (!in.Check(joints.alive[slot] <= 1)) return false;
    if (joints.alive[slot] && !ReadJoint(in, bodies, &joints.joints[slot])) return false;
  }
  joints.free_slots.assign(in.Count(4), 0);
  for (std::uint32_t& slot : joints.free_slots) {
    slot = in.U32();
    in.Check(slot < count && !joints.alive[slot]);
  }
  std::vector<std::uint32_t> sorted = joints.free_slots;
  std::sort(sorted.begin(), sorted.end());
  const auto dead = static_cast<std::size_t>(std::count(joints.alive.begin(), joints.alive.end(), 0));
  if (!in.Check(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end() && sorted.size() == dead)) {
    return false;
  }
  joints.live_ids.clear();
  for (std::uint32_t slot = 0; slot < count; ++slot) {
    if (joints.alive[slot]) joints.live_ids.push_back({slot, joints.generations[slot]});
  }
  RebuildJoints();
  return true;
}

bool World::Impl::Load(ByteReader& in) {
  step_count = in.I64();
  if (in.U8()) {
    const std::int64_t step = in.I64();
    const BodyIndex body = in.U32();
    const std::uint8_t what = in.U8();
    static const char* const names[] = {"position", "velocity", "angle", "angular velocity"};
    if (!in.Check(what < 4)) return false;
    fault = NumericFault{step, body, names[what]};
  }
  const std::uint32_t n = in.Count(5);
  for (std::uint32_t i = 0; i < n && in.Ok(); ++i) {
    const std::uint32_t generation = in.U32();
    const std::uint8_t flags = in.U8();
    if (!in.Check(flags < 32 && ((flags & kAlive) || flags == 0))) return false;
    const BodyIndex index = bodies.AppendSlot();
    bodies.generations[index] = generation;
    bodies.live_ids.back().generation = generation;
    if (!(flags & kAlive)) {
      bodies.Free(index);
      --bodies.generations[index];  // Free counts a destruction; this one was counted already
      sleep.Place(index, detail::kResting, false);
      candidates.Place(index, bodies.infos[index].shape, true);
      continue;
    }
    BodyInfo& info = bodies.infos[index];
    if (!ReadInfo(in, def.rotation, &info)) return false;
    if (!IsSimpleShape(info.shape.type)) {
      bodies.geometries[index] = ReadParts(in, info);
      if (!bodies.geometries[index]) return false;
      detail::Bodies::PlacedOrigin& placed = bodies.placed_origins[index];
      placed.origin = ReadVec(in);
      placed.center = ReadVec(in);
      placed.angle = in.F64();
      if (!in.Check(IsFinite(placed.origin) && IsFinite(placed.center) && std::isfinite(placed.angle))) return false;
    }
    BodyState& s = bodies.states[index];
    double* state[] = {&s.position.x, &s.position.y, &s.velocity.x, &s.velocity.y, &s.angle, &s.angular_velocity};
    for (double* v : state) *v = in.F64();
    const double rest = in.F64();
    const std::uint8_t awake = in.U8();
    const std::uint32_t island = in.U32();
    // What each kind of body may be: static ones rest, dynamic ones sleep or wake, kinematic
    // ones rest or move; a disabled body rests.
    const std::uint8_t most = !(flags & kEnabled) || info.is_static ? detail::kResting
                              : info.is_kinematic                   ? detail::kKinematicMoving
                                                                    : detail::kAwake;
    // A disabled body is in no island (so no waking reaches it), as SetEnabled leaves it.
    const bool island_ok = (flags & kEnabled) ? island < n : island == kNoBody;
    in.Check((awake == detail::kResting || awake == most) && island_ok && std::isfinite(rest) &&
             (fault || (IsFinite(s.position) && IsFinite(s.velocity) && std::isfinite(s.angle) &&
                        std::isfinite(s.angular_velocity))));
    bodies.enabled[index] = (flags & kEnabled) ? 1 : 0;
    if (flags & kFiltered) {
      bodies.filters[index].category_bits = in.U64();
      bodies.filters[index].mask_bits = in.U64();
      bodies.filters[index].group_index = static_cast<std::int32_t>(in.U32());
    }
    if (flags & kUserData) bodies.user_data[index] = in.U64();
    if (flags & kForced) {
      bodies.applied_forces[index] = ReadVec(in);
      bodies.applied_torques[index] = in.F64();
      bodies.forces_applied = true;
    }
    bodies.Count(index, +1);
    sleep.Place(index, detail::kResting, true);
    sleep.rest_time[index] = rest;
    sleep.awake[index] = awake;
    sleep.island[index] = island;
    candidates.Place(index, detail::QuotaShape(bodies, index), info.is_static);
  }
  // The free list, in its order: the next bodies created take the same slots.
  bodies.free_slots.assign(in.Count(4), 0);
  for (BodyIndex& slot : bodies.free_slots) {
    slot = in.U32();
    in.Check(slot < n && !bodies.alive[slot]);
  }
  std::vector<BodyIndex> sorted = bodies.free_slots;
  std::sort(sorted.begin(), sorted.end());
  const auto dead = static_cast<std::size_t>(std::count(bodies.alive.begin(), bodies.alive.end(), 0));
  if (!in.Check(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end() && sorted.size() == dead)) {
    return false;
  }
  const std::uint32_t spring_count = in.Count(8 + 1 + 7 * 8);
  for (std::uint32_t i = 0; i < spring_count && in.Ok(); ++i) {
    SpringDef s;
    s.body_a = ReadId(in);
    if (in.U8()) s.body_b = ReadId(in);
    s.local_a = ReadVec(in);
    s.local_b = ReadVec(in);
    s.rest_length = in.F64();
    s.stiffness = in.F64();
    s.damping = in.F64();
    in.Check(bodies.IsLive(s.body_a) && (!s.body_b || bodies.IsLive(*s.body_b)));
    springs.all.push_back(s);
  }
  if (!in.Ok()) return false;  // a spring naming no live body must not reach the rebuild
  RebuildActingSprings();
  std::vector<Contact>& contacts = narrow_phase.Contacts();
  contacts.resize(in.Count(8 + 16 + 1 + 16));
  for (std::size_t i = 0; i < contacts.size() && in.Ok(); ++i) {
    Contact& c = contacts[i];
    if (!ReadContact(in, &c)) return false;
    if (bodies.with_parts > 0) {
      const std::uint32_t piece_a = in.U32(), piece_b = in.U32();
      if (!in.Check(piece_a <= 0xffff && piece_b <= 0xffff)) return false;
      c.piece_a = static_cast<std::uint16_t>(piece_a);
      c.piece_b = static_cast<std::uint16_t>(piece_b);
    }
    auto pieces = [&](BodyIndex body) {
      return bodies.geometries[body] ? bodies.geometries[body]->pieces.size() : std::size_t{1};
    };
    in.Check(c.a < c.b && c.b < n && bodies.enabled[c.a] && bodies.enabled[c.b] && c.piece_a < pieces(c.a) &&
             c.piece_b < pieces(c.b) && (i == 0 || detail::ContactBefore(contacts[i - 1], c)));
  }
  if (!in.Ok() || !contact_events.Load(in, bodies) || !sensors.Load(in, bodies)) return false;
  if (!in.Check(in.U8() == solver.index())) return false;
  if (!std::visit([&](auto& s) { return s.Load(in, n); }, solver) || !in.Ok()) return false;
  if (in.Remaining() == 0) return true;
  if (!LoadJoints(in)) return false;
  return in.Remaining() == 0 || (particles.Load(in, bodies) && effects.Load(in) && in.Ok());
}

std::vector<std::uint8_t> World::TakeSnapshot() const {
  std::vector<std::uint8_t> bytes;
  TakeSnapshot(&bytes);
  return bytes;
}

void World::TakeSnapshot(std::vector<std::uint8_t>* out) const {
  out->clear();
  ByteWriter w(out);
  w.U32(kMagic);
  w.U32(kVersion);
  w.U64(Fingerprint(impl_->def));
  impl_->Save(w);
  w.U64(Fnv(*out));  // the checksum: any flipped or lost byte is caught
}

RestoreResult World::RestoreSnapshot(std::span<const std::uint8_t> snapshot) {
  if (snapshot.size() < 24) return {"not a ballbox snapshot: too short"};
  const std::span<const std::uint8_t> body = snapshot.first(snapshot.size() - 8);
  ByteReader header(snapshot);
  if (header.U32() != kMagic) return {"not a ballbox snapshot (wrong magic number)"};
  if (header.U32() != kVersion) return {"a snapshot of another format version"};
  ByteReader tail(snapshot.last(8));
  if (tail.U64() != Fnv(body)) return {"the snapshot is corrupt or truncated (checksum mismatch)"};
  if (header.U64() != Fingerprint(impl_->def)) {
    return {"the snapshot is of a world with other settings (gravity, step, solver, ...)"};
  }
  auto fresh = std::make_unique<Impl>(impl_->def);
  ByteReader in(body.subspan(header.Position()));
  if (!fresh->Load(in) || in.Remaining() != 0) return {"the snapshot is corrupt (its contents do not add up)"};
  impl_ = std::move(fresh);
  return {};
}

// The parts the stages keep from step to step.

void detail::ContactEvents::Save(ByteWriter& out) const {
  WritePairs(out, touching_);
  out.U32(static_cast<std::uint32_t>(removed_.size()));
  for (const ContactEndEvent& e : removed_) WriteId(out, e.a), WriteId(out, e.b);
}

bool detail::ContactEvents::Load(ByteReader& in, const Bodies& bodies) {
  if (!ReadPairs(in, bodies, &touching_)) return false;
  removed_.resize(in.Count(16));
  for (ContactEndEvent& e : removed_) e = {ReadId(in), ReadId(in)};
  return in.Ok();
}

void detail::SensorOverlaps::Save(ByteWriter& out) const {
  WritePairs(out, overlaps_);
  out.U32(static_cast<std::uint32_t>(removed_.size()));
  for (const SensorEvent& e : removed_) WriteId(out, e.sensor), WriteId(out, e.visitor);
}

bool detail::SensorOverlaps::Load(ByteReader& in, const Bodies& bodies) {
  if (!ReadPairs(in, bodies, &overlaps_)) return false;
  removed_.resize(in.Count(16));
  for (SensorEvent& e : removed_) e = {ReadId(in), ReadId(in)};
  return in.Ok();
}

void detail::SubstepSolver::Save(ByteWriter& out) const { WritePairs(out, direct_solver_.pairs); }

bool detail::SubstepSolver::Load(ByteReader& in, std::size_t slots) {
  const std::uint32_t n = in.Count(8);
  direct_solver_.pairs.clear();
  for (std::uint32_t i = 0; i < n && in.Ok(); ++i) {
    const BodyPair p{in.U32(), in.U32()};
    in.Check(p.a < p.b && p.b < slots && (direct_solver_.pairs.empty() || direct_solver_.pairs.back() < p));
    direct_solver_.pairs.push_back(p);
  }
  return in.Ok();
}

}  // namespace engine
