// A frame goes to the video by copy when PNGs are written too: the two writers own their frames.
#include "game/film_output.h"

#include <filesystem>
#include <system_error>

#include "game/frame_folder.h"

namespace game {

Expected<std::unique_ptr<FilmOutput>> FilmOutput::Open(const FilmOutputOptions& options) {
  auto output = std::make_unique<FilmOutput>();
  output->out_dir_ = options.out_dir;
  if (!options.out_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(options.out_dir, ec);
    if (ec || !std::filesystem::is_directory(options.out_dir)) {
      return RuntimeFailure(options.out_dir + ": cannot create the output folder: " +
                            (ec ? ec.message() : "a file of that name is in the way"));
    }
    RemoveDeadTemporaries(options.out_dir);
    // Two frames per encoder keep every encoder busy; more would only hold memory.
    output->png_ = std::make_unique<FrameWriter>(options.out_dir, options.encoding,
                                                 options.png_threads, 2 * options.png_threads);
  }
  if (!options.video_path.empty()) {
    Expected<std::unique_ptr<VideoWriter>> video = VideoWriter::Open(options.video_path, options.video);
    if (!video.HasValue()) return video.Error();
    output->video_ = std::move(video.Value());
  }
  return output;
}

bool FilmOutput::Submit(std::int64_t index, render::Image frame) {
  if (png_ && video_) {
    render::Image copy = frame;
    if (!video_->Submit(std::move(copy))) return false;
    return png_->Submit(index, std::move(frame));
  }
  return png_ ? png_->Submit(index, std::move(frame)) : video_->Submit(std::move(frame));
}

Status FilmOutput::Finish(std::int64_t frames) {
  if (png_) {
    if (Status written = png_->Finish()) return written;
    if (Status removed = RemoveStaleFrames(out_dir_, frames)) return removed;
  }
  if (video_) return video_->Finish();
  return std::nullopt;
}

Status FilmOutput::Abandon() {
  video_.reset();
  return png_ ? png_->Finish() : std::nullopt;
}

}  // namespace game
