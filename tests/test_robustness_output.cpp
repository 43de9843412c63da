// Output safety: a full or read-only output folder exits 1 with one message, keeps the frames
// already written, whole, and never leaves a truncated PNG or a temporary file; devices and pipes
// named as outputs are written in place, never replaced.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <stb/stb_image.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>

#include "game/frame_writer.h"
#include "game/output_file.h"

namespace fs = std::filesystem;

namespace {

fs::path FreshDir(const std::string& name) {
  const fs::path dir = fs::path(BALLBOX_TEST_TMP) / "robustness_output" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

int ExitCode(int status) { return WIFEXITED(status) ? WEXITSTATUS(status) : -1; }

// Runs a shell script, as `sh -c`, in a private mount namespace: mounts made there vanish with
// it and are never seen by the rest of the machine.
int RunUnshared(const std::string& script) {
  const std::string command = "unshare -m sh -c '" + script + "'";
  return ExitCode(std::system(command.c_str()));
}

// Whether this machine lets the tests mount a tmpfs (root, with unshare): a real full disk.
bool CanMountTmpfs(const fs::path& scratch) {
  fs::create_directories(scratch / "probe");
  return RunUnshared("mount -t tmpfs -o size=64k tmpfs " + (scratch / "probe").string() +
                     " 2>/dev/null") == 0;
}

const char* kBallbox = BALLBOX_EXE;

// Every name in `dir` is a frame this program writes, and the file is exactly the frame of the
// same name in `reference` (a complete run): so nothing truncated and no temporary file.
int CheckKeptFramesAreWhole(const fs::path& dir, const fs::path& reference) {
  int kept = 0;
  const std::regex frame_name("frame_[0-9]{5}\\.png");
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename();
    INFO(name);
    CHECK(std::regex_match(name, frame_name));
    REQUIRE(fs::exists(reference / name));
    CHECK(ReadFile(entry.path()) == ReadFile(reference / name));
    int w = 0, h = 0, channels = 0;
    CHECK(stbi_info(entry.path().c_str(), &w, &h, &channels) == 1);
    ++kept;
  }
  return kept;
}

}  // namespace

TEST_CASE("output safety: a full disk exits 1, keeps whole frames, leaves no partial file",
          "[robustness][render][cli]") {
  const fs::path dir = FreshDir("full");
  if (!CanMountTmpfs(dir)) {
    WARN("skipped: cannot mount a tmpfs here (needs root and unshare); the /dev/full test below "
         "still covers a write that fails with ENOSPC");
    return;
  }
  const std::string flags = " render --frames 60 --size 160x120 --out ";
  REQUIRE(ExitCode(std::system(("cd '" + dir.string() + "' && '" + kBallbox + "'" + flags +
                                "reference >/dev/null 2>&1").c_str())) == 0);
  // 64 KiB holds 16 of these frames (each takes one 4 KiB page), not 60. The run happens in the
  // namespace; what it left is copied out before the tmpfs vanishes.
  fs::create_directories(dir / "mnt");
  fs::create_directories(dir / "kept");
  const std::string script = "mount -t tmpfs -o size=64k tmpfs " + dir.string() + "/mnt && cd " +
                             dir.string() + "/mnt && " + kBallbox + flags + "frames >" +
                             dir.string() + "/out.txt 2>" + dir.string() + "/err.txt; echo $? >" +
                             dir.string() + "/rc.txt; cp -a frames/. " + dir.string() + "/kept/";
  REQUIRE(RunUnshared(script) == 0);

  CHECK(ReadFile(dir / "rc.txt") == "1\n");
  const std::string err = ReadFile(dir / "err.txt");
  INFO("stderr: " << err);
  CHECK(std::regex_match(
      err, std::regex("error: frames/frame_[0-9]{5}\\.png: cannot write: No space left on device\n")));
  CHECK(ReadFile(dir / "out.txt").empty());  // no summary line for a failed run
  const int kept = CheckKeptFramesAreWhole(dir / "kept", dir / "reference");
  CHECK(kept >= 1);
  CHECK(kept < 60);
  // The frames are written in order, so the run stops at one place: what is kept is the frames
  // before it, with no gap (written as each was encoded, a run under load once kept 1-16 and
  // lost frame 0 to the full disk).
  for (int i = 0; i < kept; ++i) CHECK(fs::exists(dir / "kept" / game::FrameFileName(i)));
}

