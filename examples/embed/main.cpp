// A program that embeds the installed engine: builds a small world, steps it, and checks what it
// does against expectations worked out independently of the engine. Exit 0 when all hold.
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <span>
#include <vector>

#include "engine/world.h"

namespace {

constexpr double kFloorTop = 0.0;

unsigned long long Hex(std::uint64_t hash) { return hash; }  // for printf's %llx

bool Report(bool ok, const char* what) {
  std::printf("%s %s\n", ok ? "ok  " : "FAIL", what);
  return ok;
}

engine::BodyDef Ball(engine::Vec2 position, double radius) {
  engine::BodyDef def;
  def.shape = {engine::ShapeType::kCircle, radius, {}};
  def.position = position;
  return def;
}

engine::BodyDef Box(engine::Vec2 position, engine::Vec2 half_extents) {
  engine::BodyDef def;
  def.shape = {engine::ShapeType::kBox, 0.0, half_extents};
  def.position = position;
  return def;
}

// A floor, balls and boxes dropped side by side onto it (none above another), and one ball far
// above everything (body 1) that falls freely for the first seconds. `nudge` moves one ball.
engine::World BuildWorld(double nudge = 0.0) {
  engine::World world(engine::WorldDef{});  // the defaults: g = 9.8 m/s², dt = 1/60 s
  engine::BodyDef floor = Box({0.0, kFloorTop - 0.5}, {20.0, 0.5});
  floor.is_static = true;
  world.CreateBody(floor);
  world.CreateBody(Ball({0.0, 30.0}, 0.5));
  world.CreateBody(Ball({-6.0 + nudge, 2.0}, 0.5));
  world.CreateBody(Ball({-3.0, 1.0}, 0.25));
  world.CreateBody(Box({3.0, 1.5}, {0.5, 0.5}));
  world.CreateBody(Box({6.0, 0.8}, {1.0, 0.25}));
  return world;
}

// Semi-implicit Euler (the default integrator) from rest, n steps of h under g:
// v_n = -g·n·h, y_n = y0 - g·h²·n(n+1)/2: the parabola y0 - g·t²/2 lowered by g·t·h/2.
// The substep solver (the default) integrates each step in Def().substeps substeps.
bool CheckFreeFall() {
  engine::World world = BuildWorld();
  const engine::WorldDef& def = world.Def();
  const double g = -def.gravity.y, y0 = world.State({1}).position.y;
  const double h = def.solver == engine::ContactSolver::kSubstep ? def.dt / def.substeps : def.dt;
  const int per_step = def.solver == engine::ContactSolver::kSubstep ? def.substeps : 1;
  double worst = 0.0;
  for (int step = 1; step <= 120; ++step) {  // 2 s: 19.6 m, well above the floor
    world.Step();
    const double n = step * per_step;
    const double expected = y0 - g * h * h * n * (n + 1) / 2.0;
    worst = std::fmax(worst, std::fabs(world.State({1}).position.y - expected) / std::fabs(expected));
  }
  const double t = 120 * def.dt;
  const double below_parabola = (y0 - g * t * t / 2.0) - world.State({1}).position.y;
  std::printf("     free fall: y(%.0f s) = %.12f m, closed form within %.1e (relative); "
              "%.6f m below the parabola, g·t·h/2 = %.6f m\n",
              t, world.State({1}).position.y, worst, below_parabola, g * t * h / 2.0);
  return Report(worst < 1e-12 && std::fabs(below_parabola - g * t * h / 2.0) < 1e-9,
                "a ball in free fall follows semi-implicit Euler's closed form");
}

// After 10 s every dropped body rests on the floor: its centre one radius or half height above
// the floor's top (contacts leave up to linear_slop of overlap), and still.
bool CheckAtRest() {
  engine::World world = BuildWorld();
  for (int step = 0; step < 600; ++step) world.Step();
  bool ok = true;
  for (const engine::BodyId id : world.BodyIds().subspan(2)) {
    const engine::Shape& shape = world.Info(id).shape;
    const bool circle = shape.type == engine::ShapeType::kCircle;
    const double half = circle ? shape.radius : shape.half_extents.y;
    const engine::BodyState& s = world.State(id);
    const double gap = s.position.y - half - kFloorTop;
    const double speed = engine::Length(s.velocity);
    std::printf("     body %u: gap to the floor %+.2e m, speed %.2e m/s\n", id.index, gap, speed);
    ok = ok && std::fabs(gap) <= world.Def().linear_slop && speed < world.Def().sleep_speed;
  }
  return Report(ok, "balls and boxes dropped on the floor rest on it after 10 s");
}

// FNV-1a 64 over the little-endian bytes of x, y, vx, vy, angle, ω of every body, as world.h
// documents it, computed here from State().
std::uint64_t DocumentedHash(const engine::World& world) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  for (const engine::BodyId id : world.BodyIds()) {
    const engine::BodyState& s = world.State(id);
    for (double value : {s.position.x, s.position.y, s.velocity.x, s.velocity.y, s.angle,
                         s.angular_velocity}) {
      const auto bits = std::bit_cast<std::uint64_t>(value);
      for (int byte = 0; byte < 8; ++byte) {
        hash = (hash ^ ((bits >> (8 * byte)) & 0xffu)) * 0x100000001b3ULL;
      }
    }
  }
  return hash;
}

