// Frames per second of `ballbox render` (default scene, 800x600, 300 frames) with the fast PNG
// settings against stb's defaults, measured in one run, and the cost of each stage of a frame.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "bench/bench_args.h"
#include "bench/bench_common.h"
#include "game/commands.h"
#include "game/frame_sequence.h"
#include "game/session.h"
#include "render/context.h"
#include "render/png_writer.h"
#include "render/renderer.h"

namespace {

using bench::Median;
using bench::CpuModel;
using bench::LoadAverage;

using bench::Clock;
using bench::SecondsSince;

struct Settings {
  std::int64_t frames = 300;
  int width = 800;
  int height = 600;
  int repeats = 3;
  int threads = 0;  // 0: as ballbox render (one encoder per core)
  std::string out_dir = "bench-out/render";
};

bench::Args Arguments(Settings& settings) {
  bench::Args args("bench_render", "`ballbox render` of the default scene with the fast PNG settings against stb's "
                                   "defaults, and the cost of each stage of a frame.");
  args.Value("--frames N", &settings.frames, "frames per run (default 300)", std::int64_t{1})
      .Value("--repeats R", &settings.repeats, "runs per PNG setting (default 3)", 1)
      .Value("--threads T", &settings.threads, "PNG encoder threads; 0: one per core, as ballbox render (default 0)", 0)
      .Value("--out DIR", &settings.out_dir, "folder for the frames and the CSV file (default bench-out/render)");
  return args;
}

std::uintmax_t FolderBytes(const std::string& dir) {
  std::uintmax_t total = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) total += entry.file_size();
  return total;
}

game::Session DefaultSession(const Settings& settings) {
  game::Expected<game::RunInput> input =
      game::LoadRunInput(game::RunOptions{{}, {}, settings.width, settings.height});
  if (!input.HasValue()) {
    std::fprintf(stderr, "error: %s\n", input.Error().message.c_str());
    std::exit(1);
  }
  return game::Session(input.Value().scene, input.Value().events, settings.width,
                       settings.height);
}

// One whole `ballbox render` run: what the command does after parsing its flags.
game::FrameSequenceStats RenderRun(const Settings& settings, render::PngEncoding encoding,
                                   const std::string& out_dir) {
  game::Session session = DefaultSession(settings);
  game::FrameSequenceOptions options;
  options.frames = settings.frames;
  options.out_dir = out_dir;
  options.encoding = encoding;
  options.encoder_threads = settings.threads;
  game::Expected<game::FrameSequenceStats> stats = game::RenderFrameSequence(session, options);
  if (!stats.HasValue()) {
    std::fprintf(stderr, "error: %s\n", stats.Error().message.c_str());
    std::exit(1);
  }
  return stats.Value();
}

struct StageCosts {
  double simulate_ms = 0;
  double draw_read_ms = 0;
  double encode_fast_ms = 0;
  double encode_stb_ms = 0;
  std::string gl;
};

// Each stage alone on this thread, per frame: simulation, draw + read-back, encoding.
StageCosts MeasureStages(const Settings& settings) {
  StageCosts costs;
  game::Session session = DefaultSession(settings);
  std::vector<render::Color> colors;
  for (const game::SceneBody& body : session.SceneDef().bodies) colors.push_back(body.color);
  std::string error;
  std::unique_ptr<render::GlContext> context = render::CreateOffscreenContext(error);
  std::unique_ptr<render::Renderer> renderer =
      context ? render::Renderer::Create(*context, settings.width, settings.height, error)
              : nullptr;
  if (!renderer) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    std::exit(1);
  }
  costs.gl = renderer->Description();

  std::vector<render::Image> images(static_cast<std::size_t>(settings.frames));
  double simulate = 0;
  double draw_read = 0;
  renderer->Draw(session.World(), colors, session.Camera());  // warm-up: shader compilation
  renderer->ReadImage(images[0]);
  for (std::int64_t frame = 0; frame < settings.frames; ++frame) {
    auto start = Clock::now();
    if (frame > 0) session.Step();
    simulate += SecondsSince(start);
    start = Clock::now();
    renderer->Draw(session.World(), colors, session.Camera());
    renderer->ReadImage(images[frame]);
    draw_read += SecondsSince(start);
  }
  auto start = Clock::now();
  for (const render::Image& image : images) render::EncodePng(image, render::PngEncoding::kFast);
  const double fast = SecondsSince(start);
  start = Clock::now();
  for (const render::Image& image : images) render::EncodePng(image, render::PngEncoding::kStbDefault);
  const double stb = SecondsSince(start);

  const double per_frame_ms = 1000.0 / settings.frames;
  costs.simulate_ms = simulate * per_frame_ms;
  costs.draw_read_ms = draw_read * per_frame_ms;
  costs.encode_fast_ms = fast * per_frame_ms;
  costs.encode_stb_ms = stb * per_frame_ms;
  return costs;
}

}  // namespace

