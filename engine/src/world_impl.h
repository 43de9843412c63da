// World's implementation: the bodies and the step's stages, each owning its scratch. Internal.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <variant>

#include "bodies.h"
#include "candidate_pairs.h"
#include "contact_events.h"
#include "engine/world.h"
#include "forces/force_model.h"
#include "forces/springs.h"
#include "integrate.h"
#include "joints/joint_solver.h"
#include "joints/joint_table.h"
#include "sensor_overlaps.h"
#include "snapshot/byte_stream.h"
#include "narrow_phase/narrow_phase.h"
#include "parallel/worker_pool.h"
#include "particles/effects.h"
#include "particles/particle_system.h"
#include "sleep.h"
#include "solver/sequential_impulse_solver.h"
#include "solver/substep_solver.h"

namespace engine {

namespace detail {
/// One of the contact solvers, chosen once, when the world is made.
using AnyContactSolver = std::variant<SubstepSolver, SequentialImpulseSolver>;
}  // namespace detail

struct World::Impl {
  explicit Impl(const WorldDef& def);

  detail::ForceModel Forces() const;
  /// Whether the chosen solver takes speculative contacts (a margin apart), or real overlap only.
  bool SpeculativeContacts() const;
  void UpdateSleep();

  /// The live body `id` names; a stale or unknown id stops the program, naming `call`.
  BodyIndex Slot(BodyId id, const char* call) const;
  /// Wakes the body's island, or for a static or kinematic body the islands touching it.
  void WakeAround(BodyIndex index);
  /// Wakes the body's island and every sleeping island touching it (or within the reach of a
  /// resting contact): for a body that moves by hand, goes, comes back or changes its filter.
  void WakeTouching(BodyIndex index);
  /// Takes the body out of the simulation (destroyed or disabled): its contacts, sensor
  /// overlaps and springs stop; what it held up wakes.
  void Withdraw(BodyIndex index);
  /// After a kinematic body's velocity changes: it moves (is integrated) only while it has one.
  void UpdateKinematicMotion(BodyIndex index);
  /// Snapshots (snapshot/world_snapshot.cpp): everything but the settings, which the reader's
  /// world must share (checked by a fingerprint).
  void Save(detail::ByteWriter& out) const;
  bool Load(detail::ByteReader& in);
  /// The joints' part of a snapshot (present only in worlds that ever had a joint).
  bool LoadJoints(detail::ByteReader& in);
  /// The springs that act: those with something to pull, between enabled bodies.
  void RebuildActingSprings();
  /// The live joint `id` names; a stale or unknown id stops the program, naming `call`.
  std::uint32_t JointSlot(JointId id, const char* call) const;
  /// After joints or bodies come, go, or are enabled or disabled: the joints' lists.
  void RebuildJoints();
  /// Destroys the joints of a body that goes; their other bodies wake.
  void DestroyJointsOf(BodyIndex body);
  /// Soft bodies and fluid, then effect particles: their step, after the bodies'.
  void StepParticles();
  /// The slots the particle calls name; a stale or unknown id stops the program, naming `call`.
  std::uint32_t SoftBodySlot(SoftBodyId id, const char* call) const;
  std::uint32_t EmitterSlot(EmitterId id, const char* call) const;
  /// The particles' part of a snapshot (present only in worlds that ever had particles).
  bool LoadParticles(detail::ByteReader& in);

  WorldDef def;                       ///< with the automatic settings filled in
  detail::Bodies bodies;
  detail::SleepTable sleep;
  detail::Springs springs;
  detail::JointTable joints;
  detail::JointSolver joint_solver;    ///< the joints' passes, run inside the contact solver
  detail::CandidatePairs candidates;  ///< the broad phase
  detail::NarrowPhase narrow_phase;   ///< this step's contacts
  detail::FreeMotion free_motion;     ///< the integrators' scratch
  detail::AnyContactSolver solver;    ///< the one WorldDef::solver chose
  detail::ContactEvents contact_events;
  detail::SensorOverlaps sensors;
  detail::ParticleSystem particles;   ///< soft bodies and fluid, stepped after the bodies
  detail::EffectSystem effects;       ///< emitters and their effect particles
  /// WorldDef::threads: the contact solver's, the particles' and the effects' (one thread: no
  /// workers).
  std::unique_ptr<detail::WorkerPool> pool;
  StepEvents events;                  ///< the last step's
  std::int64_t step_count = 0;
  std::optional<NumericFault> fault;
};

}  // namespace engine
