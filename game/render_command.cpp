// `ballbox render`: the scene (or the built-in default), simulated headlessly and written as a
// PNG sequence, then a one-line summary.
#include <cinttypes>
#include <cstdio>

#include "game/commands.h"
#include "game/frame_sequence.h"
#include "game/progress_bar.h"
#include "game/session.h"

namespace game {

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
  Expected<FrameSequenceStats> stats = RenderFrameSequence(session, sequence);
  if (!stats.HasValue()) return stats.Error();

  const FrameSequenceStats& s = stats.Value();
  std::printf("render: %s, %" PRId64 " frames, %" PRId64 " steps in %.3f s (%.1f frames/s) -> %s\n",
              session.SceneDef().name.c_str(), s.frames, s.steps, s.seconds,
              s.seconds > 0.0 ? s.frames / s.seconds : 0.0, sequence.out_dir.c_str());
  return std::nullopt;
}

}  // namespace game
