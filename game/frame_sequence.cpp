// Simulation and drawing stay on this thread (the GL context is current here); encoding and
// writing run on the outputs' threads, so the simulation runs ahead while frames are encoded.
#include "game/frame_sequence.h"

#include <algorithm>
#include <chrono>
#include <thread>
#include <vector>

#include "game/film_camera.h"
#include "game/film_output.h"
#include "game/frame_writer.h"
#include "game/gif_colors.h"
#include "game/hud.h"
#include "game/interrupt.h"
#include "game/progress_bar.h"
#include "game/scene_colors.h"
#include "render/bitmap_text.h"
#include "render/context.h"
#include "render/renderer.h"

namespace game {

namespace {

FilmOutputOptions OutputOptions(const Session& session, const FrameSequenceOptions& options) {
  FilmOutputOptions out;
  out.out_dir = options.out_dir;
  out.encoding = options.encoding;
  out.png_threads = options.encoder_threads > 0
                        ? options.encoder_threads
                        : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  out.video_path = options.video_path;
  if (!options.video_path.empty()) {
    out.video.format = render::VideoFormatOf(options.video_path).value_or(render::VideoFormat::kMp4);
    out.video.width = session.ImageWidth();
    out.video.height = session.ImageHeight();
    out.video.frame_seconds = session.World().Def().dt * static_cast<double>(options.every);
    out.video.gif_keep = GifKeepColors(session.SceneDef(), session.World());
  }
  return out;
}

// Why the film stopped early, and what of it is there to keep.
Failure InterruptedAt(std::int64_t frame, const FrameSequenceOptions& options) {
  std::string message = "interrupted at frame " + std::to_string(frame) + " of " +
                        std::to_string(options.frames) + ": ";
  if (!options.out_dir.empty()) {
    message += frame == 0 ? "no frame was complete in " + options.out_dir
                          : FrameFileName(0) + " to " + FrameFileName(frame - 1) + " in " +
                                options.out_dir + " are complete";
  }
  if (!options.video_path.empty()) {
    message += std::string(options.out_dir.empty() ? "" : "; ") + options.video_path +
               " was not written";
  }
  return RuntimeFailure(message);
}

// The simulation's steps, with the film camera following each one; Ctrl-C cuts them short (a
// long --from must not make the user wait), and the caller then reports the interruption.
Status Simulate(Session& session, FilmCamera& camera, std::int64_t steps) {
  for (std::int64_t i = 0; i < steps && !Interrupted(); ++i) {
    session.Step();
    camera.Advance(session.World());
    // A broken-down state is reported, never drawn; the frames before it stay.
    if (Status fault = session.Fault()) return fault;
  }
  return std::nullopt;
}

render::Image DrawFrame(render::Renderer& renderer, const Session& session,
                        const FilmCamera& camera, const SceneColors& colors, bool hud) {
  renderer.Draw(session.World(), colors.bodies, camera.For(session.ImageWidth(), session.ImageHeight()),
                {}, colors.particles);
  render::Image image;
  renderer.ReadImage(image);
  if (hud) {
    const double time = static_cast<double>(session.StepIndex()) * session.World().Def().dt;
    PaintHud(image, HudText(session.StepIndex(), time, session.World().StateHash()));
  }
  return image;
}

}  // namespace

Expected<FrameSequenceStats> RenderFrameSequence(Session& session,
                                                 const FrameSequenceOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  // The context comes before any output, so a machine without GL leaves nothing behind.
  std::string error;
  std::unique_ptr<render::GlContext> context = render::CreateOffscreenContext(error);
  if (!context) return RuntimeFailure(error);
  std::unique_ptr<render::Renderer> renderer =
      render::Renderer::Create(*context, session.ImageWidth(), session.ImageHeight(), error);
  if (!renderer) return RuntimeFailure(error);
  Expected<std::unique_ptr<FilmOutput>> opened = FilmOutput::Open(OutputOptions(session, options));
  if (!opened.HasValue()) return opened.Error();
  FilmOutput& output = *opened.Value();

  const SceneColors colors = ColorsOf(session.SceneDef());
  FilmCamera camera(options.view.camera.value_or(session.View()), options.view.follow, session.World());
  InterruptGuard interrupt;
  ProgressBar progress("render", options.frames, "frames", options.show_progress);
  FrameSequenceStats stats;
  const std::int64_t first_step = session.StepIndex();
  for (std::int64_t frame = 0; frame < options.frames; ++frame) {
    const std::int64_t steps = frame == 0 ? options.from : options.every;
    if (Status fault = Simulate(session, camera, steps)) {
      (void)output.Abandon();  // the fault is the error to report; frames so far are kept
      progress.Finish();
      return *fault;
    }
    stats.steps = session.StepIndex() - first_step;
    if (Interrupted()) {
      const Status kept = output.Abandon();
      progress.Finish();
      return kept ? *kept : InterruptedAt(frame, options);
    }
    if (!output.Submit(frame, DrawFrame(*renderer, session, camera, colors, options.hud))) break;
    ++stats.frames;
    progress.Update(frame + 1);
  }
  const Status written = output.Finish(options.frames);
  progress.Finish();
  if (written) return *written;
  stats.video_frames = output.VideoFrames();
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace game
