// `ballbox render`: the scene (or the built-in default), simulated headlessly and written as a
// PNG sequence and/or one video file, then the events summary and a one-line summary.
#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <system_error>

#include "game/commands.h"
#include "game/frame_folder.h"
#include "game/frame_sequence.h"
#include "game/progress_bar.h"
#include "game/session.h"
#include "render/video_encoder.h"

namespace game {

namespace {

// --video: refused before anything is written when the size cannot be encoded or the name is a
// folder; a build without FFmpeg cannot write it at all (exit 1, like play without GLFW).
Status CheckVideo(const std::string& path, int width, int height) {
  const render::VideoFormat format = render::VideoFormatOf(path).value_or(render::VideoFormat::kMp4);
  if (std::optional<std::string> problem = render::VideoSizeProblem(format, width, height)) {
    return BadInput("--video " + path + ": " + *problem);
  }
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    return BadInput("--video " + path + ": is a folder, not a file name");
  }
  if (!render::VideoSupportBuilt()) {
    std::string error;
    (void)render::VideoEncoder::Open(path, render::VideoSettings{}, error);
    return RuntimeFailure("--video: " + error);
  }
  return std::nullopt;
}

std::string Destination(const FrameSequenceOptions& sequence, const FrameSequenceStats& s,
                        double frame_seconds) {
  std::string to = sequence.out_dir;
  if (sequence.video_path.empty()) return to;
  if (!to.empty()) to += " and ";
  char detail[160];
  const double film_seconds = static_cast<double>(s.frames) * frame_seconds;
  switch (render::VideoFormatOf(sequence.video_path).value_or(render::VideoFormat::kMp4)) {
    case render::VideoFormat::kMp4:
      std::snprintf(detail, sizeof detail, " (H.264, yuv420p, %.4g frames/s, %.2f s)", 1.0 / frame_seconds, film_seconds);
      break;
    case render::VideoFormat::kWebm:
      std::snprintf(detail, sizeof detail, " (VP9, %.4g frames/s, %.2f s)", 1.0 / frame_seconds, film_seconds);
      break;
    case render::VideoFormat::kGif:
      std::snprintf(detail, sizeof detail, " (GIF, %" PRId64 " frames over %.2f s)", s.video_frames, film_seconds);
      break;
  }
  return to + sequence.video_path + detail;
}

}  // namespace

Status RunRender(const RenderOptions& options) {
  Expected<RunInput> input = LoadRunInput(options.run);
  if (!input.HasValue()) return input.Error();
  const std::string scene_label = options.run.scene_path.value_or("the default scene");
  Expected<std::optional<engine::BodyId>> follow = FollowedBody(input.Value().scene, options.view, scene_label);
  if (!follow.HasValue()) return follow.Error();
  Session session(input.Value().scene, std::move(input.Value().events), options.run.width,
                  options.run.height);
  if (options.run.load_state_path) {
    if (Status refused = session.LoadState(*options.run.load_state_path)) return refused;
  }

  FrameSequenceOptions sequence;
  sequence.frames = options.frames;
  sequence.every = options.every;
  // A video alone writes no PNG folder, unless --out asks for one too.
  if (options.out_dir || !options.video_path) {
    sequence.out_dir = options.out_dir ? *options.out_dir : "out/" + session.SceneDef().name;
    if (Status refused = CheckOutputFolder(sequence.out_dir)) return refused;
  }
  if (options.video_path) {
    if (Status refused = CheckVideo(*options.video_path, options.run.width, options.run.height)) return refused;
    sequence.video_path = *options.video_path;
  }
  sequence.show_progress = StderrIsTerminal();
  sequence.from = options.from;
  sequence.hud = options.hud;
  sequence.view = {options.view.camera, follow.Value()};
  Expected<FrameSequenceStats> stats = RenderFrameSequence(session, sequence);
  if (!stats.HasValue()) return stats.Error();
  if (options.run.save_state_path) {
    if (Status failed = session.SaveState(*options.run.save_state_path)) return failed;
  }

  const FrameSequenceStats& s = stats.Value();
  PrintEventSummary(session.SceneDef(), session.Events(), session.EventsLeft(), options.run.list_misses);
  const double frame_seconds = session.World().Def().dt * static_cast<double>(options.every);
  std::printf("render: %s, %" PRId64 " frames, %" PRId64 " steps in %.3f s (%.1f frames/s) -> %s\n",
              session.SceneDef().name.c_str(), s.frames, s.steps, s.seconds,
              s.seconds > 0.0 ? s.frames / s.seconds : 0.0,
              Destination(sequence, s, frame_seconds).c_str());
  return std::nullopt;
}

}  // namespace game
