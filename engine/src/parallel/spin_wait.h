// Waiting on an atomic: spin briefly, then yield the core for a while (hand-offs within a step
// come microseconds apart), then sleep on it (a futex), so that a thread waiting between steps
// does not burn a core. Internal.
#pragma once

#include <atomic>
#include <chrono>
#include <thread>

namespace engine::detail {

/// A few microseconds of spinning: the usual wait between two passes of a substep.
inline constexpr int kSpinsBeforeYield = 2000;
/// Then yielding until this long has passed: on an idle core a yield returns at once, so this is
/// spinning still; on a busy machine it hands the core to whoever holds it, the thread being
/// waited for among them. A worker put to sleep between two passes costs more to wake (about
/// 1.5 ms/step more on a 4000-circle pour) than the pass takes.
inline constexpr auto kYieldBeforeSleep = std::chrono::microseconds(300);

/// Returns once done() is true, re-checked whenever `value` changes.
template <typename T, typename Done>
void SpinThenWait(const std::atomic<T>& value, Done&& done) {
  for (int spin = 0; spin < kSpinsBeforeYield; ++spin) {
    if (done()) return;
  }
  const auto until = std::chrono::steady_clock::now() + kYieldBeforeSleep;
  for (int round = 0;; ++round) {
    if (done()) return;
    std::this_thread::yield();
    if (round % 16 == 15 && std::chrono::steady_clock::now() > until) break;
  }
  for (;;) {
    const T seen = value.load(std::memory_order_acquire);
    if (done()) return;
    value.wait(seen, std::memory_order_acquire);
  }
}

}  // namespace engine::detail
