// `ballbox sim`: simulate with no rendering, optionally dump CSV, print the final state hash.
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "game/commands.h"
#include "game/dump.h"
#include "game/output_file.h"
#include "game/session.h"

namespace game {

namespace {

// The dumps a run writes: the bodies', and beside it the particles' when the scene has any.
struct Dumps {
  std::optional<AtomicOutputFile> bodies;
  std::optional<AtomicOutputFile> particles;
  std::vector<std::string> ids;  ///< the bodies' ids as CSV fields

  void Write(const Session& session) {
    if (bodies) DumpBodies(bodies->Stream(), session, ids);
    if (particles) DumpParticles(particles->Stream(), session);
  }
  Status Commit() {
    if (bodies) {
      if (Status failed = bodies->Commit()) return failed;
    }
    if (particles) return particles->Commit();
    return std::nullopt;
  }
};

Status OpenDumps(const SimOptions& options, const Session& session, Dumps* dumps) {
  if (!options.dump_path) return std::nullopt;
  for (const SceneBody& body : session.SceneDef().bodies) dumps->ids.push_back(CsvField(body.id));
  Expected<AtomicOutputFile> file = AtomicOutputFile::Open(*options.dump_path);
  if (!file.HasValue()) return file.Error();
  dumps->bodies.emplace(std::move(file.Value()));
  std::fputs(kBodyDumpHeader, dumps->bodies->Stream());
  if (!session.SceneDef().HasParticles()) return std::nullopt;
  const std::optional<std::string> path = ParticleDumpPath(*options.dump_path);
  if (!path) {
    std::fprintf(stderr, "sim: %s is a device or pipe: the particles' dump (FILE.particles.csv beside a file) is "
                 "not written\n", options.dump_path->c_str());
    return std::nullopt;
  }
  Expected<AtomicOutputFile> particles = AtomicOutputFile::Open(*path);
  if (!particles.HasValue()) return particles.Error();
  dumps->particles.emplace(std::move(particles.Value()));
  std::fputs(kParticleDumpHeader, dumps->particles->Stream());
  return std::nullopt;
}

// ", 3 soft bodies, 1200 fluid particles" for a scene that has them; nothing for the others.
std::string ParticleCounts(const Session& session) {
  const engine::World& world = session.World();
  std::string text;
  if (const std::size_t soft = world.SoftBodyIds().size()) text += ", " + std::to_string(soft) + (soft == 1 ? " soft body" : " soft bodies");
  if (const std::size_t fluid = world.FluidPositions().size()) text += ", " + std::to_string(fluid) + " fluid particles";
  if (const std::size_t emitters = world.EmitterIds().size()) text += ", " + std::to_string(emitters) + (emitters == 1 ? " emitter" : " emitters");
  return text;
}

}  // namespace

Status RunSim(const SimOptions& options) {
  Expected<RunInput> input = LoadRunInput(options.run);
  if (!input.HasValue()) return input.Error();
  Session session(input.Value().scene, std::move(input.Value().events), options.run.width,
                  options.run.height);
  if (options.run.load_state_path) {
    if (Status refused = session.LoadState(*options.run.load_state_path)) return refused;
  }

  Dumps dumps;
  if (Status failed = OpenDumps(options, session, &dumps)) return failed;
  dumps.Write(session);

  const auto start = std::chrono::steady_clock::now();
  for (std::int64_t step = 1; step <= options.steps; ++step) {
    session.Step();
    if (Status fault = session.Fault()) return fault;  // the dump's temporary file goes with it
    if (step % options.dump_every == 0) dumps.Write(session);
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  if (Status failed = dumps.Commit()) return failed;
  if (options.run.save_state_path) {
    if (Status failed = session.SaveState(*options.run.save_state_path)) return failed;
  }
  std::printf("sim: %s, %zu bodies%s, %" PRId64 " steps in %.3f s\n", session.SceneDef().name.c_str(),
              session.World().BodyCount(), ParticleCounts(session).c_str(), options.steps, seconds);
  PrintEventSummary(session.SceneDef(), session.Events(), session.EventsLeft(), options.run.list_misses);
  std::printf("state-hash: %016" PRIx64 "\n", session.World().StateHash());
  return std::nullopt;
}

}  // namespace game
