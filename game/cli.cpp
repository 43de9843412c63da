// Command-line parsing. Every mistake is bad usage (exit 2) with one message naming the flag.
#include "game/cli.h"

#include <charconv>
#include <cmath>
#include <set>

#include "engine/world_def.h"
#include "game/limits.h"
#include "render/video_encoder.h"

namespace game {

namespace {

constexpr const char* kUsage =
    "ballbox: a 2D ball-and-boxes physics game\n"
    "\n"
    "usage:\n"
    "  ballbox render [SCENE] [--script FILE] [--frames N] [--every K] [--size WxH] [--out DIR]\n"
    "                 [--video FILE] [--camera X,Y,WIDTH] [--follow ID] [--from STEP] [--hud]\n"
    "                 [--misses]\n"
    "  ballbox sim    [SCENE] [--script FILE] --steps N [--dump FILE.csv] [--dump-every K]\n"
    "                 [--size WxH] [--misses]\n"
    "  ballbox play   [SCENE] [--script FILE] [--record FILE] [--size WxH] [--camera X,Y,WIDTH]\n"
    "                 [--follow ID] [--misses]\n"
    "  ballbox --help | ballbox COMMAND --help | ballbox --version\n"
    "\n"
    "SCENE is a scene file (JSON); without one, the built-in default scene runs with its demo\n"
    "clicks. Exit codes: 0 success, 2 bad usage or input, 1 any other failure.\n";

constexpr const char* kRunFlags =
    "  SCENE            scene file (JSON); default: the built-in scene and its demo script\n"
    "  --script FILE    input script of clicks to replay (step event x y per line)\n"
    "  --size WxH       image size in pixels (default 800x600); any size shows at least what\n"
    "                   800x600 shows. Pixel clicks map through it unless the script has a\n"
    "                   `size W H` line\n"
    "  --misses         list each click that hit no ball (step, where, the nearest ball)\n"
    "  --threads N      worker threads for the physics step (default: one per core); the\n"
    "                   state hash and the images are the same for every N\n"
    "  --save-state FILE  at the end, write the whole simulation state to FILE\n"
    "  --load-state FILE  start from a state saved from this scene (script events before its\n"
    "                   step are skipped)\n";

constexpr const char* kViewFlags =
    "  --camera X,Y,WIDTH  look at world point (X, Y) with WIDTH metres across an 800x600\n"
    "                   picture, instead of the scene's camera (pixel clicks in scripts still\n"
    "                   map through the scene's camera)\n"
    "  --follow ID      the camera tracks the body with this id, smoothly\n";

std::string RenderHelp() {
  return std::string(
             "usage: ballbox render [SCENE] [--script FILE] [--frames N] [--every K] [--size WxH]\n"
             "                      [--out DIR] [--video FILE] [--camera X,Y,WIDTH] [--follow ID]\n"
             "                      [--from STEP] [--hud] [--misses]\n\n"
             "Simulates headlessly and writes DIR/frame_00000.png, frame_00001.png, ... and/or one\n"
             "video file; frame k shows the world after k*K steps (frame 0 is the initial state),\n"
             "or after STEP + k*K steps with --from STEP.\n\n") +
         kRunFlags +
         "  --frames N       number of frames to write (default 300)\n"
         "  --every K        simulation steps between frames (default 1)\n"
         "  --out DIR        output folder (default out/<scene name>; none with --video alone)\n"
         "  --video FILE     write the film as one file, by its extension: .mp4 (H.264, yuv420p),\n"
         "                   .webm (VP9) or .gif; it plays in real time (1/(dt*K) frames/s)\n" +
         kViewFlags +
         "  --from STEP      simulate STEP steps first: frame 0 shows step STEP\n"
         "  --hud            draw the step, simulated time and state hash in the top-left corner\n";
}

std::string SimHelp() {
  return std::string(
             "usage: ballbox sim [SCENE] [--script FILE] --steps N [--dump FILE.csv] "
             "[--dump-every K] [--size WxH] [--misses]\n\n"
             "Simulates N steps with no rendering and prints \"state-hash: <16 hex digits>\" of the\n"
             "final state as its last line.\n\n") +
         kRunFlags +
         "  --steps N        steps to simulate (required)\n"
         "  --dump FILE.csv  write step,time,id,x,y,vx,vy,angle,omega per body per dumped step\n"
         "  --dump-every K   dump every K-th step, step 0 included (default 1)\n";
}

std::string PlayHelp() {
  return std::string(
             "usage: ballbox play [SCENE] [--script FILE] [--record FILE] [--size WxH]\n"
             "                    [--camera X,Y,WIDTH] [--follow ID] [--misses]\n\n"
             "Opens a window and runs the scene in real time; a left click pushes a ball away\n"
             "from the click point.\n\n") +
         kRunFlags + "  --record FILE    write every applied event as an input script\n" + kViewFlags;
}

Failure Usage(const std::string& command, const std::string& message) {
  return BadInput(message + " (see: ballbox " + (command.empty() ? "" : command + " ") + "--help)");
}

struct FlagSpec {
  const char* name;
  std::initializer_list<const char*> commands;
  bool takes_value;
};

const FlagSpec kFlags[] = {
    {"--script", {"render", "sim", "play"}, true}, {"--size", {"render", "sim", "play"}, true},
    {"--misses", {"render", "sim", "play"}, false}, {"--steps", {"sim"}, true},
    {"--dump", {"sim"}, true},                    {"--dump-every", {"sim"}, true},
    {"--frames", {"render"}, true},               {"--every", {"render"}, true},
    {"--out", {"render"}, true},                  {"--video", {"render"}, true},
    {"--from", {"render"}, true},                 {"--hud", {"render"}, false},
    {"--camera", {"render", "play"}, true},       {"--follow", {"render", "play"}, true},
    {"--record", {"play"}, true},
    {"--threads", {"render", "sim", "play"}, true},
    {"--save-state", {"render", "sim", "play"}, true}, {"--load-state", {"render", "sim", "play"}, true},
};

const FlagSpec* FindFlag(const std::string& command, const std::string& flag) {
  for (const FlagSpec& spec : kFlags) {
    if (flag != spec.name) continue;
    for (const char* c : spec.commands) {
      if (command == c) return &spec;
    }
  }
  return nullptr;
}

// A whole number in [min, max], or nothing.
std::optional<std::int64_t> ParseCount(const std::string& text, std::int64_t min, std::int64_t max) {
  std::int64_t value = 0;
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end || value < min || value > max) return std::nullopt;
  return value;
}

bool ParseSize(const std::string& text, int* width, int* height) {
  const auto x = text.find('x');
  if (x == std::string::npos) return false;
  const auto w = ParseCount(text.substr(0, x), 1, kMaxImageSide);
  const auto h = ParseCount(text.substr(x + 1), 1, kMaxImageSide);
  if (!w || !h) return false;
  *width = static_cast<int>(*w);
  *height = static_cast<int>(*h);
  return true;
}

// X,Y,WIDTH: finite numbers within the scene limits, WIDTH > 0.
std::optional<render::Camera> ParseCamera(const std::string& text) {
  double v[3] = {0, 0, 0};
  const char* p = text.data();
  const char* end = text.data() + text.size();
  for (int i = 0; i < 3; ++i) {
    if (i > 0 && (p == end || *p++ != ',')) return std::nullopt;
    if (p != end && *p == '+') ++p;
    auto [next, ec] = std::from_chars(p, end, v[i]);
    if (ec != std::errc() || !std::isfinite(v[i]) || std::abs(v[i]) > kMaxSceneMagnitude) {
      return std::nullopt;
    }
    p = next;
  }
  if (p != end || !(v[2] > 0.0)) return std::nullopt;
  return render::Camera{{v[0], v[1]}, v[2]};
}

// The counts. Steps may be 0 (hash the initial state), so may --from; frames and strides start at 1.
Status ApplyCount(CommandLine& cl, RunOptions& run, const std::string& command, const std::string& flag,
                  const std::string& v) {
  const std::int64_t min = flag == "--steps" || flag == "--from" ? 0 : 1;
  const std::int64_t max = flag == "--frames"    ? 100'000'000
                           : flag == "--threads" ? engine::kMaxThreads
                                                 : 1'000'000'000'000;
  const auto n = ParseCount(v, min, max);
  if (!n) {
    return Usage(command, flag + ": expected a whole number from " + std::to_string(min) + " to " +
                              std::to_string(max) + ", got \"" + v + "\"");
  }
  if (flag == "--steps") cl.sim.steps = *n;
  if (flag == "--dump-every") cl.sim.dump_every = *n;
  if (flag == "--frames") cl.render.frames = *n;
  if (flag == "--every") cl.render.every = *n;
  if (flag == "--from") cl.render.from = *n;
  if (flag == "--threads") run.threads = static_cast<int>(*n);
  return std::nullopt;
}

Status ApplyFlag(CommandLine& cl, RunOptions& run, const std::string& command,
                 const std::string& flag, const std::string& v) {
  ViewOptions& view = command == "play" ? cl.play.view : cl.render.view;
  if (flag == "--script") {
    run.script_path = v;
  } else if (flag == "--save-state" || flag == "--load-state") {
    (flag == "--save-state" ? run.save_state_path : run.load_state_path) = v;
  } else if (flag == "--size") {
    if (!ParseSize(v, &run.width, &run.height)) {
      return Usage(command, "--size: expected WxH with whole numbers from 1 to " +
                                std::to_string(kMaxImageSide) + ", got \"" + v + "\"");
    }
  } else if (flag == "--camera") {
    view.camera = ParseCamera(v);
    if (!view.camera) {
      return Usage(command, "--camera: expected X,Y,WIDTH (metres; WIDTH > 0, each at most 1e9 "
                            "in size), got \"" + v + "\"");
    }
  } else if (flag == "--video") {
    if (!render::VideoFormatOf(v)) {
      return Usage(command, "--video: \"" + v + "\" does not end in .mp4, .webm or .gif");
    }
    cl.render.video_path = v;
  } else if (flag == "--follow") {
    view.follow = v;
  } else if (flag == "--dump" || flag == "--out" || flag == "--record") {
    (flag == "--dump" ? cl.sim.dump_path : flag == "--out" ? cl.render.out_dir : cl.play.record_path) = v;
  } else {
    return ApplyCount(cl, run, command, flag, v);
  }
  return std::nullopt;
}

std::string CommandHelp(CommandKind kind) {
  return kind == CommandKind::kSim ? SimHelp() : kind == CommandKind::kRender ? RenderHelp() : PlayHelp();
}

}  // namespace

