// --save-state and --load-state: a run split in two at a saved state ends where the whole run
// ends, script events before the saved step are skipped, and a state from elsewhere is refused.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "run_program.h"

using testing::Ballbox;
using testing::FreshTestDir;
using testing::ProgramRun;
using testing::ReadFile;

namespace {

std::string LastLine(const std::string& out) {
  const std::size_t end = out.find_last_not_of('\n');
  const std::size_t start = out.rfind('\n', end);
  return out.substr(start == std::string::npos ? 0 : start + 1, end - (start == std::string::npos ? 0 : start + 1) + 1);
}

const std::string kAssets = BALLBOX_ASSETS;

}  // namespace

TEST_CASE("saved state: sim N then sim M from the saved state ends in the hash of sim N+M",
          "[saved_state]") {
  const auto dir = FreshTestDir("saved_state", "split");
  // The default scene runs its demo script: clicks both before and after the split.
  for (const std::string& scene : {std::string(""), kAssets + "/scenes/rotating_box_drop.json",
                                  kAssets + "/scenes/ball_pour.json"}) {
    INFO("scene " << (scene.empty() ? "default" : scene));
    const ProgramRun whole = Ballbox("sim " + scene + " --steps 150", dir);
    const ProgramRun first = Ballbox("sim " + scene + " --steps 25 --save-state s.state", dir);
    const ProgramRun second = Ballbox("sim " + scene + " --load-state s.state --steps 125", dir);
    REQUIRE(whole.exit_code == 0);
    REQUIRE(first.exit_code == 0);
    REQUIRE(second.exit_code == 0);
    CHECK(LastLine(second.out) == LastLine(whole.out));
    CHECK(LastLine(first.out) != LastLine(whole.out));  // the split is a real one
  }
}

TEST_CASE("saved state: one from another scene, or cut short, is bad input and writes nothing",
          "[saved_state]") {
  const auto dir = FreshTestDir("saved_state", "refused");
  REQUIRE(Ballbox("sim --steps 10 --save-state s.state", dir).exit_code == 0);
  const ProgramRun other =
      Ballbox("sim " + kAssets + "/scenes/box_pile.json --load-state s.state --steps 5 --save-state t.state", dir);
  CHECK(other.exit_code == 2);
  CHECK(other.err.rfind("error: s.state: saved from another scene", 0) == 0);
  CHECK(!std::filesystem::exists(dir / "t.state"));

  const std::string bytes = ReadFile(dir / "s.state");
  std::filesystem::resize_file(dir / "s.state", bytes.size() / 2);
  const ProgramRun cut = Ballbox("sim --load-state s.state --steps 5", dir);
  CHECK(cut.exit_code == 2);
  CHECK(cut.err.find("corrupt or truncated") != std::string::npos);

  const ProgramRun missing = Ballbox("sim --load-state nowhere.state --steps 5", dir);
  CHECK(missing.exit_code == 2);
  CHECK(missing.err.find("nowhere.state") != std::string::npos);
}
