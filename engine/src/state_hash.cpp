// The state hash of the contract: FNV-1a 64 over the little-endian IEEE-754 bytes of
// x, y, vx, vy, angle, ω of every live body in slot (scene) order; then x, y, vx, vy of every
// particle (soft bodies, effects, fluid), of which a world without particles has none.
#include <bit>
#include <cstdint>

#include "world_impl.h"

namespace engine {

namespace {

constexpr std::uint64_t kFnvOffset = 0xcbf29ce484222325ULL;
constexpr std::uint64_t kFnvPrime = 0x100000001b3ULL;

void HashDouble(double value, std::uint64_t* hash) {
  const auto bits = std::bit_cast<std::uint64_t>(value);
  for (int byte = 0; byte < 8; ++byte) {  // least significant byte first: little-endian order
    *hash ^= (bits >> (8 * byte)) & 0xffu;
    *hash *= kFnvPrime;
  }
}

}  // namespace

std::uint64_t World::StateHash() const {
  std::uint64_t hash = kFnvOffset;
  for (const BodyId id : impl_->bodies.live_ids) {
    const BodyState& s = impl_->bodies.states[id.index];
    const Vec2 origin = impl_->bodies.Origin(id.index);
    HashDouble(origin.x, &hash);
    HashDouble(origin.y, &hash);
    HashDouble(s.velocity.x, &hash);
    HashDouble(s.velocity.y, &hash);
    HashDouble(s.angle, &hash);
    HashDouble(s.angular_velocity, &hash);
  }
  // Then the particles: soft bodies in slot order, effect particles oldest first, the fluid.
  const auto hash_particle = [&hash](Vec2 x, Vec2 v) {
    for (const double value : {x.x, x.y, v.x, v.y}) HashDouble(value, &hash);
  };
  const detail::ParticleSystem& particles = impl_->particles;
  for (const SoftBodyId id : particles.SoftBodyIds()) {
    const detail::SoftBody& soft = particles.Soft(id.index);
    for (std::uint32_t i = soft.first; i < soft.first + soft.count; ++i) {
      hash_particle(particles.Positions()[i], particles.Velocities()[i]);
    }
  }
  for (const EffectParticle& p : impl_->effects.Particles()) hash_particle(p.position, p.velocity);
  for (std::size_t i = particles.FluidFirst(); i < particles.Positions().size(); ++i) {
    hash_particle(particles.Positions()[i], particles.Velocities()[i]);
  }
  return hash;
}

}  // namespace engine
