// The particles of soft bodies and fluid, and their step: substeps of prediction, XPBD soft
// constraints, PBF density constraints, particle contacts and contacts with the rigid bodies,
// which are pushed back (two-way coupling). Runs after the rigid bodies' step. Internal.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "bodies.h"
#include "engine/ids.h"
#include "engine/particles.h"
#include "engine/world_def.h"
#include "parallel/worker_pool.h"
#include "particles/body_contact.h"
#include "particles/fluid_pairs.h"
#include "particles/near_pairs.h"
#include "particles/particle_grid.h"
#include "particles/sph_kernels.h"
#include "particles/soft_bodies.h"

namespace engine::detail {

class ByteWriter;
class ByteReader;

/// The fluid's per-particle constants, in FluidPositions order.
struct FluidParticles {
  std::vector<double> rest_density;  ///< kg/m²
  std::vector<double> mass;          ///< kg
  std::vector<double> viscosity;
  std::vector<double> vorticity;
  std::vector<double> friction;
  std::vector<double> density;       ///< kg/m², as last measured
  double spacing = 0.0;              ///< shared by every block
};

class ParticleSystem {
 public:
  // Soft bodies, by slot.
  SoftBodyId CreateSoftBody(const SoftBodyDef& def, const Bodies& bodies);
  void DestroySoftBody(std::uint32_t slot);
  bool IsLive(SoftBodyId id) const {
    return id.index < soft_.size() && soft_alive_[id.index] && soft_generations_[id.index] == id.generation;
  }
  std::span<const SoftBodyId> SoftBodyIds() const { return soft_live_ids_; }
  const SoftBody& Soft(std::uint32_t slot) const { return soft_[slot]; }
  /// Removes the attachments to a body that goes (its particles come free).
  void DetachFrom(BodyIndex body);

  std::size_t AddFluid(const FluidDef& def);
  const FluidParticles& Fluid() const { return fluid_; }
  std::uint32_t FluidFirst() const { return fluid_first_; }
  std::uint32_t FluidCount() const { return static_cast<std::uint32_t>(x_.size()) - fluid_first_; }

  std::span<const Vec2> Positions() const { return x_; }
  std::span<const Vec2> Velocities() const { return v_; }
  void ApplyImpulse(std::uint32_t particle, Vec2 impulse) { v_[particle] += inv_mass_[particle] * impulse; }
  bool Empty() const { return x_.empty(); }
  /// Whether the world ever had a soft body or fluid (snapshots carry them from then on).
  bool EverUsed() const { return ever_used_; }

  /// Before the rigid bodies step: where they start, so the particles see them move through
  /// the step rather than jump to where it ends.
  void MarkStepStart(const Bodies& bodies);
  /// One step of dt: the particles move, and push the bodies they touch (velocity, and the
  /// position they were pushed by). Appends to `to_wake` the sleeping bodies pushed hard enough
  /// to wake.
  void Step(const WorldDef& def, Bodies& bodies, std::span<const std::uint8_t> awake, WorkerPool& pool,
            std::vector<BodyIndex>* to_wake);

  void Save(ByteWriter& out) const;
  bool Load(ByteReader& in, const Bodies& bodies);

