// A fixed set of threads that run one loop at a time: each on its own contiguous chunk of the
// indices, or in runs that go to whichever thread is free. Each index (or run) writes only its
// own results, so the answer is the same bits with any number of threads and whichever thread
// takes a run. Internal.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <thread>
#include <vector>

#include "parallel/spin_wait.h"

namespace engine::detail {

/// A job the pool hands out: a callable it does not own (the caller's, alive until Run returns)
/// and how to call it, in two words that travel with the hand-off's cache line. A
/// std::function in their place put the job (larger than its sixteen bytes in place) on the heap
/// every time, one more line to fetch from the caller's core before a worker could start.
class JobRef {
 public:
  JobRef() = default;
  template <typename Job>
  explicit JobRef(Job& job)
      : job_(const_cast<void*>(static_cast<const void*>(&job))),
        call_([](void* job, int thread) { (*static_cast<Job*>(job))(thread); }) {}
  void operator()(int thread) const { call_(job_, thread); }
  /// Whether it refers to a job (a default-made JobRef does not).
  explicit operator bool() const { return call_ != nullptr; }

 private:
  void* job_ = nullptr;
  void (*call_)(void* job, int thread) = nullptr;
};

class WorkerPool {
 public:
  /// `threads` ≥ 1 counts the caller: threads − 1 workers are started.
  explicit WorkerPool(int threads);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  /// How many threads share the jobs: one while the pool runs alone (EndStep).
  int Threads() const { return Alone() ? 1 : static_cast<int>(workers_.size()) + 1; }

  /// Around each step: where the calling thread spends much of several steps in a row waiting
  /// past its spinning for the other threads (kMissingWorkerSteps steps, each waiting
  /// kMissingWorkerShare of it or more: a worker that does not run, its core held by another
  /// program), the pool runs its jobs on the calling thread alone for the next kAloneSteps steps,
  /// then shares them again (the first step after not judged). Every job gives the same bits on
  /// any number of threads, so only the time changes: with another program busy on one of two
  /// cores, the settled 4 000-circle pour took 2.69 ms/step on two threads, against 1.03 on one.
  void BeginStep();
  void EndStep();

  /// Calls job(thread) once on each of the Threads() threads (the caller's is 0); returns when
  /// all are done. For jobs whose threads meet at a SpinBarrier between parts.
  template <typename Job>
  void RunOnAll(Job&& job) {
    if (Alone()) {
      job(0);
    } else {
      Run(JobRef(job));
    }
  }

  /// Runs `first` on the calling thread and `second` on a worker, side by side (with one thread,
  /// first then second): for two tasks that write nothing the other reads or writes.
  template <typename First, typename Second>
  void RunSideBySide(First&& first, Second&& second) {
    if (Alone()) {
      first();
      second();
      return;
    }
    auto job = [&](int thread) {
      if (thread == 0) first();
      if (thread == 1) second();
    };
    Run(JobRef(job));
  }

  /// As RunSideBySide, then every thread takes runs of `run` indices of [0, count) in turn, the
  /// next untaken run each time, and calls shared(begin, end) for each, until none is left: a
  /// thread done with its task takes more of the shared part. Which thread takes a run changes
  /// from call to call, so each run must write only its own results, whoever computes them.
  template <typename First, typename Second, typename Shared>
  void RunSideBySideThenShare(First&& first, Second&& second, std::uint32_t count, std::uint32_t run,
                              Shared&& shared) {
    if (Alone()) {
      first();
      second();
      for (std::uint32_t begin = 0; begin < count; begin += run) shared(begin, std::min(count, begin + run));
      return;
    }
    alignas(64) std::atomic<std::uint32_t> next{0};  // a line of its own: the caller's stack is busy
    auto job = [&](int thread) {
      if (thread == 0) first();
      if (thread == 1) second();
      TakeRuns(&next, count, run, shared);
    };
    Run(JobRef(job));
  }

