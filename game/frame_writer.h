// Writes rendered frames as PNG files on worker threads while the simulation runs ahead; a
// bounded queue keeps memory flat however far behind the encoders fall.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include "game/status.h"
#include "game/work_queue.h"
#include "render/image.h"
#include "render/png_writer.h"

namespace game {

/// "frame_00042.png": five digits, more once the index needs them.
std::string FrameFileName(std::int64_t index);

class FrameWriter {
 public:
  /// Writes into the existing folder `dir` with `threads` encoders (at least 1), holding at most
  /// `queue_capacity` (at least 1) frames that wait for one.
  FrameWriter(std::string dir, render::PngEncoding encoding, int threads,
              std::size_t queue_capacity);
  /// Waits for the queued frames, as Finish does.
  ~FrameWriter();
  FrameWriter(const FrameWriter&) = delete;
  FrameWriter& operator=(const FrameWriter&) = delete;

  /// Queues frame `index` for dir/FrameFileName(index); blocks while the queue is full. Returns
  /// false, dropping the frame, once a write has failed: there is no point rendering on.
  bool Submit(std::int64_t index, render::Image image);

  /// Waits until every queued frame is on disk; returns the first failure, if any.
  Status Finish();

 private:
  struct Job {
    std::int64_t index = 0;
    render::Image image;
  };
  void WorkerLoop();
  Status Write(const Job& job) const;

  const std::string dir_;
  const render::PngEncoding encoding_;
  WorkQueue<Job> queue_;
  std::vector<std::thread> workers_;
};

}  // namespace game
