// World's particle calls: soft bodies, fluid and emitters, and their step after the bodies'.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "engine/world.h"
#include "require.h"
#include "world_impl.h"

namespace engine {

namespace {

using detail::IsNonNegativeFinite;
using detail::IsPositiveFinite;
using detail::Require;

void RequireValid(const SoftBodyDef& def) {
  Require(detail::IsValidSoftBodyDef(def),
          "SoftBodyDef needs a circle or box larger than its spacing (at most 100000 particles), finite "
          "placement and velocity, spacing, density and pressure > 0, compliances, damping and friction >= 0");
}

void RequireValid(const FluidDef& def, double spacing) {
  Require(IsFinite(def.region.lower) && IsFinite(def.region.upper) && def.region.lower.x < def.region.upper.x &&
              def.region.lower.y < def.region.upper.y,
          "FluidDef::region must be finite with lower < upper");
  Require(IsPositiveFinite(def.spacing) && IsPositiveFinite(def.density), "FluidDef spacing and density must be > 0");
  Require(spacing == 0.0 || def.spacing == spacing, "every FluidDef in a world must have the same spacing");
  Require(def.viscosity >= 0.0 && def.viscosity <= 1.0, "FluidDef::viscosity must be in [0, 1]");
  Require(IsNonNegativeFinite(def.vorticity) && IsNonNegativeFinite(def.friction) && IsFinite(def.velocity),
          "FluidDef vorticity and friction must be finite and >= 0, velocity finite");
  const double cells = std::floor((def.region.upper.x - def.region.lower.x) / def.spacing + 1e-9) *
                       std::floor((def.region.upper.y - def.region.lower.y) / def.spacing + 1e-9);
  Require(cells <= 1.0e7, "a FluidDef may make at most 10 million particles");
}

bool IsUnit(float v) { return v >= 0.0f && v <= 1.0f; }

void RequireValid(const EmitterDef& def) {
  Require(IsFinite(def.position) && std::isfinite(def.direction), "EmitterDef position and direction must be finite");
  for (const double v : {def.spread, def.speed, def.speed_spread, def.rate, def.lifetime_spread, def.size_start,
                         def.size_end, def.drag, def.restitution, def.friction}) {
    Require(IsNonNegativeFinite(v), "EmitterDef spreads, speeds, rate, sizes, drag, restitution and friction must be >= 0");
  }
  Require(IsPositiveFinite(def.lifetime) && def.lifetime_spread <= def.lifetime && def.speed_spread <= def.speed,
          "EmitterDef needs lifetime > 0 and spreads no larger than their means");
  Require(std::isfinite(def.buoyancy), "EmitterDef::buoyancy must be finite");
  for (const Rgba c : {def.color_start, def.color_end}) {
    Require(IsUnit(c.r) && IsUnit(c.g) && IsUnit(c.b) && IsUnit(c.a), "EmitterDef colours must be in [0, 1]");
  }
}

}  // namespace

std::uint32_t World::Impl::SoftBodySlot(SoftBodyId id, const char* call) const {
  if (!particles.IsLive(id)) {
    std::fprintf(stderr, "engine precondition failed: %s: not a live soft body\n", call);
    std::abort();
  }
  return id.index;
}

std::uint32_t World::Impl::EmitterSlot(EmitterId id, const char* call) const {
  if (!effects.IsLive(id)) {
    std::fprintf(stderr, "engine precondition failed: %s: not a live emitter\n", call);
    std::abort();
  }
  return id.index;
}

void World::Impl::StepParticles() {
  if (particles.Empty() && !effects.EverUsed()) return;
  if (!particles.Empty()) {
    std::vector<BodyIndex> to_wake;
    particles.Step(def, bodies, sleep.awake, *pool, &to_wake);
    for (const BodyIndex b : to_wake) WakeAround(b);
    const auto positions = particles.Positions();
    const auto velocities = particles.Velocities();
    for (std::size_t i = 0; i < positions.size(); ++i) {
      if (!IsFinite(positions[i]) || !IsFinite(velocities[i])) {
        const bool fluid = i >= particles.FluidFirst();
        fault = NumericFault{step_count, kNoBody,
                             fluid ? (IsFinite(positions[i]) ? "fluid particle velocity" : "fluid particle position")
                                   : (IsFinite(positions[i]) ? "soft body particle velocity"
                                                             : "soft body particle position")};
        return;
      }
    }
  }
  if (effects.EverUsed()) effects.Step(def, bodies, *pool);
}

SoftBodyId World::CreateSoftBody(const SoftBodyDef& def) {
  RequireValid(def);
  if (def.attach_to) Require(impl_->bodies.IsLive(*def.attach_to), "SoftBodyDef::attach_to must be a live body");
  return impl_->particles.CreateSoftBody(def, impl_->bodies);
}

void World::DestroySoftBody(SoftBodyId id) { impl_->particles.DestroySoftBody(impl_->SoftBodySlot(id, "DestroySoftBody")); }
bool World::IsValid(SoftBodyId id) const { return impl_->particles.IsLive(id); }
std::span<const SoftBodyId> World::SoftBodyIds() const { return impl_->particles.SoftBodyIds(); }
const SoftBodyDef& World::GetSoftBodyDef(SoftBodyId id) const {
  return impl_->particles.Soft(impl_->SoftBodySlot(id, "GetSoftBodyDef")).def;
}
std::span<const Vec2> World::SoftBodyPositions(SoftBodyId id) const {
  const detail::SoftBody& soft = impl_->particles.Soft(impl_->SoftBodySlot(id, "SoftBodyPositions"));
  return impl_->particles.Positions().subspan(soft.first, soft.count);
}
std::span<const Vec2> World::SoftBodyVelocities(SoftBodyId id) const {
  const detail::SoftBody& soft = impl_->particles.Soft(impl_->SoftBodySlot(id, "SoftBodyVelocities"));
  return impl_->particles.Velocities().subspan(soft.first, soft.count);
}
std::span<const std::uint32_t> World::SoftBodyOutline(SoftBodyId id) const {
  return impl_->particles.Soft(impl_->SoftBodySlot(id, "SoftBodyOutline")).outline;
}
double World::SoftBodyParticleMass(SoftBodyId id) const {
  return impl_->particles.Soft(impl_->SoftBodySlot(id, "SoftBodyParticleMass")).particle_mass;
}
double World::SoftBodyParticleRadius(SoftBodyId id) const {
  return impl_->particles.Soft(impl_->SoftBodySlot(id, "SoftBodyParticleRadius")).radius;
}
void World::ApplySoftBodyImpulse(SoftBodyId id, std::uint32_t particle, Vec2 impulse) {
  const detail::SoftBody& soft = impl_->particles.Soft(impl_->SoftBodySlot(id, "ApplySoftBodyImpulse"));
  Require(particle < soft.count && IsFinite(impulse), "ApplySoftBodyImpulse: a particle of the body, a finite impulse");
  impl_->particles.ApplyImpulse(soft.first + particle, impulse);
}

std::size_t World::AddFluid(const FluidDef& def) {
  RequireValid(def, impl_->particles.Fluid().spacing);
  return impl_->particles.AddFluid(def);
}
std::span<const Vec2> World::FluidPositions() const {
  return impl_->particles.Positions().subspan(impl_->particles.FluidFirst());
}
std::span<const Vec2> World::FluidVelocities() const {
  return impl_->particles.Velocities().subspan(impl_->particles.FluidFirst());
}
std::span<const double> World::FluidDensities() const { return impl_->particles.Fluid().density; }
std::span<const double> World::FluidRestDensities() const { return impl_->particles.Fluid().rest_density; }
std::span<const double> World::FluidMasses() const { return impl_->particles.Fluid().mass; }
double World::FluidSpacing() const { return impl_->particles.Fluid().spacing; }
void World::ApplyFluidImpulse(std::uint32_t particle, Vec2 impulse) {
  Require(particle < impl_->particles.FluidCount() && IsFinite(impulse),
          "ApplyFluidImpulse: a fluid particle, a finite impulse");
  impl_->particles.ApplyImpulse(impl_->particles.FluidFirst() + particle, impulse);
}

EmitterId World::CreateEmitter(const EmitterDef& def) {
  RequireValid(def);
  if (def.body) Require(impl_->bodies.IsLive(*def.body), "EmitterDef::body must be a live body");
  return impl_->effects.Create(def);
}
void World::DestroyEmitter(EmitterId id) { impl_->effects.Destroy(impl_->EmitterSlot(id, "DestroyEmitter")); }
bool World::IsValid(EmitterId id) const { return impl_->effects.IsLive(id); }
std::span<const EmitterId> World::EmitterIds() const { return impl_->effects.Ids(); }
const EmitterDef& World::GetEmitterDef(EmitterId id) const {
  return impl_->effects.Def(impl_->EmitterSlot(id, "GetEmitterDef"));
}
void World::SetEmitterPosition(EmitterId id, Vec2 position) {
  Require(IsFinite(position), "SetEmitterPosition: a finite position");
  impl_->effects.MutableDef(impl_->EmitterSlot(id, "SetEmitterPosition")).position = position;
}
void World::SetEmitterRate(EmitterId id, double rate) {
  Require(IsNonNegativeFinite(rate), "SetEmitterRate: a finite rate >= 0");
  impl_->effects.MutableDef(impl_->EmitterSlot(id, "SetEmitterRate")).rate = rate;
}
std::span<const EffectParticle> World::Effects() const { return impl_->effects.Particles(); }

}  // namespace engine