bool CheckStateHash() {
  engine::World world = BuildWorld();
  for (int step = 0; step < 90; ++step) world.Step();
  std::printf("     StateHash %016llx, recomputed %016llx\n", Hex(world.StateHash()),
              Hex(DocumentedHash(world)));
  return Report(world.StateHash() == DocumentedHash(world),
                "StateHash is the documented FNV-1a of the states");
}

// Two worlds built alike give the same bits; a ball moved by 1 µm gives others.
bool CheckDeterminism() {
  engine::World a = BuildWorld(), b = BuildWorld(), nudged = BuildWorld(1e-6);
  for (int step = 0; step < 300; ++step) a.Step(), b.Step(), nudged.Step();
  std::printf("     after 300 steps: %016llx, %016llx; nudged %016llx\n", Hex(a.StateHash()),
              Hex(b.StateHash()), Hex(nudged.StateHash()));
  return Report(a.StateHash() == b.StateHash() && a.StateHash() != nudged.StateHash(),
                "two worlds built alike step to the same bits");
}

// A snapshot taken mid-run and restored gives back the same bits: step on 120 steps, note the
// hash, go back to the snapshot, step the same 120 again. A snapshot cut short is refused.
bool CheckSnapshot() {
  engine::World world = BuildWorld();
  for (int step = 0; step < 60; ++step) world.Step();
  const std::vector<std::uint8_t> saved = world.TakeSnapshot();
  for (int step = 0; step < 120; ++step) world.Step();
  const std::uint64_t first = world.StateHash();
  const bool restored = static_cast<bool>(world.RestoreSnapshot(saved));
  for (int step = 0; step < 120; ++step) world.Step();
  const engine::RestoreResult cut = world.RestoreSnapshot(std::span(saved).first(saved.size() / 2));
  std::printf("     snapshot %zu bytes; after restoring and 120 steps: %016llx, first time %016llx;\n"
              "     half a snapshot: %s\n",
              saved.size(), Hex(world.StateHash()), Hex(first), cut.error.c_str());
  return Report(restored && world.StateHash() == first && !cut && world.StepCount() == 180,
                "a restored snapshot steps on to the same bits; a truncated one is refused");
}

}  // namespace

int main() {
  const std::vector<bool> results = {CheckFreeFall(), CheckAtRest(), CheckStateHash(),
                                     CheckDeterminism(), CheckSnapshot()};
  for (bool ok : results) {
    if (!ok) {
      std::fprintf(stderr, "embed: a check failed\n");
      return 1;
    }
  }
  std::printf("embed: all checks passed\n");
  return 0;
}