 private:
  /// A rigid body as the particles see it during a step: moving from where it started to
  /// where the rigid step left it, plus what the particles pushed it by.
  struct BodyPush {
    double inv_mass = 0.0;     ///< 0 for static, kinematic and sleeping bodies
    double inv_inertia = 0.0;
    Vec2 end_center;           ///< the centre of mass where the rigid step left it
    Vec2 shift;                ///< how far the particles moved it beyond the rigid step's motion
    double turn = 0.0;         ///< and turned it
    Vec2 velocity_change;      ///< from the particles' impulses
    double angular_velocity_change = 0.0;
    double sleeping_impulse = 0.0;  ///< N·s pushed into a sleeping body, for waking it
    std::uint32_t wall_particles = 0;  ///< fluid particles within its reach this substep
    // Its pose this substep and the last one.
    Vec2 center, last_center;
    Rot rotation, last_rotation;
    bool touched = false;
    /// It does not move through the step, and nothing the particles do moves it or is read
    /// from it (a static body, or a kinematic one or an awake one of infinite mass at rest):
    /// its pose is the same bits every substep, and pushing it changes only signs of zeros that
    /// are never read (see PushWalls).
    bool fixed = false;
  };
  /// A body face a particle may touch this step, in the body's centre-of-mass frame.
  struct PlaneContact {
    std::uint32_t particle;
    BodyIndex body;
    Vec2 normal;   ///< local
    Vec2 surface;  ///< local
    double friction;
    /// A fixed body's (BodyPush::fixed) normal and surface point in the world, as each substep
    /// would work them out: once a step.
    Vec2 world_normal, world_surface;
  };
  void InsertParticles(std::uint32_t at, std::span<const Vec2> positions, Vec2 velocity, double inv_mass,
                       double radius, std::uint32_t group);
  void FindContacts(const WorldDef& def, const Bodies& bodies);
  /// The fluid's particles into the grid's order for the step (fluid_order_), or back into
  /// their own order (as FluidPositions lists them) after it.
  void ReorderFluid(bool to_grid_order);
  double LatticeKernelSum() const;
  /// The constants that follow from the fluid's spacing (set) and its first block's density.
  void SetUpFluidKernel(double first_density);
  void SolveFluid(double h, std::vector<BodyPush>& pushes);
  /// SolveFluid's density and move passes, the walls' side (PushWalls) between them, and the
  /// particles moved.
  void DensityAndMoves(const SphKernels& k, double h, std::vector<BodyPush>& pushes);
  /// The fluid's pairs (fluid_pairs_) in chunks of whole rows of the grid (chunk_particles_,
  /// chunk_pairs_), after FindNeighbours.
  void FindChunks();
  /// near_pairs_ and near_counts_ of chunk `chunk` for the particles where they are now.
  void FindNearPairs(double h2, std::uint32_t chunk);
  std::span<const ParticlePair> NearPairs(std::uint32_t chunk) const;
  PairOffsets NearOffsets(std::uint32_t chunk);
  /// Calls visit(i, j, terms) for each of chunk `chunk`'s near pairs (FindNearPairs), in pair
  /// order, with its kernel terms (only the weight unless `with_gradients`).
  template <typename Visit>
  void ForEachNearPair(const SphKernels& k, std::uint32_t chunk, bool with_gradients, Visit&& visit) const;
  /// Each fluid particle's share of its kernel filled by the bodies near it, and its slope.
  void FindWalls(std::vector<BodyPush>& pushes);
  void PushWalls(double h, std::vector<BodyPush>& pushes);
  /// `backward`: the particles, and their pairs, in reverse order.
  void SolveParticleContacts(bool backward);
  void SolveParticlePair(std::uint32_t i, std::uint32_t j);
  /// Fluid particles against the soft bodies' rims taken as capsules between their particles.
  void SolveRimContacts();
  /// Fluid particle j against the rim edge from particle a to b (`near_a`: found among a's
  /// neighbours), if it lies nearer that end.
  void SolveRimPair(std::uint32_t a, std::uint32_t b, std::uint32_t j, bool near_a);
  /// The friction of particle i's material: its soft body's, or its fluid block's.
  double OwnFriction(std::uint32_t i) const;
  /// The body's side of a correction: `impulse_h` (impulse × h) against `direction` at `arm`.
  static void PushBody(BodyPush& body, Vec2 arm, Vec2 direction, double impulse_h, double h);
  void SolveBodyContacts(double h, double max_push_out_speed, std::vector<BodyPush>& pushes);
  void SolveAttachments(double h, std::vector<BodyPush>& pushes);
  void ApplyViscosity(double dt);
  void ApplyVorticity(double dt);