int main(int argc, char** argv) {
  Settings settings;
  if (const std::optional<int> exit_code = Arguments(settings).Parse(argc, argv)) return *exit_code;
  const unsigned cores = std::thread::hardware_concurrency();
  const std::string load_before = LoadAverage();
  const int threads = settings.threads > 0 ? settings.threads : static_cast<int>(std::max(1u, cores));

  // Alternate the two settings, so drifting machine load hits both alike; report medians.
  const std::string fast_dir = settings.out_dir + "/fast";
  const std::string stb_dir = settings.out_dir + "/stb_default";
  std::vector<double> fast_seconds;
  std::vector<double> stb_seconds;
  for (int r = 0; r < settings.repeats; ++r) {
    fast_seconds.push_back(RenderRun(settings, render::PngEncoding::kFast, fast_dir).seconds);
    stb_seconds.push_back(RenderRun(settings, render::PngEncoding::kStbDefault, stb_dir).seconds);
  }
  const StageCosts stages = MeasureStages(settings);

  const double fast = Median(fast_seconds);
  const double stb = Median(stb_seconds);
  const double frames = static_cast<double>(settings.frames);
  std::printf("ballbox render: default scene, %dx%d, %lld frames, every step; median of %d runs each\n",
              settings.width, settings.height, static_cast<long long>(settings.frames),
              settings.repeats);
  std::printf("machine: %s, %u cores; %s; %d encoder threads\n", CpuModel().c_str(), cores,
              stages.gl.c_str(), threads);
  std::printf("load average (1, 5, 15 min) before: %s, after: %s\n\n", load_before.c_str(),
              LoadAverage().c_str());
  std::printf("| PNG settings | wall time (s) | frames/s | ms/frame | output (MB) |\n");
  std::printf("|---|---:|---:|---:|---:|\n");
  std::printf("| fast: filter none, zlib level 1 | %.3f | %.1f | %.2f | %.1f |\n", fast,
              frames / fast, 1000.0 * fast / frames, FolderBytes(fast_dir) / 1e6);
  std::printf("| stb defaults | %.3f | %.1f | %.2f | %.1f |\n", stb, frames / stb,
              1000.0 * stb / frames, FolderBytes(stb_dir) / 1e6);
  std::printf("\nspeed-up: %.2fx\n\n", stb / fast);
  std::printf("one frame's stages alone, on one thread (ms/frame):\n\n");
  std::printf("| simulate | draw + read back | encode, fast | encode, stb defaults |\n");
  std::printf("|---:|---:|---:|---:|\n");
  std::printf("| %.3f | %.2f | %.2f | %.2f |\n", stages.simulate_ms, stages.draw_read_ms,
              stages.encode_fast_ms, stages.encode_stb_ms);

  const std::string csv_path = settings.out_dir + "/render_bench.csv";
  if (std::FILE* csv = std::fopen(csv_path.c_str(), "w")) {
    std::fprintf(csv, "encoding,run,seconds,frames_per_second\n");
    for (int r = 0; r < settings.repeats; ++r) {
      std::fprintf(csv, "fast,%d,%.6f,%.3f\n", r, fast_seconds[r], frames / fast_seconds[r]);
      std::fprintf(csv, "stb_default,%d,%.6f,%.3f\n", r, stb_seconds[r], frames / stb_seconds[r]);
    }
    std::fclose(csv);
    std::printf("\nper-run figures: %s\n", csv_path.c_str());
  }
  return 0;
}
