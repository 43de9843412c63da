// Contact begin, end and hit events: which pairs touch after a step, against the last step.
// Internal to the engine.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "bodies.h"
#include "body_pair.h"
#include "engine/contact.h"
#include "engine/events.h"
#include "engine/world_def.h"
#include "parallel/balanced_cuts.h"
#include "parallel/per_thread.h"
#include "parallel/worker_pool.h"
#include "snapshot/byte_stream.h"

namespace engine::detail {

class ContactEvents {
 public:
  /// Before the solver: the bodies' starting velocities, for the approach speed of the contacts
  /// that begin (a copy per body: cheaper than an approach speed per contact, most of which
  /// go on touching and need none).
  void RecordStartVelocities(std::span<const BodyState> states, WorkerPool& pool);
  /// After the solver: a contact touches if the solver pushed on it or its bodies were within
  /// the linear slop; the touching pairs that are new begin, the ones gone end (`awake`: per
  /// body, whether it moved this step; a pair of bodies at rest stays touching). The approach
  /// speed is measured at the step's start (`bodies.start_positions`, the recorded velocities).
  /// Whether each contact touches, and the merge with the last step's pairs (in runs of the
  /// contacts), are found on the pool's threads.
  void Update(std::span<const Contact> contacts, const Bodies& bodies, std::span<const std::uint8_t> awake,
              const WorldDef& def, WorkerPool& pool, StepEvents* events);
  /// The body was destroyed or disabled: its touching contacts end, reported after the next step.
  void RemoveBody(BodyIndex index, const Bodies& bodies);
  /// What carries over from step to step, for snapshots (snapshot/world_snapshot.cpp).
  void Save(ByteWriter& out) const;
  bool Load(ByteReader& in, const Bodies& bodies);

 private:
  /// One thread's share of the merge.
  struct MergeRun {
    std::vector<BodyPair> touching;
    StepEvents events;
    std::size_t begin = 0;  ///< its first contact
    double seconds = 0.0;   ///< how long its merge took
  };
  /// How fast contact c closed when the step began.
  double StartApproach(const Contact& c, const Bodies& bodies) const;
  /// Merges the touching ones of contacts [begin, end) against `previous`, the last step's
  /// touching pairs from the first of these contacts' pairs up to `stop` (the next run's first
  /// pair), into `touching` and `events`.
  void Merge(std::span<const Contact> contacts, std::size_t begin, std::size_t end,
             std::span<const BodyPair> previous, BodyPair stop, const Bodies& bodies,
             std::span<const std::uint8_t> awake, const WorldDef& def, std::vector<BodyPair>* touching,
             StepEvents* events) const;

  std::vector<Vec2> start_velocities_;   ///< per body, at the step's start
  std::vector<double> start_angular_velocities_;
  std::vector<BodyPair> touching_;       ///< after the last step, sorted
  std::vector<BodyPair> previous_;
  std::vector<ContactEndEvent> removed_;
  std::vector<PerThread<MergeRun>> runs_;
  std::vector<std::size_t> run_offsets_;  ///< where each run's touching pairs go in touching_
  BalancedCuts cuts_;                      ///< where the runs are cut, from their last times
  std::vector<std::size_t> run_cuts_;
  std::vector<double> run_seconds_;
};

}  // namespace engine::detail
