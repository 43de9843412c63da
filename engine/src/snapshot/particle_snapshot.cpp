// The soft bodies' and the fluid's part of a snapshot: every particle's state, each soft body's
// definition (its constraints are rebuilt from it, as made) and attachments, the fluid's
// constants. The step's scratch is rebuilt by the next step.
#include <algorithm>
#include <cmath>

#include "particles/particle_system.h"
#include "snapshot/byte_stream.h"

namespace engine::detail {

namespace {

void WriteVec(ByteWriter& out, Vec2 v) {
  out.F64(v.x);
  out.F64(v.y);
}

Vec2 ReadVec(ByteReader& in) {
  const double x = in.F64();
  return {x, in.F64()};
}

void WriteDoubles(ByteWriter& out, const std::vector<double>& values) {
  out.U32(static_cast<std::uint32_t>(values.size()));
  for (const double v : values) out.F64(v);
}

bool ReadDoubles(ByteReader& in, std::vector<double>* values) {
  values->resize(in.Count(8));
  for (double& v : *values) v = in.F64();
  return in.Ok();
}

void WriteDef(ByteWriter& out, const SoftBodyDef& def) {
  out.U8(static_cast<std::uint8_t>(def.shape.type));
  out.F64(def.shape.radius);
  WriteVec(out, def.shape.half_extents);
  WriteVec(out, def.position);
  out.F64(def.angle);
  WriteVec(out, def.velocity);
  for (const double v : {def.density, def.spacing, def.stretch_compliance, def.shear_compliance, def.area_compliance,
                         def.pressure, def.damping, def.friction}) {
    out.F64(v);
  }
  out.U8(def.attach_to ? 1 : 0);
  if (def.attach_to) {
    out.U32(def.attach_to->index);
    out.U32(def.attach_to->generation);
  }
}

SoftBodyDef ReadDef(ByteReader& in) {
  SoftBodyDef def;
  const std::uint8_t type = in.U8();
  in.Check(type == static_cast<std::uint8_t>(ShapeType::kCircle) || type == static_cast<std::uint8_t>(ShapeType::kBox));
  def.shape.type = static_cast<ShapeType>(type);
  def.shape.radius = in.F64();
  def.shape.half_extents = ReadVec(in);
  def.position = ReadVec(in);
  def.angle = in.F64();
  def.velocity = ReadVec(in);
  for (double* v : {&def.density, &def.spacing, &def.stretch_compliance, &def.shear_compliance, &def.area_compliance,
                    &def.pressure, &def.damping, &def.friction}) {
    *v = in.F64();
  }
  if (in.U8()) {
    const std::uint32_t index = in.U32();
    def.attach_to = BodyId{index, in.U32()};
  }
  return def;
}

}  // namespace

void ParticleSystem::Save(ByteWriter& out) const {
  out.U32(static_cast<std::uint32_t>(x_.size()));
  for (std::size_t i = 0; i < x_.size(); ++i) {
    WriteVec(out, x_[i]);
    WriteVec(out, v_[i]);
  }
  out.U32(static_cast<std::uint32_t>(soft_.size()));
  for (std::uint32_t slot = 0; slot < soft_.size(); ++slot) {
    out.U32(soft_generations_[slot]);
    out.U8(soft_alive_[slot]);
    if (!soft_alive_[slot]) continue;
    const SoftBody& body = soft_[slot];
    WriteDef(out, body.def);
    out.U32(body.first);
    out.U32(static_cast<std::uint32_t>(body.attachments.size()));
    for (const SoftAttachment& a : body.attachments) {
      out.U32(a.particle);
      out.U32(a.body);
      WriteVec(out, a.local);
    }
  }
  out.U32(static_cast<std::uint32_t>(soft_free_.size()));
  for (const std::uint32_t slot : soft_free_) out.U32(slot);
  out.U32(fluid_first_);
  out.F64(fluid_.spacing);
  for (const std::vector<double>* values : {&fluid_.rest_density, &fluid_.mass, &fluid_.viscosity, &fluid_.vorticity,
                                            &fluid_.friction, &fluid_.density}) {
    WriteDoubles(out, *values);
  }
}

bool ParticleSystem::Load(ByteReader& in, const Bodies& bodies) {
  const std::uint32_t count = in.Count(32);
  std::vector<Vec2> positions(count), velocities(count);
  for (std::uint32_t i = 0; i < count; ++i) {
    positions[i] = ReadVec(in);
    velocities[i] = ReadVec(in);
  }
  // The soft bodies, rebuilt from their definitions, their particles then given the saved state.
  const std::uint32_t slots = in.Count(5);
  struct Saved {
    SoftBody body;
    std::uint32_t generation;
    bool alive;
  };
  std::vector<Saved> saved(slots);
  for (Saved& s : saved) {
    s.generation = in.U32();
    s.alive = in.U8() != 0;
    if (!s.alive || !in.Ok()) continue;
    const SoftBodyDef def = ReadDef(in);
    if (!in.Ok() || !IsValidSoftBodyDef(def)) return false;
    s.body = MakeSoftBody(def);
    s.body.first = in.U32();
    s.body.attachments.resize(in.Count(24));
    for (SoftAttachment& a : s.body.attachments) {
      a.particle = in.U32();
      a.body = in.U32();
      a.local = ReadVec(in);
      in.Check(a.particle < s.body.count && a.body < bodies.alive.size() && bodies.alive[a.body]);
    }
  }
  std::vector<std::uint32_t> free_slots(in.Count(4));
  for (std::uint32_t& slot : free_slots) {
    slot = in.U32();
    in.Check(slot < slots && !saved[slot].alive);
  }
  const std::uint32_t fluid_first = in.U32();
  const double spacing = in.F64();
  FluidParticles fluid;
  for (std::vector<double>* values : {&fluid.rest_density, &fluid.mass, &fluid.viscosity, &fluid.vorticity,
                                      &fluid.friction, &fluid.density}) {
    if (!ReadDoubles(in, values) || !in.Check(values->size() + fluid_first == count)) return false;
  }
  if (!in.Ok() || fluid_first > count) return false;
  // The soft bodies' particles must tile [0, fluid_first) exactly.
  std::uint32_t covered = 0;
  for (const Saved& s : saved) {
    if (s.alive) covered += s.body.count;
    if (s.alive && (s.body.first > fluid_first || s.body.count > fluid_first - s.body.first)) return false;
  }
  if (covered != fluid_first) return false;
  // Rebuild the arrays as the making calls would have.
  *this = ParticleSystem{};
  for (std::uint32_t slot = 0; slot < slots; ++slot) {
    soft_.push_back(std::move(saved[slot].body));
    soft_generations_.push_back(saved[slot].generation);
    soft_alive_.push_back(saved[slot].alive ? 1 : 0);
  }
  soft_free_ = free_slots;
  x_ = positions;
  v_ = velocities;
  inv_mass_.assign(count, 0.0);
  radius_.assign(count, 0.0);
  group_.assign(count, kFluidGroup);
  for (std::uint32_t slot = 0; slot < slots; ++slot) {
    if (!soft_alive_[slot]) continue;
    const SoftBody& body = soft_[slot];
    soft_live_ids_.push_back({slot, soft_generations_[slot]});
    std::fill_n(inv_mass_.begin() + body.first, body.count, 1.0 / body.particle_mass);
    std::fill_n(radius_.begin() + body.first, body.count, body.radius);
    std::fill_n(group_.begin() + body.first, body.count, slot);
    largest_radius_ = std::max(largest_radius_, body.radius);
  }
  fluid_first_ = fluid_first;
  fluid_ = std::move(fluid);
  fluid_.spacing = spacing;
  for (std::uint32_t f = 0; f < count - fluid_first; ++f) {
    if (!(fluid_.mass[f] > 0.0)) return false;
    inv_mass_[fluid_first + f] = 1.0 / fluid_.mass[f];
    radius_[fluid_first + f] = 0.5 * spacing;
    largest_radius_ = std::max(largest_radius_, 0.5 * spacing);
  }
  if (count > fluid_first) {
    if (!(spacing > 0.0) || !std::isfinite(spacing)) return false;
    SetUpFluidKernel(fluid_.rest_density[0]);
  }
  ever_used_ = true;
  return true;
}

}  // namespace engine::detail
