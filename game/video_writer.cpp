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
    : path_(std::move(path)), temp_path_(std::move(temp_path)), encoder_(std::move(encoder)) {
  worker_ = std::thread([this] { WorkerLoop(); });
}

VideoWriter::~VideoWriter() {
  if (!finished_) {
    std::lock_guard lock(mutex_);
    queue_.clear();  // the file is going: encoding what waits would only delay that
  }
  Stop();
  if (!finished_) {
    encoder_.reset();  // closes the file before it goes
    std::remove(temp_path_.c_str());
  }
}

bool VideoWriter::Submit(render::Image frame) {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return queue_.size() < kQueueFrames || failure_; });
  if (failure_ || closing_) return false;
  queue_.push_back(std::move(frame));
  lock.unlock();
  changed_.notify_all();
  return true;
}

void VideoWriter::Stop() {
  {
    std::lock_guard lock(mutex_);
    closing_ = true;
  }
  changed_.notify_all();
  if (worker_.joinable()) worker_.join();
}

Status VideoWriter::Finish() {
  Stop();
  if (failure_) return failure_;
  std::string error;
  if (!encoder_->Finish(error)) return RuntimeFailure(path_ + ": " + error);
  if (std::rename(temp_path_.c_str(), path_.c_str()) != 0) {
    return RuntimeFailure(path_ + ": cannot write: " + std::strerror(errno));
  }
  finished_ = true;
  return std::nullopt;
}

void VideoWriter::WorkerLoop() {
  for (;;) {
    render::Image frame;
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [this] { return !queue_.empty() || closing_; });
      if (queue_.empty()) return;
      frame = std::move(queue_.front());
      queue_.pop_front();
    }
    changed_.notify_all();
    std::string error;
    if (!encoder_->Write(frame, error)) {
      std::lock_guard lock(mutex_);
      failure_ = RuntimeFailure(path_ + ": " + error);
      queue_.clear();
      changed_.notify_all();
      return;
    }
  }
}

}  // namespace game
