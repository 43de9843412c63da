// Waiting on an atomic: spin briefly, then yield the core for a while (hand-offs within a step
// come microseconds apart), then sleep on it (a futex), so that a thread waiting between steps
// does not burn a core. Internal.
#pragma once

#include <atomic>
#include <chrono>
#include <thread>

namespace engine::detail {

/// About 5 µs of spinning (on this project's machine): the usual wait between two passes of a
/// substep, and most of the one-thread stretches of a step (a worker that has begun to yield
/// answers later). At 2 000 spins (0.5 µs), a worker yielded through most of them: on two
/// threads the turning 4 000-circle pour took a median 1.81 ms/step against 1.73 at 20 000, and
/// the 10 000-circle pour 3.19 against 3.05 (runs in turn, the same minutes; 80 000 was no better).
inline constexpr int kSpinsBeforeYield = 20000;
/// Then yielding until this long has passed: on an idle core a yield returns at once, so this is
/// spinning still; on a busy machine it hands the core to whoever holds it, the thread being
/// waited for among them. A worker put to sleep between two passes costs more to wake than the
/// pass takes: at 300 µs, some of a step's waits outlasted it, and half the runs of a turning
/// 4000-circle pour took 8.9 ms/step on two threads against 5.2 on one (the others 4.3); a fluid
/// dam break of 10 000 particles took 15.7 ms/step on two against 13.2 on one. At 1 ms every run
/// of the pour took 4.1-4.5 ms, and the dam break 8.0.
inline constexpr auto kYieldBeforeSleep = std::chrono::microseconds(1000);

/// The calling thread's time spent in SpinThenWait past its spinning (yielding or asleep),
/// seconds, summed: WorkerPool reads its own thread's, to notice workers that are not running.
inline thread_local double tl_seconds_waited_long = 0.0;

/// Returns once done() is true, re-checked whenever `value` changes.
template <typename T, typename Done>
void SpinThenWait(const std::atomic<T>& value, Done&& done) {
  for (int spin = 0; spin < kSpinsBeforeYield; ++spin) {
    if (done()) return;
  }
  const auto start = std::chrono::steady_clock::now();
  const auto waited = [start] {
    tl_seconds_waited_long += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  const auto until = start + kYieldBeforeSleep;
  for (int round = 0;; ++round) {
    if (done()) return waited();
    std::this_thread::yield();
    if (round % 16 == 15 && std::chrono::steady_clock::now() > until) break;
  }
  for (;;) {
    const T seen = value.load(std::memory_order_acquire);
    if (done()) return waited();
    value.wait(seen, std::memory_order_acquire);
  }
}

}  // namespace engine::detail
