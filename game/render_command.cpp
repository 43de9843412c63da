// `ballbox render`: the scene (or the built-in default), simulated headlessly and written as a
// PNG sequence, then a one-line summary.
#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <system_error>

#include "game/commands.h"
#include "game/frame_sequence.h"
#include "game/progress_bar.h"
#include "game/session.h"

namespace game {

namespace {

// A file where the output folder (or a folder above it) should be is a bad --out value, refused
// before anything is written (exit 2), like any other bad flag.
Status CheckOutputFolder(const std::string& out_dir) {
  std::error_code ec;
  for (std::filesystem::path p = out_dir; !p.empty(); p = p.parent_path()) {
    if (std::filesystem::exists(p, ec)) {
      if (std::filesystem::is_directory(p, ec)) return std::nullopt;
      std::string message = out_dir + ": ";
      if (p != out_dir) message += p.string() + " ";
      message += "is a file, not a folder (--out names the folder for the frames)";
      return BadInput(message);
    }
    if (p == p.parent_path()) break;
  }
  return std::nullopt;
}

}  // namespace

Status RunRender(const RenderOptions& options) {
  Expected<RunInput> input = LoadRunInput(options.run);
  if (!input.HasValue()) return input.Error();
  Session session(input.Value().scene, std::move(input.Value().events), options.run.width,
                  options.run.height);

  FrameSequenceOptions sequence;
  sequence.frames = options.frames;
  sequence.every = options.every;
  sequence.out_dir = options.out_dir ? *options.out_dir : "out/" + session.SceneDef().name;
  sequence.show_progress = StderrIsTerminal();
  if (Status refused = CheckOutputFolder(sequence.out_dir)) return refused;
  Expected<FrameSequenceStats> stats = RenderFrameSequence(session, sequence);
  if (!stats.HasValue()) return stats.Error();

  const FrameSequenceStats& s = stats.Value();
  std::printf("render: %s, %" PRId64 " frames, %" PRId64 " steps in %.3f s (%.1f frames/s) -> %s\n",
              session.SceneDef().name.c_str(), s.frames, s.steps, s.seconds,
              s.seconds > 0.0 ? s.frames / s.seconds : 0.0, sequence.out_dir.c_str());
  return std::nullopt;
}

}  // namespace game
