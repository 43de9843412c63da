// The world's settings: gravity, the step, and the methods that run it.
#pragma once

#include <cstdint>

#include "engine/math.h"

namespace engine {

enum class Integrator : std::uint8_t {
  kSemiImplicitEuler,  ///< velocity first, then position with the new velocity (symplectic)
  kExplicitEuler,      ///< position with the old velocity, then velocity (the seed's)
  kVelocityVerlet,     ///< position by the old acceleration, velocity by the mean of old and new
  kMidpoint,           ///< explicit second-order Runge-Kutta through the midpoint
  kRungeKutta4,        ///< the classic fourth-order Runge-Kutta
};

enum class ContactSolver : std::uint8_t {
  /// An impact pass for bounces, then substeps of warm-started rigid contacts with shock
  /// propagation and a split-impulse push-out (after Catto's "soft step")
  kSubstep,
  /// Rounds of sequential impulses per step, then a projection of the overlap: the baseline
  /// (the course's seed method; scene files call it "sequential_impulse" or "seed")
  kSequentialImpulse,
};

enum class BroadPhaseType : std::uint8_t {
  /// All pairs for a handful of bodies; beyond, the AABB tree while bodies mostly stay inside
  /// their fat boxes (resting, settling) and the uniform grid while many move (docs/broadphase.md)
  kAuto,
  kAllPairs,
  kSweepAndPrune,
  kUniformGrid,
  kQuadtree,
  kAabbTree,
};

/// The substep solver's optional mechanisms. Each runs only where a step needs it (the solver
/// decides once per step, docs/architecture.md); these switches turn one off everywhere, for
/// benchmarks and tests that measure what it buys.
struct SubstepFeatures {
  bool impact_pass = true;        ///< bounces: restitution resolved as impacts before the solve
  bool shock_propagation = true;  ///< stacks held from the ground up (needs gravity: an up)
  bool direct_solve = true;       ///< turning islands with a 10:1 mass ratio solved exactly
  /// where no applied force acts, the contacts never add kinetic energy (warm start scaled, and a
  /// last check per substep)
  bool energy_limit = true;
  bool block_solver = true;       ///< both points of a turning pair's contact solved together
  /// where nothing can turn, contacts visited by colour; where things turn, from 256 contacts of
  /// circles alone (then WorldDef::circle_velocity_iterations apply), the same
  bool colour_order = true;
  /// Where gravity loads every body: how many contacts are solved at once, side by side in SIMD
  /// lanes (a colour's where nothing can turn, four strips' or a colour's where every contact turns
  /// and there are at least 256, docs/solver.md "The wide solver: SIMD lanes"). 0: the widest
  /// the processor has (4 with AVX2, 2 on other x86-64, 1 elsewhere); 1: one at a time, without
  /// the lanes' layout; 2 or 4 (SSE2, AVX2; a width the processor lacks falls back to the widest
  /// it has). The bits are the same at every width. Joints too, with or without gravity, where
  /// bodies turn and at least 256 revolute joints without motor or limits act: those are always
  /// solved in colour order, and 1 takes them one lane at a time in that order.
  int lanes = 0;
};

/// How the particles of soft bodies and fluid are stepped: after the rigid bodies, in substeps
/// of at most `substep` seconds (Macklin et al. 2019, "Small steps in physics simulation"), so a
/// soft body's stiffness and a fluid's pressure come out the same whatever the world's dt.
struct ParticleSettings {
  double substep = 1.0 / 480.0;  ///< s: the longest substep; a step takes ceil(dt / substep)
  int iterations = 1;            ///< constraint passes per substep (more: stiffer sooner, no change at rest)
};

/// The most threads a world may use (WorldDef::threads).
inline constexpr int kMaxThreads = 256;

struct WorldDef {
  Vec2 gravity{0.0, -9.8};              ///< m/s²
  double fluid_density = 0.0;           ///< kg/m³ of the air or water around; 0: vacuum, no drag
  double gravitational_constant = 0.0;  ///< N·m²/kg² between bodies; 0: no mutual gravitation
  double dt = 1.0 / 60.0;               ///< the fixed step, s
  /// Threads (≥ 1, the caller's included) that share the step: the contact solve's colours, the
  /// fluid's per-particle passes, the effect particles' motion and bounces. The state is the
  /// same bits with any count: work is split only where no two pieces touch the same body or
  /// particle, and each piece's arithmetic runs in the same order on any thread.
  int threads = 1;
  /// With threads > 1: where the other threads are kept from running for several steps in a row
  /// (another program holds their cores: two threads on two cores, one of them busy, took 2.7
  /// times one thread's time), step on the calling thread alone for a while, then try them again.
  /// The state is the same bits either way. false: always share them.
  bool adapt_threads = true;
  bool rotation = false;                ///< false: the axis-aligned game, no angular work at all
  Integrator integrator = Integrator::kSemiImplicitEuler;
  BroadPhaseType broad_phase = BroadPhaseType::kAuto;
  ContactSolver solver = ContactSolver::kSubstep;
  int substeps = 0;                     ///< substep solver: substeps per step; 0: 4, or 8 with rotation
  /// m/s: overlap goes no faster than this (the substep solver's contacts, and soft-body
  /// particles that start a substep inside a rigid body)
  double max_push_out_speed = 3.0;
  /// Contact solver passes: per step for the sequential-impulse solver (0: 10), per substep for
  /// the substep solver (0: 1, or 4 with rotation).
  int velocity_iterations = 0;
  /// Substep solver, with rotation: the passes per substep of a step with at least 256 contacts,
  /// no joints, colour_order on, and only circles among the moving bodies in contact (0: 2 where
  /// velocity_iterations is automatic, else velocity_iterations). A circle's contacts push through
  /// its centre, so circles need fewer passes than the turning stacks of boxes the 4 are for.
  int circle_velocity_iterations = 0;
  double restitution_threshold = 1.0;   ///< m/s; slower impacts do not bounce, so rest is quiet
  double linear_slop = 0.005;           ///< m of overlap left alone, so resting contacts don't jitter
  double position_correction = 0.8;     ///< fraction of the overlap beyond the slop removed per step
  bool sleeping = true;                 ///< bodies at rest for a while stop costing work
  /// Fast bodies (moving over half their size per step) are caught wherever they pass; false:
  /// only where they land each step, so they may tunnel (bullets are always caught).
  bool continuous = true;
  double sleep_speed = 0.05;            ///< m/s below which a body counts as resting
  double time_to_sleep = 0.5;           ///< s an island must rest before it sleeps
  /// Bodies piled up keep a bounded number of contacts (the pair budget, docs/limits.md), so
  /// memory stays linear in the body count; false: every overlapping pair is a contact, at a cost
  /// quadratic in a pile's size (for tests that compare the two).
  bool pair_budget = true;
  SubstepFeatures substep_features;     ///< all on; off only to measure what one buys
  /// Contact begin and end events after each step (World::Events); false: none, at no cost.
  bool contact_events = true;
  double hit_speed = 1.0;               ///< m/s: a contact that begins this fast is also a hit
  ParticleSettings particles;           ///< soft bodies and fluid (engine/particles.h)
};

}  // namespace engine
