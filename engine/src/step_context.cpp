// Numeric faults: the first non-finite number the simulation produced.
#include "step_context.h"

#include <atomic>

#include <cmath>


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
    std::atomic<bool> any{false};  // written only by a part with a fault: no line goes back and forth
    pool->ParallelFor(n, kMinSharedCheck, [&](std::uint32_t id) {
      if (NonFinitePart(states[id])) any.store(true, std::memory_order_relaxed);
    });
    if (!any.load(std::memory_order_relaxed)) return std::nullopt;
  }
  for (BodyIndex id = 0; id < n; ++id) {
    if (const char* what = NonFinitePart(states[id])) return NumericFault{step, id, what};
  }
  return std::nullopt;
}

}  // namespace engine::detail
