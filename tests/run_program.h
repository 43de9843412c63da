// Running a program from a test: a shell command with its output captured, and file reading.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace testing {

inline std::string ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

struct ProgramRun {
  int exit_code = -1;  // 128 + the signal number when a signal ended it
  std::string out;
  std::string err;
};

// Runs `command` with sh in `cwd`, stdin empty, stdout and stderr captured to `capture_stem`.stdout
// and .stderr (outside `cwd`, so a test of an output folder sees only what the program wrote) and
// removed once read.
inline ProgramRun RunShell(const std::string& command, const std::filesystem::path& cwd,
                           const std::filesystem::path& capture_stem) {
  const std::string out = capture_stem.string() + ".stdout", err = capture_stem.string() + ".stderr";
  const std::string line = "cd '" + cwd.string() + "' && { " + command + " ; } >'" + out + "' 2>'" +
                           err + "' </dev/null";
  const int status = std::system(line.c_str());
  ProgramRun run;
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  run.out = ReadFile(out);
  run.err = ReadFile(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return run;
}

}  // namespace testing
