// Sensor overlaps: a merge of two sorted pair lists gives the begin and end events.
#include "sensor_overlaps.h"

#include <algorithm>

#include "narrow_phase/narrow_phase.h"

namespace engine::detail {

void SensorOverlaps::TakeSensorPairs(std::vector<BodyPair>* pairs, std::span<const BodyInfo> infos) {
  candidates_.clear();
  std::erase_if(*pairs, [&](BodyPair p) {
    const bool a = infos[p.a].is_sensor, b = infos[p.b].is_sensor;
    if (a != b) candidates_.push_back(p);
    return a || b;
  });
}

SensorEvent SensorOverlaps::EventOf(BodyPair pair, const Bodies& bodies) const {
  const bool a_senses = bodies.infos[pair.a].is_sensor;
  return a_senses ? SensorEvent{bodies.IdOf(pair.a), bodies.IdOf(pair.b)}
                  : SensorEvent{bodies.IdOf(pair.b), bodies.IdOf(pair.a)};
}

void SensorOverlaps::Update(const Bodies& bodies, StepEvents* events) {
  previous_.swap(overlaps_);
  overlaps_.clear();
  for (const BodyPair p : candidates_) {
    if (ShapesOverlap(bodies.infos[p.a], bodies.states[p.a], bodies.geometries[p.a].get(), bodies.infos[p.b],
                      bodies.states[p.b], bodies.geometries[p.b].get())) {
      overlaps_.push_back(p);
    }
  }
  events->sensor_end.insert(events->sensor_end.end(), removed_.begin(), removed_.end());
  removed_.clear();
  // Both lists are sorted by pair: one walk finds what is only in one of them.
  std::size_t i = 0, j = 0;
  while (i < overlaps_.size() || j < previous_.size()) {
    if (j == previous_.size() || (i < overlaps_.size() && overlaps_[i] < previous_[j])) {
      events->sensor_begin.push_back(EventOf(overlaps_[i++], bodies));
    } else if (i == overlaps_.size() || previous_[j] < overlaps_[i]) {
      events->sensor_end.push_back(EventOf(previous_[j++], bodies));
    } else {
      ++i, ++j;
    }
  }
}

void SensorOverlaps::RemoveBody(BodyIndex index, const Bodies& bodies) {
  std::erase_if(overlaps_, [&](BodyPair p) {
    if (p.a != index && p.b != index) return false;
    removed_.push_back(EventOf(p, bodies));
    return true;
  });
}

}  // namespace engine::detail
