// Saved states: "BBXSTATE", the scene's fingerprint (8 bytes, little-endian), then the engine's
// snapshot (docs/embedding.md describes its format).
#include "game/saved_state.h"

#include <bit>
#include <cstdint>
#include <cstring>
#include <vector>

#include "game/output_file.h"
#include "game/text_file.h"

namespace game {

namespace {

constexpr char kMagic[8] = {'B', 'B', 'X', 'S', 'T', 'A', 'T', 'E'};

// FNV-1a 64 over the snapshot of the scene's initial world and its click strength: two scene
// files that build the same world share it, whatever their spacing or key order.
std::uint64_t SceneFingerprint(const Scene& scene) {
  std::vector<std::uint8_t> bytes = BuildWorld(scene).TakeSnapshot();
  const auto impulse = std::bit_cast<std::uint64_t>(scene.click_max_impulse);
  for (int i = 0; i < 8; ++i) bytes.push_back(static_cast<std::uint8_t>(impulse >> (8 * i)));
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  for (const std::uint8_t b : bytes) hash = (hash ^ b) * 0x100000001b3ULL;
  return hash;
}

}  // namespace

Status SaveState(const std::string& path, const Scene& scene, const engine::World& world) {
  Expected<AtomicOutputFile> file = AtomicOutputFile::Open(path);
  if (!file.HasValue()) return file.Error();
  const std::uint64_t fingerprint = SceneFingerprint(scene);
  std::uint8_t header[16];
  std::memcpy(header, kMagic, 8);
  for (int i = 0; i < 8; ++i) header[8 + i] = static_cast<std::uint8_t>(fingerprint >> (8 * i));
  const std::vector<std::uint8_t> snapshot = world.TakeSnapshot();
  std::FILE* out = file.Value().Stream();
  if (std::fwrite(header, 1, sizeof header, out) != sizeof header ||
      std::fwrite(snapshot.data(), 1, snapshot.size(), out) != snapshot.size()) {
    return RuntimeFailure(path + ": cannot write the saved state");
  }
  return file.Value().Commit();
}

Status LoadState(const std::string& path, const Scene& scene, engine::World* world) {
  Expected<std::string> text = ReadTextFile(path);
  if (!text.HasValue()) return text.Error();
  const std::string& bytes = text.Value();
  if (bytes.size() < 16 || std::memcmp(bytes.data(), kMagic, 8) != 0) {
    return BadInput(path + ": not a ballbox saved state (write one with --save-state)");
  }
  std::uint64_t fingerprint = 0;
  for (int i = 0; i < 8; ++i) fingerprint |= static_cast<std::uint64_t>(static_cast<std::uint8_t>(bytes[8 + i])) << (8 * i);
  if (fingerprint != SceneFingerprint(scene)) {
    return BadInput(path + ": saved from another scene (a state loads only into the scene it was saved from)");
  }
  const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data());
  const engine::RestoreResult restored = world->RestoreSnapshot(std::span(data + 16, bytes.size() - 16));
  if (!restored) return BadInput(path + ": " + restored.error);
  return std::nullopt;
}

}  // namespace game
