// One worker encodes in order (a video is a sequence; libx264 and libvpx thread internally).
#include "game/video_writer.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "game/output_file.h"

namespace game {

namespace {

// Enough for the encoder to start on one frame while the next is drawn, little enough that
// memory stays flat at any size.
constexpr std::size_t kQueueFrames = 4;

}  // namespace

Expected<std::unique_ptr<VideoWriter>> VideoWriter::Open(const std::string& path,
                                                         const render::VideoSettings& settings) {
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!folder.empty()) std::filesystem::create_directories(folder, ec);
  if (ec) return RuntimeFailure(path + ": cannot create its folder: " + ec.message());
  std::string temp_path = TemporaryPath(path);
  std::string error;
  std::unique_ptr<render::VideoEncoder> encoder = render::VideoEncoder::Open(temp_path, settings, error);
  if (!encoder) {
    std::remove(temp_path.c_str());
    return RuntimeFailure(path + ": " + error);
  }
  return std::unique_ptr<VideoWriter>(new VideoWriter(path, std::move(temp_path), std::move(encoder)));
}

VideoWriter::VideoWriter(std::string path, std::string temp_path,
                         std::unique_ptr<render::VideoEncoder> encoder)
    : path_(std::move(path)),
      temp_path_(std::move(temp_path)),
      encoder_(std::move(encoder)),
      queue_(kQueueFrames) {
  worker_ = std::thread([this] { WorkerLoop(); });
}

VideoWriter::~VideoWriter() {
  if (finished_) return;
  queue_.Abandon();  // the file is going: encoding what waits would only delay that
  if (worker_.joinable()) worker_.join();
  encoder_.reset();  // closes the file before it goes
  std::remove(temp_path_.c_str());
}

bool VideoWriter::Submit(render::Image frame) { return queue_.Push(std::move(frame)); }

Status VideoWriter::Finish() {
  queue_.Close();
  if (worker_.joinable()) worker_.join();
  if (Status failed = queue_.FirstFailure()) return failed;
  std::string error;
  if (!encoder_->Finish(error)) return RuntimeFailure(path_ + ": " + error);
  if (std::rename(temp_path_.c_str(), path_.c_str()) != 0) {
    return RuntimeFailure(path_ + ": cannot write: " + std::strerror(errno));
  }
  finished_ = true;
  return std::nullopt;
}

void VideoWriter::WorkerLoop() {
  while (std::optional<render::Image> frame = queue_.Pop()) {
    std::string error;
    if (!encoder_->Write(*frame, error)) queue_.Fail(RuntimeFailure(path_ + ": " + error));
  }
}

}  // namespace game
