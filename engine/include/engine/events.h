// What a step reports besides the bodies' new states.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/ids.h"
#include "engine/math.h"

namespace engine {

/// The first non-finite number the simulation produced: which body, in which step, and which
/// part of its state. Inputs are checked when they enter, so this means the numbers overflowed.
struct NumericFault {
  std::int64_t step;  ///< the step that produced it (StepCount() before that step)
  BodyIndex body;     ///< the body's slot (World::IdAt gives its id)
  const char* what;   ///< "position", "velocity", "angle" or "angular velocity"
};

/// Two bodies began to touch in the last step: the solver pushed them apart or they met within
/// the linear slop. `a` is the one in the lower slot; `normal` points from a to b.
struct ContactBeginEvent {
  BodyId a;
  BodyId b;
  Vec2 point;             ///< where they meet (the mean of the contact points)
  Vec2 normal;
  double approach_speed;  ///< m/s along the normal at the step's start (> 0: closing)
};

/// Two bodies stopped touching: in the last step, or because one was destroyed or disabled
/// before it (then that id may already be stale).
struct ContactEndEvent {
  BodyId a;
  BodyId b;
};

/// A sensor body began or stopped overlapping another (non-sensor) body.
struct SensorEvent {
  BodyId sensor;
  BodyId visitor;
};

/// Everything the last step reported, each list in slot order of its first body.
struct StepEvents {
  std::vector<ContactBeginEvent> contact_begin;
  std::vector<ContactEndEvent> contact_end;
  /// The begin events whose approach speed reached WorldDef::hit_speed.
  std::vector<ContactBeginEvent> hits;
  std::vector<SensorEvent> sensor_begin;
  std::vector<SensorEvent> sensor_end;

  void Clear() {
    contact_begin.clear();
    contact_end.clear();
    hits.clear();
    sensor_begin.clear();
    sensor_end.clear();
  }
};

}  // namespace engine