Expected<CommandLine> ParseCommandLine(const std::vector<std::string>& args) {
  CommandLine cl;
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    cl.kind = CommandKind::kHelp;
    cl.help_text = kUsage;
    return cl;
  }
  if (args[0] == "--version") {
    cl.kind = CommandKind::kVersion;
    return cl;
  }
  const std::string& command = args[0];
  RunOptions* run = nullptr;
  if (command == "sim") {
    cl.kind = CommandKind::kSim;
    run = &cl.sim.run;
  } else if (command == "render") {
    cl.kind = CommandKind::kRender;
    run = &cl.render.run;
  } else if (command == "play") {
    cl.kind = CommandKind::kPlay;
    run = &cl.play.run;
  } else {
    return Usage("", "unknown command \"" + command + "\" (expected render, sim or play)");
  }

  std::set<std::string> given;
  for (std::size_t i = 1; i < args.size(); ++i) {
    std::string flag = args[i];
    if (flag == "--help" || flag == "-h") {
      cl.help_text = CommandHelp(cl.kind);
      cl.kind = CommandKind::kHelp;
      return cl;
    }
    if (flag.rfind("--", 0) != 0 || flag == "--") {
      if (flag.rfind("-", 0) == 0 && flag.size() > 1) {
        return Usage(command, "unknown option \"" + flag + "\" for ballbox " + command);
      }
      if (run->scene_path) return Usage(command, "more than one scene given: \"" + *run->scene_path + "\" and \"" + flag + "\"");
      run->scene_path = flag;
      continue;
    }
    // Both "--flag value" and "--flag=value".
    std::optional<std::string> value;
    if (const auto eq = flag.find('='); eq != std::string::npos) {
      value = flag.substr(eq + 1);
      flag.erase(eq);
    }
    const FlagSpec* spec = FindFlag(command, flag);
    if (!spec) return Usage(command, "unknown option \"" + flag + "\" for ballbox " + command);
    // The later of two values would win silently; which one the user meant is not ours to guess.
    if (!given.insert(flag).second) return Usage(command, flag + " is given more than once");
    if (!spec->takes_value) {
      if (value) return Usage(command, flag + " takes no value, got \"" + *value + "\"");
      (flag == "--hud" ? cl.render.hud : run->list_misses) = true;
      continue;
    }
    // A following flag is not a value: `--script --steps 5` lacks the script.
    if (!value && i + 1 < args.size() && args[i + 1].rfind("--", 0) != 0) value = args[++i];
    if (!value || value->empty()) return Usage(command, flag + " needs a value");
    if (Status bad = ApplyFlag(cl, *run, command, flag, *value)) return *bad;
  }
  if (cl.kind == CommandKind::kSim && !given.count("--steps")) return Usage(command, "ballbox sim needs --steps N");
  return cl;
}

}  // namespace game

namespace game {
const char* VersionString() { return BALLBOX_VERSION; }
}  // namespace game
