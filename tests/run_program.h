// Running a program from a test: a shell command with its output captured, and file reading.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <algorithm>
#include <iterator>
#include <string>
#include <vector>

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

// A fresh, empty folder for one test: BALLBOX_TEST_TMP/`group`/`name`.
inline std::filesystem::path FreshTestDir(const std::string& group, const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(BALLBOX_TEST_TMP) / group / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// Runs `ballbox <args>` (a shell command line) in `dir`, its output captured beside the folder,
// so the folder holds only what the program wrote.
inline ProgramRun Ballbox(const std::string& args, const std::filesystem::path& dir) {
  return RunShell("'" BALLBOX_EXE "' " + args, dir,
                  dir.parent_path() / (dir.filename().string() + "_captured"));
}

// The names in a folder, sorted.
inline std::vector<std::string> SortedNames(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) names.push_back(entry.path().filename());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace testing
