// A bounded queue between the thread that draws frames and the threads that write them: Push
// blocks while it is full, so memory stays flat however far behind the writers fall; Pop blocks
// while it is empty. After Close, Pop hands out what is left, then nothing; after Fail, Push
// refuses, what waits is dropped and Pop hands out nothing, so no work follows a failure.
#pragma once

#include <algorithm>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <mutex>
#include <optional>
#include <utility>

#include "game/status.h"

namespace game {

template <class T>
class WorkQueue {
 public:
  explicit WorkQueue(std::size_t capacity) : capacity_(std::max<std::size_t>(1, capacity)) {}

  /// Queues `item`; false (dropping it) once the queue is closed or has failed.
  bool Push(T item) {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] { return items_.size() < capacity_ || failure_ || closed_; });
    if (failure_ || closed_) return false;
    items_.push_back(std::move(item));
    lock.unlock();
    changed_.notify_all();
    return true;
  }

  /// The next item; nothing once the queue is closed and empty, or has failed.
  std::optional<T> Pop() {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] { return !items_.empty() || closed_ || failure_; });
    if (failure_ || items_.empty()) return std::nullopt;
    T item = std::move(items_.front());
    items_.pop_front();
    lock.unlock();
    changed_.notify_all();
    return item;
  }

  /// No more items: Pop drains what is queued, then returns nothing.
  void Close() { Update([this] { closed_ = true; }); }
  /// Drops what is queued (the work is abandoned) and closes.
  void Abandon() {
    Update([this] {
      items_.clear();
      closed_ = true;
    });
  }
  /// Keeps the first failure; every waiting Push and Pop returns at once.
  void Fail(Failure failure) {
    Update([&] {
      if (!failure_) failure_ = std::move(failure);
      items_.clear();
    });
  }
  Status FirstFailure() {
    std::lock_guard lock(mutex_);
    return failure_;
  }

 private:
  template <class Change>
  void Update(Change change) {
    {
      std::lock_guard lock(mutex_);
      change();
    }
    changed_.notify_all();
  }

  const std::size_t capacity_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<T> items_;
  bool closed_ = false;
  Status failure_;
};

}  // namespace game
