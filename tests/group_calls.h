// Records the calls a pass runner (ForEachGroup, ForEachGroupByBodies) makes: each call's range,
// its place in one count of starts and finishes that every thread shares, and its thread.
#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

namespace testing {

struct GroupCall {
  std::uint32_t begin, end;
  std::uint64_t started, finished;  ///< ticks of the one count
  std::thread::id thread;
};

class GroupCalls {
 public:
  /// The pass to hand the runner: records pass(begin, end) and does nothing else.
  auto Pass() {
    return [this](std::uint32_t begin, std::uint32_t end) {
      const std::uint64_t started = tick_++;
      const std::uint64_t finished = tick_++;
      const std::lock_guard<std::mutex> lock(mutex_);
      calls_.push_back({begin, end, started, finished, std::this_thread::get_id()});
    };
  }
  /// The calls, once the runner has returned.
  const std::vector<GroupCall>& Calls() const { return calls_; }

 private:
  std::atomic<std::uint64_t> tick_{0};
  std::mutex mutex_;
  std::vector<GroupCall> calls_;
};

}  // namespace testing
