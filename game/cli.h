// The command line (contract: ballbox render | sim | play, --help, --version), parsed into options.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "game/status.h"
#include "render/camera.h"

namespace game {

/// What every simulating command shares.
struct RunOptions {
  std::optional<std::string> scene_path;   ///< none: the embedded default scene
  std::optional<std::string> script_path;  ///< none: no events (the default scene's demo script)
  int width = 800;
  int height = 600;
  bool list_misses = false;  ///< --misses: a line for each click that hit no ball
  std::optional<std::string> save_state_path = std::nullopt;  ///< --save-state FILE: the state at the end
  std::optional<std::string> load_state_path = std::nullopt;  ///< --load-state FILE: the state to start from
  int threads = 0;  ///< --threads N: the physics step's threads; 0: one per core
};

/// What the picture shows, apart from the scene's camera. Pixel clicks in scripts keep mapping
/// through the scene's camera, so these never change the simulation.
struct ViewOptions {
  std::optional<render::Camera> camera;  ///< --camera X,Y,WIDTH (WIDTH as at 800x600)
  std::optional<std::string> follow;     ///< --follow ID: the camera tracks this body
};

struct SimOptions {
  RunOptions run;
  std::int64_t steps = 0;
  std::optional<std::string> dump_path;
  std::int64_t dump_every = 1;
};

struct RenderOptions {
  RunOptions run;
  std::int64_t frames = 300;
  std::int64_t every = 1;
  std::optional<std::string> out_dir;  ///< none: out/<scene name> (none at all with --video)
  std::optional<std::string> video_path;  ///< --video FILE: .mp4, .webm or .gif
  ViewOptions view;
  std::int64_t from = 0;  ///< --from STEP: the first frame shows this step
  bool hud = false;       ///< --hud: step, time and state hash drawn in a corner
};

struct PlayOptions {
  RunOptions run;
  std::optional<std::string> record_path;
  ViewOptions view;
};

enum class CommandKind { kHelp, kVersion, kSim, kRender, kPlay };

struct CommandLine {
  CommandKind kind = CommandKind::kHelp;
  std::string help_text;  ///< for kHelp: the usage to print
  SimOptions sim;
  RenderOptions render;
  PlayOptions play;
};

/// Parses argv (without the program name). Bad usage is a Failure with exit code 2.
Expected<CommandLine> ParseCommandLine(const std::vector<std::string>& args);

}  // namespace game

namespace game {
/// The program's version, e.g. "0.1.0".
const char* VersionString();
}  // namespace game