  /// As RunSideBySideThenShare, for shared runs that read what `first` writes: a thread done
  /// with `second` before `first` is done waits for it.
  template <typename First, typename Second, typename Shared>
  void RunSideBySideThenShareAfterFirst(First&& first, Second&& second, std::uint32_t count, std::uint32_t run,
                                        Shared&& shared) {
    if (Alone()) {
      RunSideBySideThenShare(first, second, count, run, shared);
      return;
    }
    alignas(64) std::atomic<std::uint32_t> next{0};
    alignas(64) std::atomic<bool> first_done{false};
    auto job = [&](int thread) {
      if (thread == 0) {
        first();
        first_done.store(true, std::memory_order_release);
        first_done.notify_all();
      } else {
        if (thread == 1) second();
        SpinThenWait(first_done, [&] { return first_done.load(std::memory_order_acquire); });
      }
      TakeRuns(&next, count, run, shared);
    };
    Run(JobRef(job));
  }

  /// Calls body(begin, end) once for each run of `run` indices (the last may be shorter) that
  /// covers [0, count): on the calling thread alone when there is one thread or fewer than
  /// `min_count` indices, else each thread takes the next untaken run until none is left. For
  /// loops whose halves cost unlike amounts (memory another thread wrote last, work that gathers
  /// at one end): a thread done early takes more. Which thread takes a run changes from call to
  /// call, so each run must write only its own results.
  template <typename Body>
  void ParallelRuns(std::uint32_t count, std::uint32_t min_count, std::uint32_t run, Body&& body) {
    if (Alone() || count < min_count) {
      for (std::uint32_t begin = 0; begin < count; begin += run) body(begin, std::min(count, begin + run));
      return;
    }
    alignas(64) std::atomic<std::uint32_t> next{0};  // a line of its own: the caller's stack is busy
    auto job = [&](int) { TakeRuns(&next, count, run, body); };
    Run(JobRef(job));
  }

  /// Calls body(i) for every i in [0, count): on the calling thread alone when there is one
  /// thread or fewer than `min_count` indices (a few microseconds of hand-off would cost more),
  /// else split into Threads() chunks, the caller taking the first. Returns when all are done.
  template <typename Body>
  void ParallelFor(std::uint32_t count, std::uint32_t min_count, Body&& body) {
    if (Alone() || count < min_count) {
      for (std::uint32_t i = 0; i < count; ++i) body(i);
      return;
    }
    const auto chunks = static_cast<std::uint64_t>(Threads());
    auto job = [&](int chunk) {
      const auto begin = static_cast<std::uint32_t>(count * static_cast<std::uint64_t>(chunk) / chunks);
      const auto end = static_cast<std::uint32_t>(count * static_cast<std::uint64_t>(chunk + 1) / chunks);
      auto own = body;  // kept in this thread's registers (see ForEachIndex)
      for (std::uint32_t i = begin; i < end; ++i) own(i);
    };
    Run(JobRef(job));
  }

 private:
  template <typename Body>
  static void TakeRuns(std::atomic<std::uint32_t>* next, std::uint32_t count, std::uint32_t run, Body& body) {
    for (;;) {
      const std::uint32_t begin = next->fetch_add(run, std::memory_order_relaxed);
      if (begin >= count) return;
      body(begin, std::min(count, begin + run));
    }
  }

  void Run(JobRef job);
  void Work(int chunk);
  bool Alone() const { return workers_.empty() || alone_steps_ > 0; }

