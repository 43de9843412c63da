// The dumps' rows (dump.h): full double precision (%.17g), time as step·dt.
#include "game/dump.h"

#include <cinttypes>

#include "game/output_file.h"

namespace game {

std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

namespace {

// Time as step·dt rather than a running sum, so it carries no accumulated rounding.
double TimeOf(const Session& session) {
  return static_cast<double>(session.StepIndex()) * session.World().Def().dt;
}

void ParticleRow(std::FILE* out, std::int64_t step, double time, const char* kind, const std::string& source,
                 std::size_t particle, engine::Vec2 x, engine::Vec2 v) {
  std::fprintf(out, "%" PRId64 ",%.17g,%s,%s,%zu,%.17g,%.17g,%.17g,%.17g\n", step, time, kind, source.c_str(),
               particle, x.x, x.y, v.x, v.y);
}

}  // namespace

void DumpBodies(std::FILE* out, const Session& session, const std::vector<std::string>& ids) {
  const engine::World& world = session.World();
  const std::int64_t step = session.StepIndex();
  const double time = TimeOf(session);
  for (const engine::BodyId id : world.BodyIds()) {
    const engine::BodyState& s = world.State(id);
    // x, y: the body frame's origin (a polygon's or compound's scene position, not its centre
    // of mass), as the state hash has it; for circles and boxes the two are the same point.
    const engine::Vec2 origin = world.Origin(id);
    std::fprintf(out, "%" PRId64 ",%.17g,%s,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", step, time,
                 ids[id.index].c_str(), origin.x, origin.y,
                 s.velocity.x, s.velocity.y, s.angle, s.angular_velocity);
  }
}

std::optional<std::string> ParticleDumpPath(const std::string& dump_path) {
  if (WritesInPlace(dump_path)) return std::nullopt;
  const std::string suffix = ".csv";
  const bool csv = dump_path.size() > suffix.size() &&
                   dump_path.compare(dump_path.size() - suffix.size(), suffix.size(), suffix) == 0;
  return (csv ? dump_path.substr(0, dump_path.size() - suffix.size()) : dump_path) + ".particles.csv";
}

void DumpParticles(std::FILE* out, const Session& session) {
  const engine::World& world = session.World();
  const Scene& scene = session.SceneDef();
  const std::int64_t step = session.StepIndex();
  const double time = TimeOf(session);
  // Soft bodies are made in file order into a fresh world, so the live ids come in that order.
  const std::span<const engine::SoftBodyId> soft_ids = world.SoftBodyIds();
  for (std::size_t s = 0; s < soft_ids.size(); ++s) {
    const std::string source = CsvField(scene.soft_bodies[s].id);
    const std::span<const engine::Vec2> x = world.SoftBodyPositions(soft_ids[s]);
    const std::span<const engine::Vec2> v = world.SoftBodyVelocities(soft_ids[s]);
    for (std::size_t i = 0; i < x.size(); ++i) ParticleRow(out, step, time, "soft", source, i, x[i], v[i]);
  }
  // An effect particle's number is its rank among its emitter's live particles, oldest first.
  std::vector<std::size_t> ranks(scene.emitters.size(), 0);
  for (const engine::EffectParticle& p : world.Effects()) {
    const std::size_t e = p.emitter.index;
    ParticleRow(out, step, time, "effect", CsvField(scene.emitters[e].id), ranks[e]++, p.position, p.velocity);
  }
  const std::span<const engine::Vec2> x = world.FluidPositions();
  const std::span<const engine::Vec2> v = world.FluidVelocities();
  std::size_t first = 0;
  for (const SceneFluid& fluid : scene.fluids) {
    const std::string source = CsvField(fluid.id);
    for (std::size_t i = 0; i < fluid.particles && first + i < x.size(); ++i) {
      ParticleRow(out, step, time, "fluid", source, i, x[first + i], v[first + i]);
    }
    first += fluid.particles;
  }
}

}  // namespace game
