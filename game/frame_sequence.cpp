// Simulation and drawing stay on this thread (the GL context is current here); encoding and
// writing run on FrameWriter's threads, so the simulation runs ahead while frames are encoded.
#include "game/frame_sequence.h"

#include <chrono>
#include <filesystem>
#include <system_error>
#include <thread>
#include <vector>

#include "game/frame_writer.h"
#include "game/progress_bar.h"
#include "render/context.h"
#include "render/renderer.h"

namespace game {

Expected<FrameSequenceStats> RenderFrameSequence(Session& session,
                                                 const FrameSequenceOptions& options) {
  const auto start = std::chrono::steady_clock::now();

  // The context comes before the folder, so a machine without GL leaves nothing behind.
  std::string error;
  std::unique_ptr<render::GlContext> context = render::CreateOffscreenContext(error);
  if (!context) return RuntimeFailure(error);
  std::unique_ptr<render::Renderer> renderer =
      render::Renderer::Create(*context, session.ImageWidth(), session.ImageHeight(), error);
  if (!renderer) return RuntimeFailure(error);

  std::error_code ec;
  std::filesystem::create_directories(options.out_dir, ec);
  if (ec || !std::filesystem::is_directory(options.out_dir)) {
    return RuntimeFailure(options.out_dir + ": cannot create the output folder: " +
                          (ec ? ec.message() : "a file of that name is in the way"));
  }

  std::vector<render::Color> colors;
  for (const SceneBody& body : session.SceneDef().bodies) colors.push_back(body.color);

  const int threads = options.encoder_threads > 0
                          ? options.encoder_threads
                          : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  // Two frames per encoder keep every encoder busy; more would only hold memory.
  FrameWriter writer(options.out_dir, options.encoding, threads, 2 * threads);
  ProgressBar progress("render", options.frames, "frames", options.show_progress);
  FrameSequenceStats stats;
  for (std::int64_t frame = 0; frame < options.frames; ++frame) {
    if (frame > 0) {
      for (std::int64_t i = 0; i < options.every; ++i) session.Step();
      stats.steps += options.every;
    }
    renderer->Draw(session.World(), colors, session.Camera());
    render::Image image;
    renderer->ReadImage(image);
    if (!writer.Submit(frame, std::move(image))) break;
    ++stats.frames;
    progress.Update(frame + 1);
  }
  const Status written = writer.Finish();
  progress.Finish();
  if (written) return *written;

  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats.gl_description = renderer->Description();
  return stats;
}

}  // namespace game