TEST_CASE("output safety: a read-only output folder exits 1 and writes nothing",
          "[robustness][render][cli]") {
  const fs::path dir = FreshDir("read_only");
  fs::create_directories(dir / "frames");
  const std::string run = std::string(kBallbox) + " render --frames 3 --size 64x48 --out " +
                          dir.string() + "/frames >/dev/null 2>" + dir.string() + "/err.txt";
  int rc = -1;
  if (::geteuid() != 0) {
    // Permissions stop everyone but root.
    fs::permissions(dir / "frames", fs::perms::owner_read | fs::perms::owner_exec);
    rc = ExitCode(std::system(run.c_str()));
    fs::permissions(dir / "frames", fs::perms::owner_all);
  } else if (CanMountTmpfs(dir)) {
    // Root writes through permissions, so the folder becomes a read-only mount instead.
    rc = RunUnshared("mount -t tmpfs -o ro,size=64k tmpfs " + dir.string() + "/frames && " + run +
                     "; echo $? >" + dir.string() + "/rc.txt");
    REQUIRE(rc == 0);
    rc = std::stoi(ReadFile(dir / "rc.txt"));
  } else {
    WARN("skipped: running as root where no read-only tmpfs can be mounted");
    return;
  }
  CHECK(rc == 1);
  const std::string err = ReadFile(dir / "err.txt");
  INFO("stderr: " << err);
  CHECK(std::regex_match(
      err, std::regex("error: .*/frames/frame_0000[0-9]\\.png: cannot write: "
                      "(Read-only file system|Permission denied)\n")));
  CHECK(fs::is_empty(dir / "frames"));
}

TEST_CASE("output safety: a CSV dump to a full device (/dev/full) exits 1, the device stays",
          "[robustness][sim][cli]") {
  // /dev/full fails every write with ENOSPC: the same failure as a full disk, without a mount.
  const fs::path dir = FreshDir("dev_full");
  const std::string command = std::string("'") + kBallbox + "' sim --steps 50 --dump /dev/full >'" +
                              dir.string() + "/out.txt' 2>'" + dir.string() + "/err.txt'";
  CHECK(ExitCode(std::system(command.c_str())) == 1);
  CHECK(ReadFile(dir / "err.txt") == "error: /dev/full: cannot write: No space left on device\n");
  CHECK(ReadFile(dir / "out.txt").empty());
  struct stat info;
  REQUIRE(::stat("/dev/full", &info) == 0);
  CHECK(S_ISCHR(info.st_mode));
}

TEST_CASE("output safety: a dump into a pipe is written in place, not renamed over it",
          "[robustness][sim][cli]") {
  // Before the fix, the CSV went to a temporary file renamed over the named pipe: the pipe was
  // gone, and as root the same would replace /dev/stdout or /dev/null.
  const fs::path dir = FreshDir("fifo");
  const fs::path fifo = dir / "dump.fifo";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  // Opened for reading first, without blocking, so the program's open for writing succeeds; the
  // dump is small enough for the pipe's buffer, so it is read after the program exits.
  const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
  REQUIRE(reader >= 0);
  const std::string sim = std::string("'") + kBallbox + "' sim --steps 3 --dump ";
  const int rc = ExitCode(std::system((sim + "'" + fifo.string() + "' >/dev/null 2>&1").c_str()));
  std::string piped;
  char buffer[4096];
  for (ssize_t n; (n = ::read(reader, buffer, sizeof buffer)) > 0;) piped.append(buffer, n);
  ::close(reader);
  CHECK(rc == 0);
  struct stat info;
  REQUIRE(::stat(fifo.c_str(), &info) == 0);
  CHECK(S_ISFIFO(info.st_mode));

  REQUIRE(ExitCode(std::system((sim + "'" + (dir / "dump.csv").string() + "' >/dev/null").c_str())) == 0);
  CHECK(piped == ReadFile(dir / "dump.csv"));
  CHECK(piped.rfind("step,time,id,x,y,vx,vy,angle,omega\n", 0) == 0);
}

TEST_CASE("output safety: /dev and /proc paths are written in place even when they lead to a file",
          "[robustness][sim][cli]") {
  // With stdout redirected to a file, /dev/stdout leads to a regular file: before the fix a dump
  // there went to /dev/stdout.tmp-<pid>, renamed over the /dev/stdout link itself (as root).
  CHECK(game::WritesInPlace("/dev/stdout"));
  CHECK(game::WritesInPlace("/dev/fd/1"));
  CHECK(game::WritesInPlace("/proc/self/fd/1"));
  CHECK(game::WritesInPlace("/dev/../dev/null"));
  const fs::path dir = FreshDir("in_place");
  CHECK_FALSE(game::WritesInPlace((dir / "d.csv").string()));
  std::ofstream(dir / "e.csv") << "old\n";
  CHECK_FALSE(game::WritesInPlace((dir / "e.csv").string()));
  REQUIRE(::mkfifo((dir / "f.fifo").c_str(), 0600) == 0);
  CHECK(game::WritesInPlace((dir / "f.fifo").string()));
}

TEST_CASE("output safety: --out naming an existing file exits 2 and leaves the file alone",
          "[robustness][render][cli]") {
  const fs::path dir = FreshDir("out_is_file");
  std::ofstream(dir / "notes.txt") << "mine\n";
  const std::string command = "cd '" + dir.string() + "' && '" + kBallbox +
                              "' render --frames 2 --size 64x48 --out notes.txt >/dev/null 2>err.txt";
  CHECK(ExitCode(std::system(command.c_str())) == 2);
  CHECK(ReadFile(dir / "err.txt") ==
        "error: notes.txt: is a file, not a folder (--out names the folder for the frames)\n");
  CHECK(ReadFile(dir / "notes.txt") == "mine\n");
  fs::remove(dir / "err.txt");
  CHECK(fs::directory_iterator(dir) != fs::directory_iterator());
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);
}
