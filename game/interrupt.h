// Ctrl-C and SIGTERM as a request to stop, for commands that must clean up on the way out
// (render removes its temporary files and says which frames are complete; play writes its
// recording). Outside a guard the signals keep their usual effect.
#pragma once

namespace game {

/// While one lives, SIGINT and SIGTERM set a flag instead of ending the process.
class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

 private:
  void (*previous_int_)(int);
  void (*previous_term_)(int);
};

/// Whether a stop was requested since the current guard was made.
bool Interrupted();

}  // namespace game
