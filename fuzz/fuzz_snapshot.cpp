// libFuzzer target: bytes through World::RestoreSnapshot. Whatever it is given, a restore either
// refuses (the world unchanged) or succeeds with a world that steps and snapshots again to
// bytes that restore once more. The seeds (make_corpus.sh) are real snapshots, so mutations reach
// past the checksum only where the fuzzer rewrites it too: the target also tries each input with
// its checksum repaired, which lets it explore the reader's checks behind the checksum.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "engine/world.h"
#include "game/default_scene.h"
#include "game/scene.h"

namespace {

[[noreturn]] void Fail(const char* what) {
  std::fprintf(stderr, "%s\n", what);
  std::abort();
}

const game::Scene& DefaultScene() {
  static const game::Scene scene = game::ParseScene(game::DefaultSceneJson(), "default", "default").Value();
  return scene;
}

// The last 8 bytes are FNV-1a 64 of the rest (snapshot/world_snapshot.cpp).
void RepairChecksum(std::vector<std::uint8_t>* bytes) {
  if (bytes->size() < 8) return;
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  for (std::size_t i = 0; i + 8 < bytes->size(); ++i) hash = (hash ^ (*bytes)[i]) * 0x100000001b3ULL;
  for (int i = 0; i < 8; ++i) (*bytes)[bytes->size() - 8 + i] = static_cast<std::uint8_t>(hash >> (8 * i));
}

void Try(const std::vector<std::uint8_t>& bytes) {
  engine::World world = game::BuildWorld(DefaultScene());
  const std::uint64_t before = world.StateHash();
  if (!world.RestoreSnapshot(bytes)) {
    if (world.StateHash() != before || world.StepCount() != 0) Fail("a refused snapshot changed the world");
    return;
  }
  for (int i = 0; i < 3; ++i) world.Step();
  engine::World again = game::BuildWorld(DefaultScene());
  if (!again.RestoreSnapshot(world.TakeSnapshot())) Fail("a world's own snapshot was refused");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::uint8_t> bytes(data, data + size);
  Try(bytes);
  RepairChecksum(&bytes);
  Try(bytes);
  return 0;
}
