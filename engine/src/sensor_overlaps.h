// Sensor bodies: their candidate pairs leave the contact pipeline, and after each step the ones
// that overlap are compared with the last step's to report begin and end. Internal.
#pragma once

#include <span>
#include <vector>

#include "bodies.h"
#include "body_pair.h"
#include "engine/events.h"
#include "snapshot/byte_stream.h"

namespace engine::detail {

class SensorOverlaps {
 public:
  /// Moves the pairs with a sensor in them out of `pairs` (two sensors never meet), before the
  /// sleep stage drops pairs where nothing moves: a sleeper stays inside a sensor.
  void TakeSensorPairs(std::vector<BodyPair>* pairs, std::span<const BodyInfo> infos);
  /// After the step: which taken pairs overlap where the bodies now stand, and the begin and end
  /// events against the last step's overlaps (plus the ends of removed bodies).
  void Update(const Bodies& bodies, StepEvents* events);
  /// The body was destroyed or disabled: its overlaps end, reported after the next step.
  void RemoveBody(BodyIndex index, const Bodies& bodies);
  /// Ends of removed bodies wait to be reported (even with no sensor left).
  bool HasQueuedEnds() const { return !removed_.empty(); }
  /// What carries over from step to step, for snapshots (snapshot/world_snapshot.cpp).
  void Save(ByteWriter& out) const;
  bool Load(ByteReader& in, const Bodies& bodies);

 private:
  SensorEvent EventOf(BodyPair pair, const Bodies& bodies) const;

  std::vector<BodyPair> candidates_;  ///< this step's pairs with a sensor
  std::vector<BodyPair> overlaps_;    ///< the pairs overlapping after the last step, sorted
  std::vector<BodyPair> previous_;
  std::vector<SensorEvent> removed_;  ///< ends of removed bodies, for the next step's events
};

}  // namespace engine::detail
