// The events summary: counts kept as the clicks are applied, and the lines that report them.
#include "game/event_log.h"

#include <cinttypes>
#include <cmath>
#include <cstdio>

#include "game/click.h"

namespace game {

void EventLog::Record(const InputEvent& event, engine::Vec2 world, bool hit, bool pushed_particles,
                      const engine::World& world_state) {
  if (hit || pushed_particles) {
    ++(hit ? hits_ : pushes_);
    return;
  }
  MissedClick miss{event, world, std::nullopt, 0.0};
  if (const std::optional<NearBall> near = NearestBall(world_state, world)) {
    miss.nearest = near->body;
    miss.gap = near->gap;
  }
  misses_.push_back(miss);
}

namespace {

std::string Count(std::int64_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

}  // namespace

std::string EventSummary(const EventLog& log, const EventsAfterEnd& late, bool misses_listed) {
  const std::int64_t applied = log.Applied();
  const bool dragging = log.Grabs() + log.Drags() + log.Releases() > 0;
  if (applied == 0 && !dragging && late.count == 0) return "events: none";
  std::string line = "events: ";
  // A run of drags alone says nothing of clicks; any other run says how its clicks went.
  if (applied > 0 || !dragging) {
    const std::size_t missed = log.Misses().size();
    line += Count(applied, "click", "clicks") + " applied, " + std::to_string(log.Hits()) + " hit a ball, ";
    // Only scenes with particles can push any, so the others' line reads as it always did.
    if (log.ParticlePushes() > 0) line += std::to_string(log.ParticlePushes()) + " pushed particles, ";
    line += std::to_string(missed) + " missed";
    if (missed > 0 && !misses_listed) line += " (--misses lists where)";
    if (dragging) line += "; ";
  }
  if (dragging) {
    line += Count(log.Grabs(), "grab", "grabs") + " (" + std::to_string(log.Held()) +
            " took hold of a body), " + Count(log.Drags(), "drag", "drags") + ", " +
            Count(log.Releases(), "release", "releases");
  }
  if (late.count > 0) {
    line += "; " + std::to_string(late.count) + (late.count == 1 ? " event" : " events") +
            " after the end of the run (the first at step " + std::to_string(late.first_step) +
            "; the run ended before simulating step " + std::to_string(late.end_step) + ")";
  }
  return line;
}

std::string MissLine(const MissedClick& miss, const std::vector<std::string>& ids) {
  const InputEvent& e = miss.event;
  char text[256];
  std::string line = "miss: step " + std::to_string(e.step) + ", ";
  if (e.kind == EventKind::kClickPixel) {
    std::snprintf(text, sizeof text, "click %g %g (pixels", e.at.x, e.at.y);
    line += text;
    if (e.image_width > 0) {
      line += " at " + std::to_string(e.image_width) + "x" + std::to_string(e.image_height);
    }
    std::snprintf(text, sizeof text, ") -> world (%.4g, %.4g)", miss.world.x, miss.world.y);
    line += text;
  } else {
    std::snprintf(text, sizeof text, "click-world %.4g %.4g", miss.world.x, miss.world.y);
    line += text;
  }
  line += ": no ball there";
  if (miss.nearest) {
    std::snprintf(text, sizeof text, "; nearest \"%s\", %.3g m beyond its rim",
                  ids[miss.nearest->index].c_str(), miss.gap);
    line += text;
  }
  return line;
}

}  // namespace game
