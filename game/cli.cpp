// Command-line parsing. Every mistake is bad usage (exit 2) with one message naming the flag.
#include "game/cli.h"

#include <charconv>

#include "game/limits.h"

namespace game {

namespace {

constexpr const char* kUsage =
    "ballbox: a 2D ball-and-boxes physics game\n"
    "\n"
    "usage:\n"
    "  ballbox render [SCENE] [--script FILE] [--frames N] [--every K] [--size WxH] [--out DIR]\n"
    "  ballbox sim    [SCENE] [--script FILE] --steps N [--dump FILE.csv] [--dump-every K] [--size WxH]\n"
    "  ballbox play   [SCENE] [--script FILE] [--record FILE] [--size WxH]\n"
    "  ballbox --help | ballbox COMMAND --help | ballbox --version\n"
    "\n"
    "SCENE is a scene file (JSON); without one, the built-in default scene runs with its demo\n"
    "clicks. Exit codes: 0 success, 2 bad usage or input, 1 any other failure.\n";

constexpr const char* kRunFlags =
    "  SCENE            scene file (JSON); default: the built-in scene and its demo script\n"
    "  --script FILE    input script of clicks to replay (step event x y per line)\n"
    "  --size WxH       image size in pixels; pixel clicks map through it (default 800x600)\n";

std::string RenderHelp() {
  return std::string(
             "usage: ballbox render [SCENE] [--script FILE] [--frames N] [--every K] [--size WxH] "
             "[--out DIR]\n\n"
             "Simulates headlessly and writes DIR/frame_00000.png, frame_00001.png, ...; frame k\n"
             "shows the world after k*K steps (frame 0 is the initial state).\n\n") +
         kRunFlags +
         "  --frames N       number of frames to write (default 300)\n"
         "  --every K        simulation steps between frames (default 1)\n"
         "  --out DIR        output folder (default out/<scene name>)\n";
}

std::string SimHelp() {
  return std::string(
             "usage: ballbox sim [SCENE] [--script FILE] --steps N [--dump FILE.csv] "
             "[--dump-every K] [--size WxH]\n\n"
             "Simulates N steps with no rendering and prints \"state-hash: <16 hex digits>\" of the\n"
             "final state as its last line.\n\n") +
         kRunFlags +
         "  --steps N        steps to simulate (required)\n"
         "  --dump FILE.csv  write step,time,id,x,y,vx,vy,angle,omega per body per dumped step\n"
         "  --dump-every K   dump every K-th step, step 0 included (default 1)\n";
}

std::string PlayHelp() {
  return std::string(
             "usage: ballbox play [SCENE] [--script FILE] [--record FILE] [--size WxH]\n\n"
             "Opens a window and runs the scene in real time; a left click pushes a ball away\n"
             "from the click point.\n\n") +
         kRunFlags + "  --record FILE    write every applied event as an input script\n";
}

Failure Usage(const std::string& command, const std::string& message) {
  return BadInput(message + " (see: ballbox " + (command.empty() ? "" : command + " ") + "--help)");
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

  bool steps_given = false;
  for (std::size_t i = 1; i < args.size(); ++i) {
    std::string flag = args[i];
    if (flag == "--help" || flag == "-h") {
      cl.help_text = cl.kind == CommandKind::kSim      ? SimHelp()
                     : cl.kind == CommandKind::kRender ? RenderHelp()
                                                       : PlayHelp();
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
    // A following flag is not a value: `--script --steps 5` lacks the script.
    auto take_value = [&]() -> std::optional<std::string> {
      if (value) return value;
      if (i + 1 < args.size() && args[i + 1].rfind("--", 0) != 0) return args[++i];
      return std::nullopt;
    };
    auto known = [&](std::initializer_list<const char*> for_commands) {
      for (const char* c : for_commands) {
        if (command == c) return true;
      }
      return false;
    };
    const bool takes_value =
        (flag == "--script" || flag == "--size") ||
        (known({"sim"}) && (flag == "--steps" || flag == "--dump" || flag == "--dump-every")) ||
        (known({"render"}) && (flag == "--frames" || flag == "--every" || flag == "--out")) ||
        (known({"play"}) && flag == "--record");
    if (!takes_value) return Usage(command, "unknown option \"" + flag + "\" for ballbox " + command);
    const std::optional<std::string> v = take_value();
    if (!v || v->empty()) return Usage(command, flag + " needs a value");

    if (flag == "--script") {
      run->script_path = *v;
    } else if (flag == "--size") {
      if (!ParseSize(*v, &run->width, &run->height)) {
        return Usage(command, "--size: expected WxH with whole numbers from 1 to " +
                                  std::to_string(kMaxImageSide) + ", got \"" + *v + "\"");
      }
    } else if (flag == "--dump" || flag == "--out" || flag == "--record") {
      (flag == "--dump" ? cl.sim.dump_path : flag == "--out" ? cl.render.out_dir : cl.play.record_path) = *v;
    } else {
      // The counts. Steps may be 0 (hash the initial state); frames and strides start at 1.
      const std::int64_t min = flag == "--steps" ? 0 : 1;
      const std::int64_t max = flag == "--frames" ? 100'000'000 : 1'000'000'000'000;
      const auto n = ParseCount(*v, min, max);
      if (!n) {
        return Usage(command, flag + ": expected a whole number from " + std::to_string(min) +
                                  " to " + std::to_string(max) + ", got \"" + *v + "\"");
      }
      if (flag == "--steps") cl.sim.steps = *n, steps_given = true;
      if (flag == "--dump-every") cl.sim.dump_every = *n;
      if (flag == "--frames") cl.render.frames = *n;
      if (flag == "--every") cl.render.every = *n;
    }
  }
  if (cl.kind == CommandKind::kSim && !steps_given) return Usage(command, "ballbox sim needs --steps N");
  return cl;
}

}  // namespace game

namespace game {
const char* VersionString() { return BALLBOX_VERSION; }
}  // namespace game
