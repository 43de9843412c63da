// Numeric faults: the first non-finite number the simulation produced.
#include "step_context.h"

#include <algorithm>
#include <vector>

#include <cmath>

#include "parallel/per_thread.h"

namespace engine::detail {

namespace {

// Fewer bodies than this are looked over on the calling thread alone.
constexpr std::uint32_t kMinSharedCheck = 2048;

// What is not finite in the body's state, or nothing.
const char* NonFinitePart(const BodyState& s) {
  return !IsFinite(s.position)                ? "position"
         : !IsFinite(s.velocity)              ? "velocity"
         : !std::isfinite(s.angle)            ? "angle"
         : !std::isfinite(s.angular_velocity) ? "angular velocity"
                                              : nullptr;
}

}  // namespace

// Shared, each thread only asks whether its part is all finite; the first body at fault is then
// looked for on one thread, as faults are rare.
std::optional<NumericFault> FindNonFinite(std::span<const BodyState> states, std::int64_t step, WorkerPool* pool) {
  const auto n = static_cast<std::uint32_t>(states.size());
  if (pool && pool->Threads() > 1 && n >= kMinSharedCheck) {
    const auto threads = static_cast<std::uint32_t>(pool->Threads());
    std::vector<PerThread<bool>> finite(threads);
    pool->RunOnAll([&](int thread) {
      const auto t = static_cast<std::uint32_t>(thread);
      bool all = true;
      for (std::uint32_t id = n * t / threads; id < n * (t + 1) / threads; ++id) all = all && !NonFinitePart(states[id]);
      finite[t].value = all;
    });
    if (std::all_of(finite.begin(), finite.end(), [](const PerThread<bool>& f) { return f.value; })) return std::nullopt;
  }
  for (BodyIndex id = 0; id < n; ++id) {
    if (const char* what = NonFinitePart(states[id])) return NumericFault{step, id, what};
  }
  return std::nullopt;
}

}  // namespace engine::detail
