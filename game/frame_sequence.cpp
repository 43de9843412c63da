// Simulation and drawing stay on this thread (the GL context is current here); encoding and
// writing run on FrameWriter's threads, so the simulation runs ahead while frames are encoded.
#include "game/frame_sequence.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <string_view>
#include <system_error>
#include <thread>
#include <vector>

#include "game/frame_writer.h"
#include "game/progress_bar.h"
#include "render/context.h"
#include "render/renderer.h"

namespace game {

namespace {

// Frames past this run's last, left in the folder by an earlier and longer run, would pass for
// part of this film (a video tool takes every frame_*.png). Only names this program writes are
// touched: frame_ with the index as FrameFileName spells it, then .png.
Status RemoveStaleFrames(const std::string& dir, std::int64_t frames) {
  std::vector<std::filesystem::path> stale;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    constexpr std::string_view kPrefix = "frame_";
    constexpr std::string_view kSuffix = ".png";
    if (name.size() <= kPrefix.size() + kSuffix.size() || !name.starts_with(kPrefix) ||
        !name.ends_with(kSuffix)) {
      continue;
    }
    const std::string digits =
        name.substr(kPrefix.size(), name.size() - kPrefix.size() - kSuffix.size());
    if (digits.size() > 18 ||
        !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; })) {
      continue;
    }
    const std::int64_t index = std::stoll(digits);
    if (index >= frames && FrameFileName(index) == name && entry.is_regular_file()) {
      stale.push_back(entry.path());
    }
  }
  if (ec) return RuntimeFailure(dir + ": cannot list the output folder: " + ec.message());
  for (const std::filesystem::path& path : stale) {
    std::filesystem::remove(path, ec);
    if (ec) {
      return RuntimeFailure(path.string() + ": cannot remove this frame of an earlier run: " +
                            ec.message());
    }
  }
  return std::nullopt;
}

}  // namespace

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
      // A broken-down state is reported, never drawn; the frames before it stay.
      if (Status fault = session.Fault()) {
        (void)writer.Finish();  // the fault is the error to report; frames so far are kept
        progress.Finish();
        return *fault;
      }
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
  if (Status removed = RemoveStaleFrames(options.out_dir, options.frames)) return *removed;

  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace game
