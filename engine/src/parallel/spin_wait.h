// Waiting on an atomic: spin briefly (hand-offs within a step come microseconds apart), then
// sleep on it (a futex), so that a thread waiting between steps does not burn a core. Internal.
#pragma once

#include <atomic>

namespace engine::detail {

/// About 10–20 µs of spinning before a thread sleeps.
inline constexpr int kSpinsBeforeSleep = 100000;

/// Returns once done() is true, re-checked whenever `value` changes.
template <typename T, typename Done>
void SpinThenWait(const std::atomic<T>& value, Done&& done) {
  for (int spin = 0; spin < kSpinsBeforeSleep; ++spin) {
    if (done()) return;
  }
  for (;;) {
    const T seen = value.load(std::memory_order_acquire);
    if (done()) return;
    value.wait(seen, std::memory_order_acquire);
  }
}

}  // namespace engine::detail
