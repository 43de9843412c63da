// What became of a run's events: how many clicks were applied, hit a ball or missed, where each
// miss was, how many grabs took hold of a body, the drags and releases, and how many events the
// run ended before. Commands print it as their events summary.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/math.h"
#include "engine/world.h"
#include "game/script.h"

namespace game {

/// A click that hit no dynamic ball.
struct MissedClick {
  InputEvent event;    ///< as the script or the window gave it (pixel or world point)
  engine::Vec2 world;  ///< the world point it acted on
  std::optional<engine::BodyId> nearest;  ///< the dynamic ball nearest to that point, if any
  double gap = 0.0;    ///< metres from `world` to that ball's rim
};

class EventLog {
 public:
  /// Notes one applied click that acted at `world` on `world_state` and hit a ball, or else
  /// pushed particles, or neither (a miss).
  void Record(const InputEvent& event, engine::Vec2 world, bool hit, bool pushed_particles,
              const engine::World& world_state);

  /// Notes a grab, which took hold of a body or found none under it.
  void RecordGrab(bool held) { ++grabs_, held_ += held ? 1 : 0; }
  void RecordDrag() { ++drags_; }
  void RecordRelease() { ++releases_; }

  /// Clicks applied.
  std::int64_t Applied() const { return hits_ + pushes_ + static_cast<std::int64_t>(misses_.size()); }
  std::int64_t Hits() const { return hits_; }
  /// Clicks that hit no ball but pushed soft-body or fluid particles.
  std::int64_t ParticlePushes() const { return pushes_; }
  const std::vector<MissedClick>& Misses() const { return misses_; }
  std::int64_t Grabs() const { return grabs_; }
  /// Grabs that took hold of a body.
  std::int64_t Held() const { return held_; }
  std::int64_t Drags() const { return drags_; }
  std::int64_t Releases() const { return releases_; }

 private:
  std::int64_t hits_ = 0;
  std::int64_t pushes_ = 0;
  std::vector<MissedClick> misses_;
  std::int64_t grabs_ = 0;
  std::int64_t held_ = 0;
  std::int64_t drags_ = 0;
  std::int64_t releases_ = 0;
};

/// Events a run never applied because it ended first.
struct EventsAfterEnd {
  std::size_t count = 0;
  std::int64_t first_step = 0;  ///< the step of the first of them
  std::int64_t end_step = 0;    ///< the step the run ended before (events at it or later are late)
};

/// The summary line, e.g. "events: 6 clicks applied, 5 hit a ball, 1 missed (--misses lists
/// where)" (with "2 pushed particles" before the misses when any click did), with "; 1 grab (1 took hold of a body), 40 drags, 1 release" when the run had any,
/// or "events: none" for a run without any. `misses_listed`: the misses are printed above it,
/// so the hint is left out.
std::string EventSummary(const EventLog& log, const EventsAfterEnd& late, bool misses_listed);

/// One line per miss, e.g. "miss: step 40, click 361 231 (pixels at 800x600) -> world (-1.07,
/// 8.40): no ball there; nearest \"bouncy_ball\", 0.12 m beyond its rim". `ids`: body ids.
std::string MissLine(const MissedClick& miss, const std::vector<std::string>& ids);

}  // namespace game
