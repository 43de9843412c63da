// The render loop behind `ballbox render`: simulate, draw every K-th step through an offscreen
// GL context, and hand the pictures to the PNG writers.
#pragma once

#include <cstdint>
#include <string>

#include "game/session.h"
#include "game/status.h"
#include "render/png_writer.h"

namespace game {

struct FrameSequenceOptions {
  std::int64_t frames = 300;  ///< N ≥ 1
  std::int64_t every = 1;     ///< K ≥ 1 steps between frames
  std::string out_dir;        ///< created when missing
  render::PngEncoding encoding = render::PngEncoding::kFast;
  bool show_progress = false;
  int encoder_threads = 0;    ///< 0: one per core
};

struct FrameSequenceStats {
  std::int64_t frames = 0;
  std::int64_t steps = 0;  ///< (N − 1)·K: the last frame is the last state simulated
  double seconds = 0.0;    ///< wall time, from context creation to the last file on disk
};

/// Writes out_dir/frame_00000.png … for frames k = 0 … N−1, frame k showing the session after
/// k·K more steps (frame 0: its state now). Images are the session's image size, seen through
/// its camera. Frames of an earlier run numbered N or more are removed from the folder, so it
/// holds this film alone. Failures (GL context, output folder, writing) exit 1.
Expected<FrameSequenceStats> RenderFrameSequence(Session& session,
                                                 const FrameSequenceOptions& options);

}  // namespace game
