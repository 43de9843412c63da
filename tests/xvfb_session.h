// `ballbox play` under Xvfb for the window tests: whether they can run here, one Xvfb session
// at a time, and the shell lines that start play paused at a step and wait for it to end.
#pragma once

#include <catch2/catch.hpp>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "render/window.h"
#include "run_program.h"

namespace testing {

inline bool HaveProgram(const std::string& name) {
  return std::system(("command -v " + name + " >/dev/null 2>&1").c_str()) == 0;
}

/// Whether window tests can run here; if not, says why where the test output shows it.
inline bool WindowTestsCanRun() {
  if (!render::WindowSupportBuilt()) {
    WARN("SKIPPED: this ballbox is built without GLFW, so play opens no window");
    return false;
  }
  for (const char* program : {"xvfb-run", "xauth", "xdotool", "flock", "timeout"}) {
    if (!HaveProgram(program)) {
      WARN("SKIPPED: " << program << " is missing (make deps installs xvfb, xauth and xdotool)");
      return false;
    }
  }
  return true;
}

/// Runs `script` (sh) inside a fresh Xvfb, in `cwd`, its output captured beside the folder. One
/// at a time (a lock file): two xvfb-run -a started together can pick the same display. A
/// server that fails to start is retried.
inline ProgramRun UnderXvfb(const std::string& script, const std::filesystem::path& cwd) {
  std::ofstream(cwd / "session.sh") << script;
  const std::string lock = (std::filesystem::path(BALLBOX_TEST_TMP) / "xvfb.lock").string();
  ProgramRun run;
  for (int attempt = 0; attempt < 3; ++attempt) {
    run = RunShell("flock '" + lock + "' xvfb-run -a -s '-screen 0 1024x768x24' sh session.sh", cwd, cwd);
    if (run.err.find("Xvfb failed to start") == std::string::npos) break;
  }
  return run;
}

/// The shell lines that start play in the background (with a time limit, so a lost key cannot
/// hang the tests), wait until its title says it is paused at `step`, and leave the window id
/// in $wid.
inline std::string StartPausedPlay(const std::string& env, const std::string& args, std::int64_t step) {
  // The closing parenthesis keeps "step 9" from matching "step 90" (xdotool takes a regex).
  const std::string paused = "paused at step " + std::to_string(step) + "\\)";
  return "set -u\n" + env + " timeout 120 '" BALLBOX_EXE "' play " + args +
         " >play.out 2>play.err &\n"
         "pid=$!\n"
         "wid=$(timeout 60 xdotool search --sync --name '" + paused + "' | head -n 1)\n"
         "if [ -z \"$wid\" ]; then echo 'no window paused at step " + std::to_string(step) +
         "' >&2; kill $pid; wait $pid; exit 3; fi\n"
         "timeout 30 xdotool windowfocus --sync \"$wid\"\n";
}

/// The shell lines that wait for play to end and leave its exit code in play.rc.
inline std::string EndPlay() { return "wait $pid\necho $? >play.rc\n"; }

}  // namespace testing
