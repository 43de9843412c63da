// The PNG output folder's housekeeping: refusing a file in its place before anything is
// written, and leaving it holding this film alone afterwards.
#pragma once

#include <cstdint>
#include <string>

#include "game/status.h"

namespace game {

/// A file where the output folder (or a folder above it) should be is a bad --out value
/// (exit 2), refused before anything is written.
Status CheckOutputFolder(const std::string& out_dir);

/// Removes frame_NNNNN.png files numbered `frames` or more, left by an earlier, longer run.
Status RemoveStaleFrames(const std::string& dir, std::int64_t frames);

/// Removes frame_NNNNN.png.tmp-PID files of processes that no longer run: what a run killed
/// before it could clean up (SIGKILL, a power cut) left behind.
void RemoveDeadTemporaries(const std::string& dir);

}  // namespace game