  std::vector<std::thread> workers_;
  // What a hand-off writes and reads, on one cache line of its own: where the pool's place in
  // the heap split them over two lines, an empty job on two threads took 1 056-1 415 cycles
  // against 342-379 on one.
  alignas(64) JobRef job_;                    ///< the current job: valid while Run runs
  std::atomic<std::uint64_t> generation_{0};  ///< bumped to hand out a job (or to stop)
  std::atomic<int> pending_{0};               ///< workers still on the current job
  bool stopping_ = false;
  alignas(64) int alone_steps_ = 0;  ///< steps left to run alone (EndStep)
  int missing_steps_ = 0;     ///< judged steps in a row that missed the workers
  bool judge_next_ = false;   ///< whether EndStep judges this step (not the first, nor the first shared again)
  std::chrono::steady_clock::time_point step_start_;
  double waited_before_ = 0.0;  ///< tl_seconds_waited_long at the step's start
};

/// A step whose calling thread waited longer than this share of it past its spinning for the
/// other threads missed them: two threads on two cores, one held by another busy program, waited
/// about half of every step of the 4 000-circle pour; sharing as they should, 5 % on average and
/// a few steps in a hundred past 30 % (6 of 149 in the 10 000-circle pour), hence several in a row.
inline constexpr double kMissingWorkerShare = 0.3;
/// How many judged steps in a row must miss the workers before the pool runs alone.
inline constexpr int kMissingWorkerSteps = 4;
/// Steps run alone before trying the threads again.
inline constexpr int kAloneSteps = 64;

/// Passes over the bodies are shared among threads from these many: fewer cost more to hand out
/// than they save.
inline constexpr std::uint32_t kMinSharedBodies = 2048;

/// body(i) for every i in [0, count): shared among `pool`'s threads from `min_count` indices
/// (WorkerPool::ParallelFor), on the calling thread alone where there is no pool.
///
/// A body whose loop stores numbers and reads captured ones is best a lambda that captures by
/// value, which each thread copies: a value captured by reference lives on the calling thread's
/// stack, and the loop, called through the pool, reads it from there again after every store it
/// cannot prove does not overwrite it. The free step of the 4 000-circle pour on two threads took
/// 17 kcyc a substep with its lambda capturing by reference, 12.8 by value. (Without a pool the
/// loop is inlined where the values live, and either way is the same.)
template <typename Body>
void ForEachIndex(WorkerPool* pool, std::size_t count, std::uint32_t min_count, Body&& body) {
  const auto n = static_cast<std::uint32_t>(count);
  if (pool) {
    pool->ParallelFor(n, min_count, body);
  } else {
    for (std::uint32_t i = 0; i < n; ++i) body(i);
  }
}

/// How many runs a thread takes, on average, where the indices go out in runs: fewer runs
/// balance coarser, more cost more hand-overs of the shared counter between the cores (three
/// measured faster than eight on the 4 000-circle pour).
inline constexpr std::uint32_t kRunsPerThread = 3;

/// The length of the runs ForEachRun deals out: about kRunsPerThread a thread when the loop is
/// shared (a pool of several threads and at least `min_count` indices), else all `count` in one
/// run. A run's own results go at begin / run.
inline std::uint32_t RunLength(const WorkerPool* pool, std::uint32_t count, std::uint32_t min_count) {
  const auto threads = pool && count >= min_count ? static_cast<std::uint32_t>(pool->Threads()) : 1;
  return threads == 1 ? std::max<std::uint32_t>(count, 1) : count / (kRunsPerThread * threads) + 1;
}

/// Calls body(begin, end) for each run of `run` indices covering [0, count): on the pool's threads
/// as WorkerPool::ParallelRuns deals them out, or on the calling thread when there is no pool.
template <typename Body>
void ForEachRun(WorkerPool* pool, std::uint32_t count, std::uint32_t min_count, std::uint32_t run, Body&& body) {
  if (pool) {
    pool->ParallelRuns(count, min_count, run, body);
    return;
  }
  for (std::uint32_t begin = 0; begin < count; begin += run) body(begin, std::min(count, begin + run));
}

/// As ForEachIndex, but the indices go out in runs, each to whichever thread is free
/// (WorkerPool::ParallelRuns), kRunsPerThread a thread.
template <typename Body>
void ForEachIndexInRuns(WorkerPool* pool, std::size_t count, std::uint32_t min_count, Body&& body) {
  const auto n = static_cast<std::uint32_t>(count);
  const auto each = [&](std::uint32_t begin, std::uint32_t end) {
    for (std::uint32_t i = begin; i < end; ++i) body(i);
  };
  if (pool) {
    const auto threads = static_cast<std::uint32_t>(pool->Threads());
    pool->ParallelRuns(n, min_count, std::max<std::uint32_t>(64, n / (kRunsPerThread * threads) + 1), each);
  } else {
    each(0, n);
  }
}

}  // namespace engine::detail