  // Every particle of the soft bodies (first, body by body) and the fluid (after).
  std::vector<Vec2> x_, v_, previous_;
  std::vector<double> inv_mass_, radius_;
  std::vector<std::uint32_t> group_;  ///< the soft body's slot, or kFluidGroup
  double largest_radius_ = 0.0;

  std::vector<SoftBody> soft_;
  std::vector<std::uint32_t> soft_generations_;
  std::vector<std::uint8_t> soft_alive_;
  std::vector<std::uint32_t> soft_free_;
  std::vector<SoftBodyId> soft_live_ids_;
  std::uint32_t fluid_first_ = 0;
  FluidParticles fluid_;
  double density_denominator_ = 0.0;  ///< the PBF denominator of a particle inside a perfect lattice
  std::optional<WallShare> wall_;
  double wall_scale_ = 0.0;
  bool ever_used_ = false;

  // The step's scratch.
  ParticleGrid grid_;
  /// This step's order of the fluid's particles, by grid cell, so that neighbours lie near in
  /// memory: each one's own number (less fluid_first_); and where each row of cells begins.
  std::vector<std::uint32_t> fluid_order_, fluid_rows_;
  std::vector<std::uint32_t> neighbour_offsets_, neighbours_;
  std::vector<PlaneContact> planes_;
  std::vector<Vec2> start_centers_;
  std::vector<double> start_angles_;
  std::vector<BodyPush> pushes_;
  std::vector<BodyIndex> touched_;
  std::vector<double> omega_;
  std::vector<double> shares_, mass_over_density_;  ///< ApplyViscosity's, per particle
  std::vector<double> lambda_;
  WorkerPool* pool_ = nullptr;  ///< the step's (WorldDef::threads)
  std::vector<double> lambda_over_rest_;  ///< each fluid particle's λ/ρ0, for its neighbours' moves
  /// Each pair of two fluid particles once (i < j), by their lower particle, numbered from
  /// fluid_first_ (the grid's, until its next search).
  std::span<const ParticlePair> fluid_pairs_;
  /// The fluid's pairs in chunks, each summed on one thread: chunk c holds the fluid particles
  /// [chunk_particles_[c], chunk_particles_[c + 1]) (less fluid_first_), whole rows of the
  /// grid, and fluid_pairs_[chunk_pairs_[c], chunk_pairs_[c + 1]), whose lower particles are
  /// those. A pair's higher particle lies in the same chunk or in the next one's first row: it
  /// adds into the `spill` sums there, which no other chunk writes (see DensityAndMoves).
  std::vector<std::uint32_t> chunk_particles_, chunk_pairs_;
  /// The particles [begin, end) (from fluid_first_) that the chunk before theirs may spill into.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> spill_rows_;
  /// Each chunk's pairs within the kernel this substep: near_counts_[c] of them from
  /// near_pairs_[chunk_pairs_[c]], with their terms from pair_terms_[3 · chunk_pairs_[c]] once
  /// the density pass has found them.
  std::vector<ParticlePair> near_pairs_;
  std::vector<double> near_dx_, near_dy_, near_r2_;  ///< their offsets (PairsWithin)
  std::vector<double> pair_terms_;
  std::vector<std::uint32_t> near_counts_;
  std::vector<DensitySums> sums_, spill_sums_;
  std::vector<Vec2> moves_, spill_moves_;
  std::vector<double> inv_rest_;  ///< each fluid particle's 1 / rest density
  bool one_kind_ = false;         ///< every fluid particle has the same mass and rest density
  std::vector<double> wall_share_;
  std::vector<Vec2> wall_slope_;
  std::vector<double> wall_distances_;    ///< per plane, this substep (fluid particles' only)
  std::vector<double> wall_denominator_;  ///< the pushed bodies' part of each PBF denominator
  std::vector<Vec2> delta_, soft_scratch_;
};

inline constexpr std::uint32_t kFluidGroup = 0xffffffffu;

}  // namespace engine::detail
