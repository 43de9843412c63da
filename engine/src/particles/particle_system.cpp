// The particles' step (docs/soft-bodies.md, docs/fluids.md). Each substep of h (Macklin et al.
// 2019, "Small steps in physics simulation"): predict under gravity; one or more passes of the
// soft bodies' XPBD constraints, the fluid's density constraints (Macklin and Müller 2013,
// "Position based fluids"), contacts between particles of different bodies, attachments and
// contacts with the rigid bodies; then velocities from the positions moved. The rigid bodies
// have already stepped: a particle pushing one changes its velocity at once and moves it by
// its share of the correction, as XPBD moves both sides of a constraint.
#include "particles/particle_system.h"

#include <algorithm>
#include <cmath>

#include "candidate_pairs.h"
#include "geometry/transform.h"
#include "particles/sph_kernels.h"

namespace engine::detail {

namespace {

/// The fluid kernel reaches this many spacings: about 20 neighbours on a square lattice.
constexpr double kKernelSpacings = 2.5;
/// PBF's artificial pressure (Macklin and Müller 2013, §4: s_corr = −k·(W(r)/W(Δq))⁴, Δq =
/// 0.2 h): `kClumpingStrength` is k as a share of a unit density error.
constexpr double kClumpingStrength = 0.001;
constexpr double kClumpingDistance = 0.2;
/// The PBF denominator's relaxation (the paper's ε), as a share of a lattice particle's.
constexpr double kRelaxation = 0.1;
/// The share of the Jacobi sum applied (see SolveFluid).
constexpr double kJacobiShare = 0.5;
/// A wall pushes a particle as a fluid neighbour would: with its multiplier on both sides of
/// the pair (the wall's own taken as the particle's), so twice its one-sided share. With one
/// side only, a crate of density 500 in water sank to 0.532 of its height, with both 0.517.
constexpr double kWallFactor = 2.0;
/// Fewer fluid particles than this are looped over on one thread: handing the others their
/// chunks costs a few microseconds, more than a few hundred particles' work.
constexpr std::uint32_t kMinParallel = 1024;
/// The fewest fluid particles in a chunk of pairs (FindChunks) but the last: enough that
/// handing a chunk to a thread costs little beside its work.
constexpr std::uint32_t kChunkParticles = 1024;

double KernelRadius(double spacing) { return kKernelSpacings * spacing; }

/// values[offset + k] = the old values[offset + order[k]], for each k.
template <typename T>
void GatherInOrder(std::vector<T>& values, std::size_t offset, std::span<const std::uint32_t> order) {
  const std::vector<T> old(values.begin() + static_cast<std::ptrdiff_t>(offset), values.end());
  for (std::size_t k = 0; k < order.size(); ++k) values[offset + k] = old[order[k]];
}

/// GatherInOrder undone: values[offset + order[k]] = the old values[offset + k].
template <typename T>
void ScatterFromOrder(std::vector<T>& values, std::size_t offset, std::span<const std::uint32_t> order) {
  const std::vector<T> sorted(values.begin() + static_cast<std::ptrdiff_t>(offset), values.end());
  for (std::size_t k = 0; k < order.size(); ++k) values[offset + order[k]] = sorted[k];
}

}  // namespace

SoftBodyId ParticleSystem::CreateSoftBody(const SoftBodyDef& def, const Bodies& bodies) {
  SoftBody body = MakeSoftBody(def);
  std::uint32_t slot;
  if (!soft_free_.empty()) {
    slot = soft_free_.back();
    soft_free_.pop_back();
  } else {
    slot = static_cast<std::uint32_t>(soft_.size());
    soft_.emplace_back();
    soft_generations_.push_back(0);
    soft_alive_.push_back(0);
  }
  // Its particles go after the other soft bodies', before the fluid's.
  body.first = fluid_first_;
  InsertParticles(fluid_first_, body.rest_positions, def.velocity, 1.0 / body.particle_mass, body.radius, slot);
  fluid_first_ += body.count;
  if (def.attach_to) {
    const BodyIndex b = def.attach_to->index;
    std::vector<BodyPlane> planes;
    const geometry::Transform frame{bodies.states[b].position, MakeRot(bodies.states[b].angle)};
    for (std::uint32_t k = 0; k < body.count; ++k) {
      const Vec2 p = body.rest_positions[k];
      planes.clear();
      AppendBodyPlanes(bodies, b, p, 0.0, 0.0, &planes);
      const bool inside = std::any_of(planes.begin(), planes.end(),
                                      [&](const BodyPlane& plane) { return Dot(plane.normal, p - plane.surface) <= 0.0; });
      if (inside) body.attachments.push_back({k, b, geometry::InvTransformPoint(frame, p)});
    }
  }
  soft_[slot] = std::move(body);
  soft_alive_[slot] = 1;
  soft_live_ids_.clear();
  for (std::uint32_t s = 0; s < soft_.size(); ++s) {
    if (soft_alive_[s]) soft_live_ids_.push_back({s, soft_generations_[s]});
  }
  ever_used_ = true;
  return {slot, soft_generations_[slot]};
}

void ParticleSystem::InsertParticles(std::uint32_t at, std::span<const Vec2> positions, Vec2 velocity,
                                     double inv_mass, double radius, std::uint32_t group) {
  const std::size_t n = positions.size();
  x_.insert(x_.begin() + at, positions.begin(), positions.end());
  v_.insert(v_.begin() + at, n, velocity);
  inv_mass_.insert(inv_mass_.begin() + at, n, inv_mass);
  radius_.insert(radius_.begin() + at, n, radius);
  group_.insert(group_.begin() + at, n, group);
  largest_radius_ = std::max(largest_radius_, radius);
}

void ParticleSystem::DestroySoftBody(std::uint32_t slot) {
  SoftBody& gone = soft_[slot];
  const auto begin = static_cast<std::ptrdiff_t>(gone.first), end = begin + gone.count;
  x_.erase(x_.begin() + begin, x_.begin() + end);
  v_.erase(v_.begin() + begin, v_.begin() + end);
  inv_mass_.erase(inv_mass_.begin() + begin, inv_mass_.begin() + end);
  radius_.erase(radius_.begin() + begin, radius_.begin() + end);
  group_.erase(group_.begin() + begin, group_.begin() + end);
  for (SoftBody& other : soft_) {
    if (other.count > 0 && other.first > gone.first) other.first -= gone.count;
  }
  fluid_first_ -= gone.count;
  gone = SoftBody{};
  soft_alive_[slot] = 0;
  ++soft_generations_[slot];
  soft_free_.push_back(slot);
  std::erase(soft_live_ids_, SoftBodyId{slot, soft_generations_[slot] - 1});
}

void ParticleSystem::DetachFrom(BodyIndex body) {
  for (SoftBody& soft : soft_) {
    std::erase_if(soft.attachments, [body](const SoftAttachment& a) { return a.body == body; });
  }
}

double ParticleSystem::LatticeKernelSum() const {
  // The kernel summed over a perfect square lattice of the fluid's spacing: a particle of mass
  // m inside it sits at density m × this.
  const SphKernels kernels(KernelRadius(fluid_.spacing));
  const int reach = static_cast<int>(std::ceil(kKernelSpacings));
  double sum = 0.0;
  for (int j = -reach; j <= reach; ++j) {
    for (int i = -reach; i <= reach; ++i) sum += kernels.W(LengthSquared(Vec2{i * fluid_.spacing, j * fluid_.spacing}));
  }
  return sum;
}

void ParticleSystem::SetUpFluidKernel(double first_density) {
  const double s = fluid_.spacing;
  const SphKernels kernels(KernelRadius(s));
  const int reach = static_cast<int>(std::ceil(kKernelSpacings));
  double gradient_sum = 0.0;
  for (int j = -reach; j <= reach; ++j) {
    for (int i = -reach; i <= reach; ++i) {
      const Vec2 d{i * s, j * s};
      gradient_sum += LengthSquared(kernels.Gradient(d, Length(d)));
    }
  }
  const double lattice_sum = LatticeKernelSum();
  // The PBF denominator of a particle inside the lattice, m/ρ0²·Σ|∇W|² with m = ρ0 / Σ W.
  density_denominator_ = gradient_sum / (first_density * lattice_sum);
  // A wall counts as fluid at rest: its share of the kernel scaled as the lattice's sum is.
  wall_ = WallShare(kernels);
  wall_scale_ = 1.0 / (s * s * lattice_sum);
}

std::size_t ParticleSystem::AddFluid(const FluidDef& def) {
  if (fluid_.spacing == 0.0) {
    fluid_.spacing = def.spacing;
    SetUpFluidKernel(def.density);
  }
  const double s = fluid_.spacing;
  const double mass = def.density / LatticeKernelSum();
  std::vector<Vec2> lattice;
  for (double y = def.region.lower.y + 0.5 * s; y <= def.region.upper.y - 0.5 * s + 1e-9 * s; y += s) {
    for (double x = def.region.lower.x + 0.5 * s; x <= def.region.upper.x - 0.5 * s + 1e-9 * s; x += s) {
      lattice.push_back({x, y});
    }
  }
  InsertParticles(static_cast<std::uint32_t>(x_.size()), lattice, def.velocity, 1.0 / mass, 0.5 * s, kFluidGroup);
  const std::size_t n = lattice.size();
  fluid_.rest_density.insert(fluid_.rest_density.end(), n, def.density);
  fluid_.mass.insert(fluid_.mass.end(), n, mass);
  fluid_.viscosity.insert(fluid_.viscosity.end(), n, def.viscosity);
  fluid_.vorticity.insert(fluid_.vorticity.end(), n, def.vorticity);
  fluid_.friction.insert(fluid_.friction.end(), n, def.friction);
  fluid_.density.insert(fluid_.density.end(), n, def.density);
  ever_used_ = true;
  return n;
}

void ParticleSystem::MarkStepStart(const Bodies& bodies) {
  start_centers_.resize(bodies.states.size());
  start_angles_.resize(bodies.states.size());
  for (std::size_t b = 0; b < bodies.states.size(); ++b) {
    start_centers_[b] = bodies.states[b].position;
    start_angles_[b] = bodies.states[b].angle;
  }
}

void ParticleSystem::Step(const WorldDef& def, Bodies& bodies, std::span<const std::uint8_t> awake, WorkerPool& pool,
                          std::vector<BodyIndex>* to_wake) {
  if (x_.empty()) return;
  pool_ = &pool;
  const int substeps = std::max(1, static_cast<int>(std::ceil(def.dt / def.particles.substep - 1e-9)));
  const double h = def.dt / substeps;
  FindContacts(def, bodies);
  pushes_.resize(bodies.states.size());
  touched_.clear();
  const auto touch = [&](BodyIndex b) {
    BodyPush& p = pushes_[b];
    if (p.touched) return;
    p = BodyPush{};
    p.touched = true;
    p.end_center = bodies.states[b].position;
    if (awake[b] && !HasInfiniteMass(bodies.infos[b])) {
      p.inv_mass = bodies.infos[b].inv_mass;
      p.inv_inertia = bodies.infos[b].inv_inertia;
    }
    touched_.push_back(b);
  };
  for (const PlaneContact& c : planes_) touch(c.body);
  for (const SoftBodyId id : soft_live_ids_) {
    for (const SoftAttachment& a : soft_[id.index].attachments) touch(a.body);
  }
  std::sort(touched_.begin(), touched_.end());
  // A body new since the step began starts where it is.
  const auto start_center = [&](BodyIndex b) { return b < start_centers_.size() ? start_centers_[b] : bodies.states[b].position; };
  const auto start_angle = [&](BodyIndex b) { return b < start_angles_.size() ? start_angles_[b] : bodies.states[b].angle; };
  for (const BodyIndex b : touched_) {
    BodyPush& p = pushes_[b];
    p.center = start_center(b);
    p.rotation = MakeRot(start_angle(b));
    // Fixed: the particles cannot push it (a sleeping body that can move is pushed for its
    // waking impulse) and it does not move through the step (a kinematic body sweeping through
    // the water does: its planes turn with it each substep).
    const bool unpushed = p.inv_mass == 0.0 && p.inv_inertia == 0.0 && (awake[b] || HasInfiniteMass(bodies.infos[b]));
    p.fixed = unpushed && p.end_center == p.center && start_angle(b) == bodies.states[b].angle;
  }
  previous_.resize(x_.size());
  for (int step = 0; step < substeps; ++step) {
    // The bodies' poses through the step: from the start to the end as the rigid step moved
    // them, plus the particles' pushes and the velocity those gave (as XPBD would move a body
    // it stepped itself: without that, a body the particles stop would keep going).
    const double t = static_cast<double>(step + 1) / substeps;
    for (const BodyIndex b : touched_) {
      BodyPush& p = pushes_[b];
      p.shift += h * p.velocity_change;
      p.turn += h * p.angular_velocity_change;
      p.last_center = p.center;
      p.last_rotation = p.rotation;
      const Vec2 c0 = start_center(b);
      const double a0 = start_angle(b);
      p.center = c0 + t * (p.end_center - c0) + p.shift;
      const double angle = a0 + t * (bodies.states[b].angle - a0) + p.turn;
      p.rotation = angle == 0.0 ? Rot{} : MakeRot(angle);
    }
    if (step == 0) {
      for (PlaneContact& c : planes_) {
        const BodyPush& p = pushes_[c.body];
        if (!p.fixed) continue;
        c.world_normal = Rotate(p.rotation, c.normal);
        c.world_surface = p.center + Rotate(p.rotation, c.surface);
      }
    }
    const auto count = static_cast<std::uint32_t>(x_.size());
    PredictParticles(def.gravity, h, inv_mass_.data(), 0, count, x_.data(), v_.data(), previous_.data());
    for (int pass = 0; pass < def.particles.iterations; ++pass) {
      // Contacts between particles are swept forward and back on alternate passes (see
      // SolveParticleContacts); a soft body's own constraints go by colour (OrderByColour).
      const bool backward = (step * def.particles.iterations + pass) % 2 == 1;
      for (const SoftBodyId id : soft_live_ids_) {
        const SoftBody& soft = soft_[id.index];
        lambda_.assign(soft.edges.size() + soft.areas.size(), 0.0);
        SolveSoftBody(soft, h, x_, inv_mass_, lambda_, soft_scratch_);
      }
      if (FluidCount() > 0) SolveFluid(h, pushes_);
      SolveParticleContacts(backward);
      if (FluidCount() > 0) SolveRimContacts();
      SolveAttachments(h, pushes_);
      SolveBodyContacts(h, def.max_push_out_speed, pushes_);
    }
    VelocitiesOfMoves(h, x_.data(), previous_.data(), 0, count, v_.data());
    for (const SoftBodyId id : soft_live_ids_) DampSoftBody(soft_[id.index], h, x_, v_, inv_mass_);
  }
  if (FluidCount() > 0) {
    ApplyViscosity(def.dt);
    ApplyVorticity(def.dt);
    ReorderFluid(false);
  }
  // The bodies keep what the particles pushed them by; sleeping ones pushed hard enough wake.
  for (const BodyIndex b : touched_) {
    BodyPush& p = pushes_[b];
    p.touched = false;
    if (p.inv_mass > 0.0 || p.inv_inertia > 0.0) {
      BodyState& state = bodies.states[b];
      state.position += p.shift;
      state.angle += p.turn;
      state.velocity += p.velocity_change;
      state.angular_velocity += p.angular_velocity_change;
    } else if (!awake[b] && !HasInfiniteMass(bodies.infos[b]) &&
               p.sleeping_impulse * bodies.infos[b].inv_mass > def.sleep_speed) {
      to_wake->push_back(b);
    }
  }
}

void ParticleSystem::FindContacts(const WorldDef& def, const Bodies& bodies) {
  // How far a particle can go this step, bounding the pairs and planes found once per step.
  double fastest = 0.0;
  for (const Vec2& v : v_) fastest = std::max(fastest, LengthSquared(v));
  const double travel = (std::sqrt(fastest) + Length(def.gravity) * def.dt) * def.dt;
  const double kernel = FluidCount() > 0 ? KernelRadius(fluid_.spacing) : 0.0;
  // Pairs that may come within the kernel, or discs of different bodies within reach of
  // touching, this step: two particles closing at twice the fastest travel. Without fluid that
  // is the whole skin, so soft bodies never pass through each other unseen (capped, a soft ball
  // at 4 m/s sank a third of the contact distance into a soft box before it was found). With
  // fluid it is capped at a quarter of the kernel, since the lists would grow with the speed
  // squared: a pair missed then meets in mid-step and is pushed apart at the next.
  const double skin = kernel > 0.0 ? std::min(2.0 * travel, 0.25 * kernel) : 2.0 * travel;
  const double reach = std::max(kernel, 2.0 * largest_radius_) + skin;
  grid_.Build(x_, reach);
  if (FluidCount() > 0) {
    grid_.RenumberFrom(fluid_first_, &fluid_order_, &fluid_rows_);
    ReorderFluid(true);
  }
  // The fluid's particles need lists only for vorticity (its other passes go by pairs).
  const bool vorticity = std::any_of(fluid_.vorticity.begin(), fluid_.vorticity.end(), [](double v) { return v > 0.0; });
  fluid_pairs_ = grid_.FindNeighbours(x_, reach, *pool_, &neighbour_offsets_, &neighbours_, fluid_first_,
                                      vorticity ? static_cast<std::uint32_t>(x_.size()) : fluid_first_);
  if (FluidCount() > 0) FindChunks();
  planes_.clear();
  std::vector<BodyPlane> found;
  for (const BodyId id : bodies.live_ids) {
    const BodyIndex b = id.index;
    if (!bodies.enabled[b] || bodies.infos[b].is_sensor) continue;
    // The body's reach over the step: where it ends, grown by how far it came.
    const Vec2 moved = b < start_centers_.size() ? bodies.states[b].position - start_centers_[b] : Vec2{};
    // Fluid particles see a wall within the kernel's reach (it adds to their density).
    const double wall_reach = FluidCount() > 0 ? kernel : 0.0;
    const double margin = std::max(largest_radius_, wall_reach) + travel + Length(moved);
    AABB box = BoundsOf(bodies, b);
    box.lower -= Vec2{margin, margin};
    box.upper += Vec2{margin, margin};
    const geometry::Transform frame{bodies.states[b].position, MakeRot(bodies.states[b].angle)};
    grid_.ForEachInBox(box, [&](std::uint32_t i) {
      // A soft body fastened to a body does not collide with it (as a joint's bodies do not).
      if (group_[i] != kFluidGroup && soft_[group_[i]].def.attach_to &&
          soft_[group_[i]].def.attach_to->index == b) {
        return;
      }
      found.clear();
      const double reach_i = group_[i] == kFluidGroup ? std::max(0.0, kernel - radius_[i]) : 0.0;
      AppendBodyPlanes(bodies, b, x_[i], radius_[i], reach_i + travel + Length(moved), &found);
      for (const BodyPlane& plane : found) {
        planes_.push_back({i, b, InvRotate(frame.rotation, plane.normal),
                           geometry::InvTransformPoint(frame, plane.surface), std::sqrt(plane.friction * OwnFriction(i)),
                           Vec2{}, Vec2{}});
      }
    });
  }
}

void ParticleSystem::ReorderFluid(bool to_grid_order) {
  // Every per-particle array of the fluid, so that nothing read during the step need know.
  const auto reorder = [&](auto& values, std::size_t offset) {
    if (to_grid_order) {
      GatherInOrder(values, offset, fluid_order_);
    } else {
      ScatterFromOrder(values, offset, fluid_order_);
    }
  };
  reorder(x_, fluid_first_);
  reorder(v_, fluid_first_);
  reorder(inv_mass_, fluid_first_);
  reorder(radius_, fluid_first_);
  reorder(fluid_.rest_density, 0);
  reorder(fluid_.mass, 0);
  reorder(fluid_.viscosity, 0);
  reorder(fluid_.vorticity, 0);
  reorder(fluid_.friction, 0);
  reorder(fluid_.density, 0);
}

void ParticleSystem::FindChunks() {
  // Whole rows, so that a pair's higher particle (in its lower one's row or the next, since
  // the fluid is numbered row by row) lies at most in the next chunk's first row.
  const std::uint32_t first = fluid_first_, n = FluidCount();
  chunk_particles_.assign(1, 0);
  for (const std::uint32_t start : fluid_rows_) {
    if (start - chunk_particles_.back() >= kChunkParticles && start < n) chunk_particles_.push_back(start);
  }
  chunk_particles_.push_back(n);
  // Each chunk's first row but the first chunk's, where the chunk before may spill.
  spill_rows_.clear();
  for (std::size_t c = 1; c + 1 < chunk_particles_.size(); ++c) {
    const std::uint32_t begin = chunk_particles_[c];
    const auto next_row = std::upper_bound(fluid_rows_.begin(), fluid_rows_.end(), begin);
    spill_rows_.push_back({begin, next_row == fluid_rows_.end() ? n : std::min(*next_row, chunk_particles_[c + 1])});
  }
  // The fluid's pairs come sorted by their lower particle (FindNeighbours), so a chunk's pairs
  // are a run.
  chunk_pairs_.assign(1, 0);
  for (std::size_t c = 1; c < chunk_particles_.size(); ++c) {
    const auto begin = std::partition_point(fluid_pairs_.begin(), fluid_pairs_.end(), [&](const ParticlePair& p) {
      return p.first < chunk_particles_[c];
    });
    chunk_pairs_.push_back(static_cast<std::uint32_t>(begin - fluid_pairs_.begin()));
  }
  near_pairs_.resize(fluid_pairs_.size());
  near_dx_.resize(fluid_pairs_.size());
  near_dy_.resize(fluid_pairs_.size());
  near_r2_.resize(fluid_pairs_.size());
  near_counts_.resize(chunk_particles_.size() - 1);
  // A fluid of one kind (one block, or blocks of one density) takes its mass and density once
  // rather than per pair, four pairs at a time (AddDensityOfPairs): the same values, so the
  // same bits.
  inv_rest_.resize(n);
  one_kind_ = true;
  for (std::uint32_t f = 0; f < n; ++f) {
    inv_rest_[f] = 1.0 / fluid_.rest_density[f];
    one_kind_ &= (fluid_.mass[f] == fluid_.mass[0]) & (inv_mass_[first + f] == inv_mass_[first]) &
                 (inv_rest_[f] == inv_rest_[0]);
  }
}

PairOffsets ParticleSystem::NearOffsets(std::uint32_t chunk) {
  const std::uint32_t begin = chunk_pairs_[chunk];
  return {near_dx_.data() + begin, near_dy_.data() + begin, near_r2_.data() + begin};
}

std::span<const ParticlePair> ParticleSystem::NearPairs(std::uint32_t chunk) const {
  return std::span(near_pairs_).subspan(chunk_pairs_[chunk], near_counts_[chunk]);
}

void ParticleSystem::FindNearPairs(double h2, std::uint32_t chunk) {
  const std::uint32_t begin = chunk_pairs_[chunk], end = chunk_pairs_[chunk + 1];
  near_counts_[chunk] = PairsWithin(x_.data() + fluid_first_, std::span(fluid_pairs_).subspan(begin, end - begin), h2,
                                    near_pairs_.data() + begin, NearOffsets(chunk));
}

template <typename Visit>
void ParticleSystem::ForEachNearPair(const SphKernels& k, std::uint32_t chunk, bool with_gradients,
                                     Visit&& visit) const {
  // Each pair's kernel and gradient once for both its particles (the two sides differ only in
  // the gradient's sign), several pairs at a time: the square root and the division were most
  // of the density pass when worked out per list entry, one at a time.
  const double clumping_over_w = 1.0 / k.W(std::pow(kClumpingDistance * k.h, 2));
  const double clumping_strength = -kClumpingStrength / density_denominator_;
  constexpr std::uint32_t kBlock = 256;
  const Vec2* const x = x_.data() + fluid_first_;
  const ParticlePair* const near = near_pairs_.data() + chunk_pairs_[chunk];
  const std::uint32_t count = near_counts_[chunk];
  alignas(32) double dxs[kBlock + 4], dys[kBlock + 4], r2s[kBlock + 4];
  PairTerms terms[kBlock + 4];
  for (std::uint32_t begin = 0; begin < count; begin += kBlock) {
    const std::uint32_t m = std::min(kBlock, count - begin);
    for (std::uint32_t q = 0; q < m; ++q) {
      const auto [i, j] = near[begin + q];
      const Vec2 d = x[i] - x[j];
      dxs[q] = d.x, dys[q] = d.y, r2s[q] = LengthSquared(d);
    }
    // The lanes past the last pair work on a harmless stand-in and are not stored.
    for (std::uint32_t q = m; q < m + 4; ++q) dxs[q] = 0.0, dys[q] = 0.0, r2s[q] = k.h2;
    KernelTermsOfPairs(k, clumping_over_w, clumping_strength, with_gradients, {dxs, dys, r2s, m}, terms);
    for (std::uint32_t q = 0; q < m; ++q) {
      visit(fluid_first_ + near[begin + q].first, fluid_first_ + near[begin + q].second, terms[q]);
    }
  }
}

void ParticleSystem::SolveFluid(double h, std::vector<BodyPush>& pushes) {
  const SphKernels k(KernelRadius(fluid_.spacing));
  const std::uint32_t n = FluidCount();
  lambda_.resize(n);
  lambda_over_rest_.resize(n);
  FindWalls(pushes);
  DensityAndMoves(k, h, pushes);
}

void ParticleSystem::DensityAndMoves(const SphKernels& k, double h, std::vector<BodyPush>& pushes) {
  // Each pair adds into both its particles, in pair order (each particle's sums then go in the
  // order of its neighbour list): the pairs' terms are used as they are worked out, never
  // stored and looked up again. A chunk's pairs add into its own particles' sums, and into the
  // `spill` sums of the next chunk's first row, so that chunks can run on any threads; a
  // particle's sums are then its spill plus its own, the same bits with any thread count.
  const std::uint32_t first = fluid_first_, n = FluidCount();
  const auto chunks = static_cast<std::uint32_t>(chunk_particles_.size() - 1);
  const double epsilon = kRelaxation * density_denominator_;
  const double* const inv_mass = inv_mass_.data();
  const double* const mass = fluid_.mass.data();
  const double* const inv_rest = inv_rest_.data();
  const bool uniform = one_kind_;
  UniformPairs one_kind{k, mass[0], inv_mass[first], inv_rest[0], 1.0 / k.W(std::pow(kClumpingDistance * k.h, 2)),
                        -kClumpingStrength / density_denominator_, 0};
  pair_terms_.resize(3 * fluid_pairs_.size());
  // Each particle's density and multiplier (Macklin and Müller 2013, eq. 11).
  sums_.resize(n);
  spill_sums_.resize(n);
  for (const auto& [begin, end] : spill_rows_) std::fill(spill_sums_.begin() + begin, spill_sums_.begin() + end, DensitySums{});
  if (uniform) {
    InitialSums(one_kind, mass[0] * k.W(0.0, 0.0), fluid_.rest_density[0], wall_share_.data(), wall_slope_.data(), 0, n,
                sums_.data());
  } else {
    for (std::uint32_t f = 0; f < n; ++f) {
      sums_[f] = {fluid_.mass[f] * k.W(0.0, 0.0) + fluid_.rest_density[f] * wall_share_[f], wall_slope_[f], 0.0};
    }
  }
  DensitySums* const sums = sums_.data();
  DensitySums* const spill_sums = spill_sums_.data();
  const auto add = [](DensitySums& to, double density, Vec2 gradient, double denominator) {
    to.density += density;
    to.gradient += gradient;
    to.denominator += denominator;
  };
  pool_->ParallelFor(chunks, 2, [&](std::uint32_t c) {
    FindNearPairs(k.h2, c);
    const std::uint32_t own_end = chunk_particles_[c + 1];
    if (uniform) {
      UniformPairs chunk = one_kind;
      chunk.own_end = own_end;
      AddDensityOfPairs(chunk, x_.data() + first, NearPairs(c), NearOffsets(c), sums, spill_sums,
                        pair_terms_.data() + 3 * chunk_pairs_[c]);
      return;
    }
    ForEachNearPair(k, c, true, [&](std::uint32_t i, std::uint32_t j, const PairTerms& t) {
      // Soft particles meet the fluid by contact, not pressure: only fluid pairs come here.
      const std::uint32_t fi = i - first, fj = j - first;
      const Vec2 gi = (mass[fj] * inv_rest[fi]) * t.gradient, gj = (mass[fi] * inv_rest[fj]) * (-t.gradient);
      add(sums[fi], mass[fj] * t.weight, gi, inv_mass[j] * LengthSquared(gi));
      add(fj < own_end ? sums[fj] : spill_sums[fj], mass[fi] * t.weight, gj, inv_mass[i] * LengthSquared(gj));
    });
  });
  // A particle's sums are its spill plus its own (elsewhere the spill is nothing, and adding
  // +0 would change no bit).
  for (const auto& [begin, end] : spill_rows_) {
    for (std::uint32_t f = begin; f < end; ++f) {
      DensitySums& own = sums_[f];
      const DensitySums& spill = spill_sums_[f];
      own = {spill.density + own.density, spill.gradient + own.gradient, spill.denominator + own.denominator};
    }
  }
  moves_.resize(n);
  spill_moves_.resize(n);
  // A fluid of one kind's in blocks of particles, lanes at a time where the processor has them.
  const std::uint32_t blocks = (n + kMinParallel - 1) / kMinParallel;
  const auto block_end = [&](std::uint32_t b) { return std::min(n, (b + 1) * kMinParallel); };
  if (uniform) {
    pool_->ParallelFor(blocks, 2, [&](std::uint32_t b) {
      MultipliersOf(one_kind, sums_.data(), wall_denominator_.data(), epsilon, b * kMinParallel, block_end(b),
                    fluid_.density.data(), lambda_.data());
    });
    std::fill(moves_.begin(), moves_.end(), Vec2{});
  } else {
    pool_->ParallelFor(n, kMinParallel, [&](std::uint32_t f) {
      const DensitySums& sum = sums_[f];
      const double density = sum.density;
      const Vec2 gradient_i = sum.gradient;
      const double denominator =
          sum.denominator + (inv_mass[first + f] * LengthSquared(gradient_i) + wall_denominator_[f]);
      fluid_.density[f] = density;
      moves_[f] = Vec2{};
      // Only compression is pushed apart: a free surface, below the rest density, is left alone
      // rather than pulled together.
      const double c = std::max(0.0, density * inv_rest[f] - 1.0);
      lambda_[f] = -c / (denominator + epsilon);
      lambda_over_rest_[f] = lambda_[f] * inv_rest[f];
    });
  }
  // The walls' side (before any particle moves).
  PushWalls(h, pushes);
  // The moves (eq. 14 with unequal masses), with the artificial pressure against clumping.
  for (const auto& [begin, end] : spill_rows_) std::fill(spill_moves_.begin() + begin, spill_moves_.begin() + end, Vec2{});
  Vec2* const moves = moves_.data();
  Vec2* const spill_moves = spill_moves_.data();
  const double* const lambda = lambda_.data();
  const double* const lambda_over_rest = lambda_over_rest_.data();
  pool_->ParallelFor(chunks, 2, [&](std::uint32_t c) {
    const std::uint32_t own_end = chunk_particles_[c + 1];
    if (uniform) {
      UniformPairs chunk = one_kind;
      chunk.own_end = own_end;
      AddMovesOfPairs(chunk, x_.data() + first, NearPairs(c), lambda, pair_terms_.data() + 3 * chunk_pairs_[c], moves,
                      spill_moves);
      return;
    }
    ForEachNearPair(k, c, true, [&](std::uint32_t i, std::uint32_t j, const PairTerms& t) {
      const std::uint32_t fi = i - first, fj = j - first;
      const double weight_i = (lambda[fi] + t.clumping) * (mass[fj] * inv_rest[fi]) + mass[fi] * lambda_over_rest[fj];
      const double weight_j = (lambda[fj] + t.clumping) * (mass[fi] * inv_rest[fj]) + mass[fj] * lambda_over_rest[fi];
      moves[fi] += weight_i * t.gradient;
      (fj < own_end ? moves[fj] : spill_moves[fj]) += weight_j * (-t.gradient);
    });
  });
  for (const auto& [begin, end] : spill_rows_) {
    for (std::uint32_t f = begin; f < end; ++f) moves_[f] = spill_moves_[f] + moves_[f];
  }
  // Jacobi: a pair pushes each of its particles from both their constraints, which in a
  // uniformly squeezed fluid moves them twice as far as either needs; half of it converges.
  Vec2* const x = x_.data() + first;
  if (uniform) {
    pool_->ParallelFor(blocks, 2, [&](std::uint32_t b) {
      MoveParticles(one_kind, moves_.data(), lambda_.data(), wall_slope_.data(), kWallFactor, kJacobiShare,
                    b * kMinParallel, block_end(b), x);
    });
    return;
  }
  pool_->ParallelFor(n, kMinParallel, [&](std::uint32_t f) {
    const Vec2 delta = inv_mass[first + f] * (moves_[f] + kWallFactor * lambda_[f] * wall_slope_[f]);
    x[f] += kJacobiShare * delta;
  });
}

void ParticleSystem::FindWalls(std::vector<BodyPush>& pushes) {
  const std::uint32_t first = fluid_first_, n = FluidCount();
  wall_share_.assign(n, 0.0);
  wall_slope_.assign(n, Vec2{});
  wall_denominator_.assign(n, 0.0);
  // Each fluid plane's distance, then how many particles each body has within reach (the
  // count mass splitting needs before any particle's share is worked out).
  wall_distances_.resize(planes_.size());
  for (const PlaneContact& c : planes_) pushes[c.body].wall_particles = 0;
  for (std::size_t k = 0; k < planes_.size(); ++k) {
    const PlaneContact& c = planes_[k];
    if (c.particle < first) continue;
    const BodyPush& body = pushes[c.body];
    wall_distances_[k] = body.fixed ? Dot(c.world_normal, x_[c.particle] - c.world_surface)
                                    : Dot(Rotate(body.rotation, c.normal),
                                          x_[c.particle] - (body.center + Rotate(body.rotation, c.surface)));
    if (wall_distances_[k] < wall_->Reach()) ++pushes[c.body].wall_particles;
  }
  for (std::size_t k = 0; k < planes_.size(); ++k) {
    const PlaneContact& c = planes_[k];
    if (c.particle < first) continue;
    const BodyPush& body = pushes[c.body];
    const double d = wall_distances_[k];
    if (d >= wall_->Reach()) continue;
    const std::uint32_t f = c.particle - first;
    const Vec2 normal = body.fixed ? c.world_normal : Rotate(body.rotation, c.normal);
    const double slope = wall_scale_ * wall_->Slope(d);
    wall_share_[f] += wall_scale_ * wall_->Share(d);
    wall_slope_[f] += slope * normal;  // ∂share/∂x: the wall's pull on C
    // A fixed body's give is +0 (adding it changes no bit: the sum is never −0).
    if (body.fixed) continue;
    // A body that moves gives way: its generalised inverse mass joins the denominator, times
    // the particles pushing it at once (mass splitting, Tonge, Benevolenskiy and Jehle 2012),
    // so that their pushes together cannot overshoot what a light body needs. Without it a
    // crate of 80 kg squeezed by a wave against a wall gained speed each step until 1e10 m/s.
    const double rn = Cross(Rotate(body.rotation, c.surface), normal);
    const double give = body.inv_mass + body.inv_inertia * rn * rn;
    wall_denominator_[f] += body.wall_particles * give * slope * slope;
  }
}

void ParticleSystem::PushWalls(double h, std::vector<BodyPush>& pushes) {
  // The walls' side of the density constraints: a particle pressed against a body pushes it
  // back with the impulse that moves the particle away (how water holds a crate up).
  const std::uint32_t first = fluid_first_;
  for (const PlaneContact& c : planes_) {
    if (c.particle < first) continue;
    const std::uint32_t f = c.particle - first;
    if (lambda_[f] == 0.0) continue;
    BodyPush& body = pushes[c.body];
    // A fixed body's pose, velocity and turn would change by ±0 at most, leaving the same
    // bits: its centre is never −0 (the substep's pose adds +0 shifts), and its velocity and
    // turn changes start at +0, which adding or taking away a zero keeps.
    if (body.fixed) continue;
    const Vec2 normal = Rotate(body.rotation, c.normal);
    const Vec2 arm = Rotate(body.rotation, c.surface);
    const double d = Dot(normal, x_[c.particle] - (body.center + arm));
    if (d >= wall_->Reach()) continue;
    const double impulse_h = kWallFactor * kJacobiShare * lambda_[f] * wall_scale_ * wall_->Slope(d);
    if (impulse_h > 0.0) PushBody(body, arm, normal, impulse_h, h);
  }
}

void ParticleSystem::SolveParticleContacts(bool backward) {
  // Discs of different bodies (two soft bodies, or a soft body and the fluid) keep apart; each
  // pair once, from its lower-numbered particle (a fluid particle's pairs from the soft side).
  // Gauss-Seidel leans the way it sweeps: in index order every substep, a soft box landing flat
  // on another was pushed sideways and tipped. Swept back every other pass, the lean cancels.
  const std::uint32_t n = fluid_first_;
  for (std::uint32_t s = 0; s < n; ++s) {
    const std::uint32_t i = backward ? n - 1 - s : s;
    const std::uint32_t begin = neighbour_offsets_[i], end = neighbour_offsets_[i + 1];
    for (std::uint32_t k = 0; k < end - begin; ++k) {
      const std::uint32_t j = neighbours_[backward ? end - 1 - k : begin + k];
      if ((j < n && j <= i) || group_[j] == group_[i]) continue;
      SolveParticlePair(i, j);
    }
  }
}

void ParticleSystem::SolveParticlePair(std::uint32_t i, std::uint32_t j) {
  const Vec2 d = x_[j] - x_[i];
  const double reach = radius_[i] + radius_[j];
  const double r2 = LengthSquared(d);
  if (r2 >= reach * reach || r2 == 0.0) return;
  const double w = inv_mass_[i] + inv_mass_[j];
  if (w == 0.0) return;
  const double r = std::sqrt(r2);
  const Vec2 n = d / r;
  const double push = (reach - r) / w;
  x_[i] -= (inv_mass_[i] * push) * n;
  x_[j] += (inv_mass_[j] * push) * n;
  // Friction as against a body (SolveBodyContacts): the pair's slide over each other this
  // substep taken away up to μ times the push, μ the geometric mean of the two materials'.
  const double friction = std::sqrt(OwnFriction(i) * OwnFriction(j));
  if (friction == 0.0) return;
  const Vec2 slide = (x_[j] - previous_[j]) - (x_[i] - previous_[i]);
  const Vec2 tangent_slide = slide - Dot(slide, n) * n;
  const double length = Length(tangent_slide);
  if (length == 0.0) return;
  const Vec2 t = tangent_slide / length;
  const double tangential = std::min(length, friction * (reach - r)) / w;
  x_[i] += (inv_mass_[i] * tangential) * t;
  x_[j] -= (inv_mass_[j] * tangential) * t;
}

void ParticleSystem::SolveRimContacts() {
  // Fluid against each soft body's rim as a chain of capsules, not only of discs: where the rim
  // is stretched its discs part, and fluid went between them (a quarter of a block poured into
  // a soft ring ended outside it). A fluid particle is taken from the neighbours of the end of
  // the edge it lies nearer, so each pair is solved once; its contacts with the discs at the
  // ends are SolveParticleContacts'.
  for (const SoftBodyId id : soft_live_ids_) {
    const SoftBody& soft = soft_[id.index];
    const std::size_t n = soft.outline.size();
    for (std::size_t k = 0; k < n; ++k) {
      const std::uint32_t a = soft.first + soft.outline[k], b = soft.first + soft.outline[(k + 1) % n];
      for (const std::uint32_t end : {a, b}) {
        for (std::uint32_t e = neighbour_offsets_[end]; e < neighbour_offsets_[end + 1]; ++e) {
          const std::uint32_t j = neighbours_[e];
          if (j >= fluid_first_) SolveRimPair(a, b, j, end == a);
        }
      }
    }
  }
}

void ParticleSystem::SolveRimPair(std::uint32_t a, std::uint32_t b, std::uint32_t j, bool near_a) {
  const Vec2 edge = x_[b] - x_[a];
  const double length2 = LengthSquared(edge);
  if (length2 == 0.0) return;
  const double t = Dot(x_[j] - x_[a], edge) / length2;
  // Inside the edge only (the ends are discs), and from the nearer end's neighbours only.
  if (t <= 0.0 || t >= 1.0 || (t <= 0.5) != near_a) return;
  const Vec2 d = x_[j] - (x_[a] + t * edge);
  const double reach = (1.0 - t) * radius_[a] + t * radius_[b] + radius_[j];
  const double r2 = LengthSquared(d);
  if (r2 >= reach * reach || r2 == 0.0) return;
  // C = |x_j − (x_a + t·(x_b − x_a))| − reach, t held: gradients n, −(1 − t)·n, −t·n.
  const double w = inv_mass_[j] + (1.0 - t) * (1.0 - t) * inv_mass_[a] + t * t * inv_mass_[b];
  if (w == 0.0) return;
  const double r = std::sqrt(r2);
  const Vec2 normal = d / r;
  const double push = (reach - r) / w;
  x_[j] += (inv_mass_[j] * push) * normal;
  x_[a] -= ((1.0 - t) * inv_mass_[a] * push) * normal;
  x_[b] -= (t * inv_mass_[b] * push) * normal;
}

double ParticleSystem::OwnFriction(std::uint32_t i) const {
  return group_[i] == kFluidGroup ? fluid_.friction[i - fluid_first_] : soft_[group_[i]].def.friction;
}

void ParticleSystem::PushBody(BodyPush& body, Vec2 arm, Vec2 direction, double impulse_h, double h) {
  // impulse_h is the impulse times h (XPBD's Δλ): the body moves by its share of the
  // correction now, and keeps the impulse's velocity.
  const double turn = body.inv_inertia * Cross(arm, direction) * impulse_h;
  body.shift -= (body.inv_mass * impulse_h) * direction;
  body.turn -= turn;
  body.velocity_change -= (body.inv_mass * impulse_h / h) * direction;
  body.angular_velocity_change -= turn / h;
  body.center -= (body.inv_mass * impulse_h) * direction;
  if (turn != 0.0) body.rotation = geometry::MulRot(MakeRot(-turn), body.rotation);
  body.sleeping_impulse += impulse_h / h;
}

void ParticleSystem::SolveBodyContacts(double h, double max_push_out_speed, std::vector<BodyPush>& pushes) {
  for (const PlaneContact& c : planes_) {
    BodyPush& body = pushes[c.body];
    const std::uint32_t i = c.particle;
    // A fluid particle clear of a fixed body, found without turning its plane each substep.
    if (body.fixed && i >= fluid_first_ && Dot(c.world_normal, x_[i] - c.world_surface) - radius_[i] >= 0.0) continue;
    const Vec2 n = Rotate(body.rotation, c.normal);
    const Vec2 surface_arm = Rotate(body.rotation, c.surface);
    const double gap = Dot(n, x_[i] - (body.center + surface_arm)) - radius_[i];
    // A soft particle that began the substep inside the body (a body made overlapping a soft
    // one, or slipped between its particles) comes out no faster than max_push_out_speed, as
    // rigid bodies do: resolved at once, a depth d became a speed d/h, and a plank made inside
    // a blown-up soft ball was shot out at hundreds of m/s. New contacts are solved in full.
    double allowed = 0.0;
    if (i < fluid_first_) {
      const Vec2 n_before = Rotate(body.last_rotation, c.normal);
      const Vec2 surface_before = body.last_center + Rotate(body.last_rotation, c.surface);
      const double gap_before = Dot(n_before, previous_[i] - surface_before) - radius_[i];
      allowed = std::min(0.0, gap_before + max_push_out_speed * h);
    }
    if (gap >= allowed) continue;
    const double wp = inv_mass_[i];
    const double rn = Cross(surface_arm, n);
    const double w = wp + body.inv_mass + body.inv_inertia * rn * rn;
    if (w == 0.0) continue;
    const double depth = allowed - gap;
    const double normal = depth / w;
    x_[i] += (wp * normal) * n;
    if (!body.fixed) PushBody(body, surface_arm, n, normal, h);
    if (c.friction == 0.0) continue;
    // Friction: the particle's slide over the surface this substep (the surface moving with
    // the body) is taken away up to μ times the normal correction (Macklin et al. 2014,
    // "Unified particle physics for real-time applications", §6.1).
    const Vec2 surface_now = body.center + Rotate(body.rotation, c.surface);
    const Vec2 surface_before = body.last_center + Rotate(body.last_rotation, c.surface);
    const Vec2 slide = (x_[i] - previous_[i]) - (surface_now - surface_before);
    const Vec2 tangent_slide = slide - Dot(slide, n) * n;
    const double length = Length(tangent_slide);
    if (length == 0.0) continue;
    const Vec2 t = tangent_slide / length;
    const double rt = Cross(surface_arm, t);
    const double wt = wp + body.inv_mass + body.inv_inertia * rt * rt;
    const double tangential = std::min(length, c.friction * depth) / wt;
    x_[i] -= (wp * tangential) * t;
    if (!body.fixed) PushBody(body, surface_arm, -t, tangential, h);
  }
}

void ParticleSystem::SolveAttachments(double h, std::vector<BodyPush>& pushes) {
  for (const SoftBodyId id : soft_live_ids_) {
    const SoftBody& soft = soft_[id.index];
    for (const SoftAttachment& a : soft.attachments) {
      BodyPush& body = pushes[a.body];
      const std::uint32_t i = soft.first + a.particle;
      const Vec2 arm = Rotate(body.rotation, a.local);
      const Vec2 error = x_[i] - (body.center + arm);
      // The point-to-point row pair: K = (wp + wb)·1 + I⁻¹·perp(r)·perp(r)ᵀ, solved exactly.
      const double wp = inv_mass_[i], wb = body.inv_mass, wi = body.inv_inertia;
      const double k11 = wp + wb + wi * arm.y * arm.y, k22 = wp + wb + wi * arm.x * arm.x;
      const double k12 = -wi * arm.x * arm.y;
      const double det = k11 * k22 - k12 * k12;
      if (det <= 0.0) continue;
      // The correction impulse (× h) that moves the particle towards the body point.
      const Vec2 impulse{-(k22 * error.x - k12 * error.y) / det, -(k11 * error.y - k12 * error.x) / det};
      x_[i] += wp * impulse;
      const double size = Length(impulse);
      if (size > 0.0) PushBody(body, arm, impulse / size, size, h);
    }
  }
}

void ParticleSystem::ApplyViscosity(double dt) {
  // XSPH (Schechter and Bridson 2012; PBF §5): each velocity moves towards its neighbours' kernel
  // mean, by the block's share per 1/60 s.
  const SphKernels k(KernelRadius(fluid_.spacing));
  const std::uint32_t first = fluid_first_, n = FluidCount();
  delta_.assign(n, Vec2{});
  // The share per viscosity: a block's particles share one, so pow runs once per block.
  shares_.resize(n);
  for (std::uint32_t f = 0; f < n; ++f) {
    shares_[f] = f > 0 && fluid_.viscosity[f] == fluid_.viscosity[f - 1]
                     ? shares_[f - 1]
                     : 1.0 - std::pow(1.0 - fluid_.viscosity[f], 60.0 * dt);
  }
  // Each pair within the kernel adds into both its particles, as in DensityAndMoves.
  moves_.assign(n, Vec2{});
  spill_moves_.resize(n);
  for (const auto& [begin, end] : spill_rows_) std::fill(spill_moves_.begin() + begin, spill_moves_.begin() + end, Vec2{});
  Vec2* const pulls = moves_.data();
  Vec2* const spill_pulls = spill_moves_.data();
  const double* const mass = fluid_.mass.data();
  const double* const density = fluid_.density.data();
  // Each particle's m/ρ, as the pairs take it.
  mass_over_density_.resize(n);
  for (std::uint32_t f = 0; f < n; ++f) mass_over_density_[f] = mass[f] / density[f];
  // Masses and densities come per particle here, so any fluid takes the four-lane loop.
  pool_->ParallelFor(static_cast<std::uint32_t>(chunk_particles_.size() - 1), 2, [&](std::uint32_t c) {
    FindNearPairs(k.h2, c);
    UniformPairs chunk{k, 0.0, 0.0, 0.0, 0.0, 0.0, chunk_particles_[c + 1]};
    AddPullsOfPairs(chunk, x_.data() + first, v_.data() + first, mass_over_density_.data(), NearPairs(c),
                    NearOffsets(c), pulls, spill_pulls);
  });
  for (const auto& [begin, end] : spill_rows_) {
    for (std::uint32_t f = begin; f < end; ++f) moves_[f] = spill_moves_[f] + moves_[f];
  }
  pool_->ParallelFor(n, kMinParallel, [&](std::uint32_t f) {
    delta_[f] = fluid_.viscosity[f] == 0.0 ? Vec2{} : shares_[f] * moves_[f];
  });
  for (std::uint32_t f = 0; f < n; ++f) v_[first + f] += delta_[f];
}

void ParticleSystem::ApplyVorticity(double dt) {
  // Vorticity confinement (Fedkiw, Stam and Jensen 2001; PBF §6): the swirl viscosity and the
  // solver damp is put back, pushing towards where the curl is larger.
  const std::uint32_t first = fluid_first_, n = FluidCount();
  bool any = false;
  for (std::uint32_t f = 0; f < n && !any; ++f) any = fluid_.vorticity[f] > 0.0;
  if (!any) return;
  const SphKernels k(KernelRadius(fluid_.spacing));
  omega_.assign(n, 0.0);
  pool_->ParallelFor(n, kMinParallel, [&](std::uint32_t f) {
    const std::uint32_t i = first + f;
    double curl = 0.0;
    for (std::uint32_t a = neighbour_offsets_[i]; a < neighbour_offsets_[i + 1]; ++a) {
      const std::uint32_t j = neighbours_[a];
      if (j < first) continue;
      const Vec2 d = x_[i] - x_[j];
      const double r = Length(d);
      const std::uint32_t g = j - first;
      curl += fluid_.mass[g] / fluid_.density[g] * Cross(v_[j] - v_[i], k.Gradient(d, r));
    }
    omega_[f] = curl;
  });
  pool_->ParallelFor(n, kMinParallel, [&](std::uint32_t f) {
    if (fluid_.vorticity[f] == 0.0) return;
    const std::uint32_t i = first + f;
    Vec2 towards;  // the gradient of |ω|
    for (std::uint32_t a = neighbour_offsets_[i]; a < neighbour_offsets_[i + 1]; ++a) {
      const std::uint32_t j = neighbours_[a];
      if (j < first) continue;
      const Vec2 d = x_[i] - x_[j];
      const std::uint32_t g = j - first;
      towards += (fluid_.mass[g] / fluid_.density[g] * std::abs(omega_[g])) * k.Gradient(d, Length(d));
    }
    const double length = Length(towards);
    if (length == 0.0) return;
    const Vec2 nn = towards / length;
    // N × ω for ω along z: (N.y·ω, −N.x·ω).
    v_[i] += (dt * fluid_.vorticity[f] * omega_[f]) * Vec2{nn.y, -nn.x};
  });
}

}  // namespace engine::detail
