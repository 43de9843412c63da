// The worker pool's hand-off: a job is published by bumping a generation counter; workers spin
// on it briefly (jobs come back to back within a step) before sleeping on it (a futex).
#include "parallel/worker_pool.h"

#include <cassert>

#include "parallel/spin_wait.h"

namespace engine::detail {


WorkerPool::WorkerPool(int threads) {
  assert(threads >= 1);
  for (int chunk = 1; chunk < threads; ++chunk) workers_.emplace_back([this, chunk] { Work(chunk); });
}

WorkerPool::~WorkerPool() {
  stopping_ = true;
  generation_.fetch_add(1, std::memory_order_release);
  generation_.notify_all();
  for (std::thread& worker : workers_) worker.join();
}

void WorkerPool::BeginStep() {
  step_start_ = std::chrono::steady_clock::now();
  waited_before_ = tl_seconds_waited_long;
}

void WorkerPool::EndStep() {
  if (workers_.empty()) return;
  if (alone_steps_ > 0) {
    if (--alone_steps_ == 0) judge_next_ = false;  // the workers wake from their sleep first
    return;
  }
  if (!judge_next_) {
    judge_next_ = true;
    return;
  }
  const double step = std::chrono::duration<double>(std::chrono::steady_clock::now() - step_start_).count();
  const double waited = tl_seconds_waited_long - waited_before_;
  missing_steps_ = waited > kMissingWorkerShare * step ? missing_steps_ + 1 : 0;
  if (missing_steps_ == kMissingWorkerSteps) {
    alone_steps_ = kAloneSteps;
    missing_steps_ = 0;
  }
}

void WorkerPool::Run(JobRef job) {
  job_ = job;
  pending_.store(static_cast<int>(workers_.size()), std::memory_order_relaxed);
  generation_.fetch_add(1, std::memory_order_release);
  generation_.notify_all();
  job(0);
  SpinThenWait(pending_, [this] { return pending_.load(std::memory_order_acquire) == 0; });
}

void WorkerPool::Work(int chunk) {
  std::uint64_t seen = 0;
  for (;;) {
    SpinThenWait(generation_, [&] { return generation_.load(std::memory_order_acquire) != seen; });
    seen = generation_.load(std::memory_order_acquire);
    if (stopping_) return;
    job_(chunk);
    if (pending_.fetch_sub(1, std::memory_order_acq_rel) == 1) pending_.notify_one();
  }
}

}  // namespace engine::detail
