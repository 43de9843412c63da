// The effect particles in a snapshot: every emitter slot (its def, generation, generator and
// carried births), the free and draining lists in order, and the particles oldest first. Load
// checks every count, index and number, so a corrupt save is refused, never half taken.
#include <algorithm>
#include <bit>
#include <cmath>

#include "particles/effects.h"
#include "snapshot/byte_stream.h"

namespace engine::detail {

namespace {

void WriteColour(ByteWriter& out, Rgba c) {
  for (const float v : {c.r, c.g, c.b, c.a}) out.U32(std::bit_cast<std::uint32_t>(v));
}

Rgba ReadColour(ByteReader& in) {
  Rgba c;
  for (float* v : {&c.r, &c.g, &c.b, &c.a}) *v = std::bit_cast<float>(in.U32());
  return c;
}

void WriteDef(ByteWriter& out, const EmitterDef& d) {
  WriteVec(out, d.position);
  out.U8(d.body ? 1 : 0);
  if (d.body) {
    out.U32(d.body->index);
    out.U32(d.body->generation);
  }
  for (const double v : {d.direction, d.spread, d.speed, d.speed_spread, d.rate, d.lifetime, d.lifetime_spread,
                         d.size_start, d.size_end, d.drag, d.buoyancy, d.restitution, d.friction}) {
    out.F64(v);
  }
  WriteColour(out, d.color_start);
  WriteColour(out, d.color_end);
  out.U8(static_cast<std::uint8_t>(d.blend));
  out.U8(d.collide ? 1 : 0);
  out.U64(d.seed);
  out.U32(d.max_particles);
}

bool IsUnit(float v) { return v >= 0.0f && v <= 1.0f; }

// The def, checked as World::CreateEmitter checks one (the body is checked when it emits).
bool ReadDef(ByteReader& in, EmitterDef* d) {
  d->position = ReadVec(in);
  const std::uint8_t has_body = in.U8();
  if (has_body == 1) {
    const BodyIndex index = in.U32();
    d->body = BodyId{index, in.U32()};
  }
  for (double* v : {&d->direction, &d->spread, &d->speed, &d->speed_spread, &d->rate, &d->lifetime,
                    &d->lifetime_spread, &d->size_start, &d->size_end, &d->drag, &d->buoyancy, &d->restitution,
                    &d->friction}) {
    *v = in.F64();
  }
  d->color_start = ReadColour(in);
  d->color_end = ReadColour(in);
  const std::uint8_t blend = in.U8(), collide = in.U8();
  d->blend = static_cast<EffectBlend>(blend);
  d->collide = collide == 1;
  d->seed = in.U64();
  d->max_particles = in.U32();
  bool ok = has_body <= 1 && blend <= 1 && collide <= 1 && IsFinite(d->position) && std::isfinite(d->direction) &&
            std::isfinite(d->buoyancy);
  for (const double v : {d->spread, d->speed, d->speed_spread, d->rate, d->lifetime_spread, d->size_start, d->size_end,
                         d->drag, d->restitution, d->friction}) {
    ok = ok && std::isfinite(v) && v >= 0.0;
  }
  ok = ok && std::isfinite(d->lifetime) && d->lifetime > 0.0 && d->lifetime_spread <= d->lifetime &&
       d->speed_spread <= d->speed;
  for (const Rgba c : {d->color_start, d->color_end}) {
    ok = ok && IsUnit(c.r) && IsUnit(c.g) && IsUnit(c.b) && IsUnit(c.a);
  }
  return in.Check(ok);
}

// A list of slots, each dead, named once, and not already in `listed` (which it joins).
bool ReadDeadSlots(ByteReader& in, const std::vector<std::uint8_t>& alive, std::vector<std::uint8_t>* listed,
                   std::vector<std::uint32_t>* out) {
  out->resize(in.Count(4));
  for (std::uint32_t& slot : *out) {
    slot = in.U32();
    if (!in.Check(slot < alive.size() && !alive[slot] && !(*listed)[slot])) return false;
    (*listed)[slot] = 1;
  }
  return in.Ok();
}

}  // namespace

void EffectSystem::Save(ByteWriter& out) const {
  out.U32(static_cast<std::uint32_t>(defs_.size()));
  for (std::uint32_t s = 0; s < defs_.size(); ++s) {
    WriteDef(out, defs_[s]);
    out.U32(generations_[s]);
    out.U8(alive_[s]);
    out.U64(random_states_[s]);
    out.F64(owed_births_[s]);
  }
  for (const std::vector<std::uint32_t>* list : {&free_, &draining_}) {
    out.U32(static_cast<std::uint32_t>(list->size()));
    for (const std::uint32_t slot : *list) out.U32(slot);
  }
  out.U32(static_cast<std::uint32_t>(particles_.size()));
  for (const EffectParticle& p : particles_) {
    WriteVec(out, p.position);
    WriteVec(out, p.velocity);
    out.F64(p.age);
    out.F64(p.lifetime);
    out.U32(p.emitter.index);
    out.U32(p.emitter.generation);
  }
  out.U8(ever_used_ ? 1 : 0);
}

bool EffectSystem::Load(ByteReader& in) {
  EffectSystem loaded;
  const std::uint32_t n = in.Count(100);  // a def alone is over 100 bytes
  loaded.defs_.resize(n);
  loaded.generations_.resize(n);
  loaded.alive_.resize(n);
  loaded.random_states_.resize(n);
  loaded.owed_births_.resize(n);
  loaded.alive_counts_.assign(n, 0);
  for (std::uint32_t s = 0; s < n; ++s) {
    if (!ReadDef(in, &loaded.defs_[s])) return false;
    loaded.generations_[s] = in.U32();
    loaded.alive_[s] = in.U8();
    loaded.random_states_[s] = in.U64();
    loaded.owed_births_[s] = in.F64();
    // A step leaves less than one birth owed, or exactly one waiting for room.
    const double owed = loaded.owed_births_[s];
    if (!in.Check(loaded.alive_[s] <= 1 && owed >= -1.0 && owed <= 1.0)) return false;
  }
  std::vector<std::uint8_t> listed(n, 0);
  if (!ReadDeadSlots(in, loaded.alive_, &listed, &loaded.free_) ||
      !ReadDeadSlots(in, loaded.alive_, &listed, &loaded.draining_)) {
    return false;
  }
  const auto dead = static_cast<std::size_t>(std::count(loaded.alive_.begin(), loaded.alive_.end(), 0));
  if (!in.Check(loaded.free_.size() + loaded.draining_.size() == dead)) return false;
  // Each slot's role: 0 free, 1 live, 2 draining.
  std::vector<std::uint8_t> roles(loaded.alive_.begin(), loaded.alive_.end());
  for (const std::uint32_t slot : loaded.draining_) roles[slot] = 2;
  if (!loaded.LoadParticles(in, roles)) return false;
  const std::uint8_t ever_used = in.U8();
  if (!in.Check(ever_used <= 1)) return false;
  loaded.ever_used_ = ever_used == 1;
  loaded.RebuildLiveIds();
  *this = std::move(loaded);
  return true;
}

// The particles: finite, younger than their lifetimes, oldest first, each of a live emitter (of
// its generation) or of a draining one (of the generation before).
bool EffectSystem::LoadParticles(ByteReader& in, std::span<const std::uint8_t> roles) {
  particles_.resize(in.Count(56));
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    EffectParticle& p = particles_[i];
    p.position = ReadVec(in);
    p.velocity = ReadVec(in);
    p.age = in.F64();
    p.lifetime = in.F64();
    p.emitter.index = in.U32();
    p.emitter.generation = in.U32();
    const std::uint32_t s = p.emitter.index;
    const bool numbers = IsFinite(p.position) && IsFinite(p.velocity) && p.age >= 0.0 && p.age < p.lifetime &&
                         std::isfinite(p.lifetime) && (i == 0 || p.age <= particles_[i - 1].age);
    const bool owner = s < roles.size() && ((roles[s] == 1 && p.emitter.generation == generations_[s]) ||
                                            (roles[s] == 2 && generations_[s] > 0 &&
                                             p.emitter.generation == generations_[s] - 1));
    if (!in.Check(numbers && owner)) return false;
    ++alive_counts_[s];
  }
  return in.Ok();
}

}  // namespace engine::detail
