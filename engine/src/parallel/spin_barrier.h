// A barrier for the threads of one WorkerPool job: none passes Wait() until all have reached it.
// Internal.
#pragma once

#include <atomic>
#include <cstdint>

#include "parallel/spin_wait.h"

namespace engine::detail {

/// A cache line of its own: on the caller's stack it could share one with the caller's other
/// locals, written while the other threads spin on it.
class alignas(64) SpinBarrier {
 public:
  explicit SpinBarrier(int threads) : threads_(threads) {}

  void Wait() {
    const std::uint32_t round = round_.load(std::memory_order_acquire);
    if (arrived_.fetch_add(1, std::memory_order_acq_rel) == threads_ - 1) {
      // The last to arrive opens the next round; its writes (and everyone's, by the
      // acquire-release chain on arrived_) are visible to all who see the new round.
      arrived_.store(0, std::memory_order_relaxed);
      round_.fetch_add(1, std::memory_order_release);
      round_.notify_all();
      return;
    }
    SpinThenWait(round_, [&] { return round_.load(std::memory_order_acquire) != round; });
  }

 private:
  const int threads_;
  std::atomic<int> arrived_{0};
  std::atomic<std::uint32_t> round_{0};
};

}  // namespace engine::detail
