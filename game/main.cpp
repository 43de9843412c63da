// ballbox: parse the command line, run the command, print its error and pick the exit code.
#include <cstdio>
#include <string>
#include <vector>

#include "game/cli.h"
#include "game/commands.h"

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  game::Expected<game::CommandLine> parsed = game::ParseCommandLine(args);
  game::Status status;
  if (!parsed.HasValue()) {
    status = parsed.Error();
  } else {
    const game::CommandLine& cl = parsed.Value();
    switch (cl.kind) {
      case game::CommandKind::kHelp:
        std::fputs(cl.help_text.c_str(), stdout);
        break;
      case game::CommandKind::kVersion:
        std::printf("ballbox %s\n", game::VersionString());
        break;
      case game::CommandKind::kSim:
        status = game::RunSim(cl.sim);
        break;
      case game::CommandKind::kRender:
        status = game::RunRender(cl.render);
        break;
      case game::CommandKind::kPlay:
        status = game::RunPlay(cl.play);
        break;
    }
  }
  if (status) {
    std::fflush(stdout);
    std::fprintf(stderr, "error: %s\n", status->message.c_str());
    return status->exit_code;
  }
  return 0;
}
