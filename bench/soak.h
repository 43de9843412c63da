// The soak run shared by bench_soak (10⁶ steps) and its short version in the tests: the default
// scene with random clicks from a fixed seed, watched for non-finite numbers, energy and memory.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <optional>
#include <random>
#include <string>

#include "game/commands.h"
#include "game/session.h"
#include "render/camera.h"

#if defined(__SANITIZE_ADDRESS__)
#define BALLBOX_SOAK_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define BALLBOX_SOAK_ASAN 1
#endif
#endif

#ifdef BALLBOX_SOAK_ASAN
extern "C" std::size_t __sanitizer_get_current_allocated_bytes();
#else
#include <malloc.h>
#endif

namespace soak {

/// Bytes the program has allocated and not freed: malloc's own count, or AddressSanitizer's
/// (whose quarantine keeps freed memory resident, so RSS would mislead there).
inline std::size_t HeapBytesInUse() {
#ifdef BALLBOX_SOAK_ASAN
  return __sanitizer_get_current_allocated_bytes();
#else
  const struct mallinfo2 info = mallinfo2();
  return info.uordblks + info.hblkhd;
#endif
}

/// A field of /proc/self/status in KiB ("VmRSS", "VmHWM" for the peak); 0 when unreadable.
inline std::int64_t ProcStatusKiB(const std::string& field) {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind(field + ":", 0) == 0) return std::stoll(line.substr(field.size() + 1));
  }
  return 0;
}

/// Kinetic plus potential energy of the dynamic bodies, J (potential −m g·p: zero at the origin).
inline double MechanicalEnergy(const engine::World& world) {
  const engine::Vec2 g = world.Def().gravity;
  double energy = 0.0;
  for (const engine::BodyId id : world.BodyIds()) {
    const engine::BodyInfo& info = world.Info(id);
    if (info.is_static) continue;
    const engine::BodyState& s = world.State(id);
    energy += 0.5 * info.mass * engine::Dot(s.velocity, s.velocity) - info.mass * engine::Dot(g, s.position);
  }
  return energy;
}

/// The default scene clicked at random: every `click_every` steps a click at a random pixel of
/// the 800x600 image half the time (mostly misses, as a player's clicks often are), else at a
/// random point inside a random ball, which always hits it.
class Soak {
 public:
  explicit Soak(std::uint64_t seed, int click_every = 30)
      : session_(LoadDefault(), {}, kWidth, kHeight), rng_(seed), click_every_(click_every) {
    initial_energy_ = MechanicalEnergy(session_.World());
  }

  /// One step, with a click first when one is due. Returns a description of the first
  /// non-finite number found afterwards (body and step), or nothing.
  std::optional<std::string> Step() {
    if (session_.StepIndex() % click_every_ == 0) Click();
    session_.Step();
    const engine::World& world = session_.World();
    for (const engine::BodyId id : world.BodyIds()) {
      const engine::BodyState& s = world.State(id);
      for (double v : {s.position.x, s.position.y, s.velocity.x, s.velocity.y, s.angle, s.angular_velocity}) {
        if (!std::isfinite(v)) {
          return "body " + session_.SceneDef().bodies[id.index].id + " is not finite after step " +
                 std::to_string(session_.StepIndex());
        }
      }
    }
    return std::nullopt;
  }

  /// The energy now, over the most the scene may hold: its start plus all that clicks put in.
  /// Contacts, friction and the integrator only take energy away, so this stays at or below 0.
  double EnergyExcess() const {
    return MechanicalEnergy(session_.World()) - (initial_energy_ + injected_energy_);
  }

  const game::Session& Session() const { return session_; }
  std::int64_t Clicks() const { return clicks_; }
  std::int64_t Hits() const { return hits_; }
  double InjectedEnergy() const { return injected_energy_; }
  double InitialEnergy() const { return initial_energy_; }

  /// Dynamic bodies whose centre is inside the default scene's box (walls at x = ±9, floor at
  /// 0); clicks can throw balls over the 14 m walls, after which they fall for ever.
  int BodiesInTheBox() const {
    int inside = 0;
    const engine::World& world = session_.World();
    for (const engine::BodyId id : world.BodyIds()) {
      const engine::BodyState& s = world.State(id);
      if (!world.Info(id).is_static && std::abs(s.position.x) < 9.0 && s.position.y > -0.1) ++inside;
    }
    return inside;
  }

 private:
  static constexpr int kWidth = 800;
  static constexpr int kHeight = 600;

  static game::Scene LoadDefault() {
    game::Expected<game::RunInput> input = game::LoadRunInput(game::RunOptions{{}, {}, kWidth, kHeight});
    return input.Value().scene;  // the embedded scene always loads (tests prove it)
  }

  void Click() {
    const engine::World& world = session_.World();
    game::InputEvent event;
    event.step = session_.StepIndex();
    if (std::uniform_int_distribution<int>(0, 1)(rng_) == 0) {
      event.kind = game::EventKind::kClickPixel;
      event.at = {std::uniform_real_distribution<double>(0, kWidth)(rng_),
                  std::uniform_real_distribution<double>(0, kHeight)(rng_)};
    } else {
      std::vector<engine::BodyId> balls;
      for (const engine::BodyId id : world.BodyIds()) {
        const engine::BodyInfo& info = world.Info(id);
        if (!info.is_static && info.shape.type == engine::ShapeType::kCircle) balls.push_back(id);
      }
      const engine::BodyId ball =
          balls[std::uniform_int_distribution<std::size_t>(0, balls.size() - 1)(rng_)];
      // A uniform point in the disc, but never the exact centre (a click there does nothing).
      const double r = world.Info(ball).shape.radius *
                       std::sqrt(std::uniform_real_distribution<double>(1e-6, 1.0)(rng_));
      const double a = std::uniform_real_distribution<double>(0, 2 * 3.14159265358979323846)(rng_);
      event.kind = game::EventKind::kClickWorld;
      event.at = world.State(ball).position + engine::Vec2{r * std::cos(a), r * std::sin(a)};
    }
    const std::uint64_t before_hash = world.StateHash();
    const double before = MechanicalEnergy(world);
    session_.ApplyEvent(event);
    injected_energy_ += MechanicalEnergy(session_.World()) - before;
    ++clicks_;
    if (session_.World().StateHash() != before_hash) ++hits_;
  }

  game::Session session_;
  std::mt19937_64 rng_;
  int click_every_;
  double initial_energy_ = 0.0;
  double injected_energy_ = 0.0;
  std::int64_t clicks_ = 0;
  std::int64_t hits_ = 0;
};

}  // namespace soak
