// Writes rendered frames as PNG files on worker threads while the simulation runs ahead; a
// bounded queue keeps memory flat however far behind the encoders fall. The frames are encoded
// side by side but written one after another in the order they were submitted, so a write that
// fails (a full disk) leaves every frame before it and none after.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <mutex>
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
    std::uint64_t turn = 0;  ///< which Submit it came from, from 0: the order its file is written in
    render::Image image;
  };
  void WorkerLoop();
  Status Write(const Job& job);
  /// Blocks until the frames of every earlier turn are written; false once a write has failed.
  bool WaitForTurn(std::uint64_t turn);
  /// Hands the next turn on, or (`failed`) stops every writer: no frame follows a failed one.
  void EndTurn(bool failed);

  const std::string dir_;
  const render::PngEncoding encoding_;
  WorkQueue<Job> queue_;
  std::vector<std::thread> workers_;
  std::uint64_t submitted_ = 0;  ///< Submit's thread alone
  std::mutex turn_mutex_;
  std::condition_variable turn_changed_;
  std::uint64_t next_turn_ = 0;
  bool stopped_ = false;
};

}  // namespace game
