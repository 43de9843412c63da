// Snapshots: a world's whole state as bytes (World::TakeSnapshot), and what restoring one says.
#pragma once

#include <string>

namespace engine {

/// The outcome of World::RestoreSnapshot: empty `error` on success; otherwise why the snapshot
/// was refused (taken from a world with other settings, truncated, corrupt), and the world is
/// left as it was.
struct RestoreResult {
  std::string error;
  explicit operator bool() const { return error.empty(); }
};

}  // namespace engine
