// PNG frames on worker threads. Each frame is encoded on its own, then written under a temporary
// name and renamed, in turn: the files come out identical whatever order the workers finish
// encoding in, and a full disk stops the sequence at one place. (Written as each was encoded, a
// worker held up encoding frame 0 found the disk already filled by frames 1-17.)
#include "game/frame_writer.h"

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <utility>

#include "game/output_file.h"

namespace game {

std::string FrameFileName(std::int64_t index) {
  char name[40];
  std::snprintf(name, sizeof name, "frame_%05" PRId64 ".png", index);
  return name;
}

FrameWriter::FrameWriter(std::string dir, render::PngEncoding encoding, int threads,
                         std::size_t queue_capacity)
    : dir_(std::move(dir)), encoding_(encoding), queue_(queue_capacity) {
  for (int i = 0; i < std::max(1, threads); ++i) workers_.emplace_back([this] { WorkerLoop(); });
}

FrameWriter::~FrameWriter() { Finish(); }

bool FrameWriter::Submit(std::int64_t index, render::Image image) {
  return queue_.Push(Job{index, submitted_++, std::move(image)});
}

Status FrameWriter::Finish() {
  queue_.Close();
  for (std::thread& worker : workers_) worker.join();
  workers_.clear();
  return queue_.FirstFailure();
}

void FrameWriter::WorkerLoop() {
  // After a failure the queue hands out nothing more: the remaining frames are dropped, and a
  // Submit blocked on a full queue returns, so the renderer learns of the failure.
  while (std::optional<Job> job = queue_.Pop()) {
    if (Status written = Write(*job)) queue_.Fail(std::move(*written));
  }
}

Status FrameWriter::Write(const Job& job) {
  const std::string path = dir_ + "/" + FrameFileName(job.index);
  const std::vector<std::uint8_t> png = render::EncodePng(job.image, encoding_);
  if (!WaitForTurn(job.turn)) return {};  // an earlier frame failed, and said so
  const Status written = [&]() -> Status {
    if (png.empty()) return RuntimeFailure(path + ": cannot encode the PNG: out of memory");
    Expected<AtomicOutputFile> file = AtomicOutputFile::Open(path);
    if (!file.HasValue()) return file.Error();
    std::fwrite(png.data(), 1, png.size(), file.Value().Stream());
    return file.Value().Commit();
  }();
  EndTurn(written.has_value());
  return written;
}

bool FrameWriter::WaitForTurn(std::uint64_t turn) {
  std::unique_lock lock(turn_mutex_);
  turn_changed_.wait(lock, [&] { return next_turn_ == turn || stopped_; });
  return !stopped_;
}

void FrameWriter::EndTurn(bool failed) {
  {
    std::lock_guard lock(turn_mutex_);
    if (failed) {
      stopped_ = true;
    } else {
      ++next_turn_;
    }
  }
  turn_changed_.notify_all();
}

}  // namespace game
