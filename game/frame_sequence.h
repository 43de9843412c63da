// The render loop behind `ballbox render`: simulate, draw every K-th step through an offscreen
// GL context, and hand the pictures to the PNG writers and the video encoder.
#pragma once

#include <cstdint>
#include <string>

#include "game/film_camera.h"
#include "game/session.h"
#include "game/status.h"
#include "render/png_writer.h"

namespace game {

struct FrameSequenceOptions {
  std::int64_t frames = 300;  ///< N ≥ 1
  std::int64_t every = 1;     ///< K ≥ 1 steps between frames
  std::string out_dir;        ///< PNG frames here, created when missing; empty: no PNG files
  std::string video_path;     ///< the film as one video file (.mp4, .webm, .gif); empty: none
  render::PngEncoding encoding = render::PngEncoding::kFast;
  bool show_progress = false;
  int encoder_threads = 0;    ///< 0: one per core
  std::int64_t from = 0;      ///< steps simulated before frame 0
  bool hud = false;           ///< step, time and state hash drawn on every frame
  FilmView view;              ///< --camera instead of the session's view; --follow
};

struct FrameSequenceStats {
  std::int64_t frames = 0;
  std::int64_t steps = 0;  ///< from + (N − 1)·K: the last frame is the last state simulated
  double seconds = 0.0;    ///< wall time, from context creation to the last file on disk
  std::int64_t video_frames = 0;  ///< frames in the video (a GIF may keep fewer)
};

/// Writes out_dir/frame_00000.png … and/or the video for frames k = 0 … N−1, frame k showing
/// the session after from + k·K more steps. Images are the session's image size, seen through
/// its camera (or view's camera, or following view's body). Frames of an earlier run numbered N or more
/// are removed from the folder, so it holds this film alone. Failures (GL context, output,
/// writing) exit 1, and so does Ctrl-C, which stops at the next frame: the frames written so far
/// stay, the video and every temporary file go, and the message says which frames are complete.
Expected<FrameSequenceStats> RenderFrameSequence(Session& session,
                                                 const FrameSequenceOptions& options);

}  // namespace game
