// The signal handler only stores to a lock-free atomic, the one thing a handler may safely do.
#include "game/interrupt.h"

#include <atomic>
#include <csignal>

namespace game {

namespace {

std::atomic<bool> g_interrupted{false};
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void OnInterrupt(int) { g_interrupted.store(true); }

}  // namespace

InterruptGuard::InterruptGuard() {
  g_interrupted = false;
  previous_int_ = std::signal(SIGINT, OnInterrupt);
  previous_term_ = std::signal(SIGTERM, OnInterrupt);
}

InterruptGuard::~InterruptGuard() {
  std::signal(SIGINT, previous_int_);
  std::signal(SIGTERM, previous_term_);
}

bool Interrupted() { return g_interrupted.load(); }

}  // namespace game
