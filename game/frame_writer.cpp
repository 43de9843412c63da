// PNG frames on worker threads. Each frame is encoded on its own and written under a temporary
// name, then renamed: the files come out identical whatever order the workers finish in.
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
    : dir_(std::move(dir)),
      encoding_(encoding),
      queue_capacity_(std::max<std::size_t>(1, queue_capacity)) {
  for (int i = 0; i < std::max(1, threads); ++i) workers_.emplace_back([this] { WorkerLoop(); });
}

FrameWriter::~FrameWriter() { Finish(); }

bool FrameWriter::Submit(std::int64_t index, render::Image image) {
  std::unique_lock lock(mutex_);
  slot_free_.wait(lock, [this] { return queue_.size() < queue_capacity_ || failure_; });
  if (failure_ || closing_) return false;
  queue_.push_back(Job{index, std::move(image)});
  lock.unlock();
  job_ready_.notify_one();
  return true;
}

Status FrameWriter::Finish() {
  {
    std::lock_guard lock(mutex_);
    closing_ = true;
  }
  job_ready_.notify_all();
  for (std::thread& worker : workers_) worker.join();
  workers_.clear();
  std::lock_guard lock(mutex_);
  return failure_;
}

void FrameWriter::WorkerLoop() {
  for (;;) {
    Job job;
    {
      std::unique_lock lock(mutex_);
      job_ready_.wait(lock, [this] { return !queue_.empty() || closing_; });
      if (queue_.empty()) return;
      job = std::move(queue_.front());
      queue_.pop_front();
      // After a failure the remaining frames are dropped, not written.
      if (failure_) continue;
    }
    slot_free_.notify_one();
    Status written = Write(job);
    if (written) {
      std::lock_guard lock(mutex_);
      if (!failure_) failure_ = std::move(written);
      // Wake a Submit blocked on a full queue, so the renderer learns of the failure.
      slot_free_.notify_all();
    }
  }
}

Status FrameWriter::Write(const Job& job) const {
  const std::string path = dir_ + "/" + FrameFileName(job.index);
  const std::vector<std::uint8_t> png = render::EncodePng(job.image, encoding_);
  if (png.empty()) return RuntimeFailure(path + ": cannot encode the PNG: out of memory");
  Expected<AtomicOutputFile> file = AtomicOutputFile::Open(path);
  if (!file.HasValue()) return file.Error();
  std::fwrite(png.data(), 1, png.size(), file.Value().Stream());
  return file.Value().Commit();
}

}  // namespace game
