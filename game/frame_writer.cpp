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
    : dir_(std::move(dir)), encoding_(encoding), queue_(queue_capacity) {
  for (int i = 0; i < std::max(1, threads); ++i) workers_.emplace_back([this] { WorkerLoop(); });
}

FrameWriter::~FrameWriter() { Finish(); }

bool FrameWriter::Submit(std::int64_t index, render::Image image) {
  return queue_.Push(Job{index, std::move(image)});
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
