// `ballbox sim`: simulate with no rendering, optionally dump CSV, print the final state hash.
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "game/commands.h"
#include "game/output_file.h"
#include "game/session.h"

namespace game {

namespace {

// An id as a CSV field: quoted (RFC 4180) when it holds a comma, a quote or a line break.
std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

void DumpStep(std::FILE* out, const Session& session, const std::vector<std::string>& ids) {
  const engine::World& world = session.World();
  const std::int64_t step = session.StepIndex();
  // Time as step·dt rather than a running sum, so it carries no accumulated rounding.
  const double time = static_cast<double>(step) * world.Def().dt;
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

}  // namespace

Status RunSim(const SimOptions& options) {
  Expected<RunInput> input = LoadRunInput(options.run);
  if (!input.HasValue()) return input.Error();
  Session session(input.Value().scene, std::move(input.Value().events), options.run.width,
                  options.run.height);
  if (options.run.load_state_path) {
    if (Status refused = session.LoadState(*options.run.load_state_path)) return refused;
  }

  std::optional<AtomicOutputFile> dump;
  std::vector<std::string> ids;
  for (const SceneBody& body : session.SceneDef().bodies) ids.push_back(CsvField(body.id));
  if (options.dump_path) {
    Expected<AtomicOutputFile> file = AtomicOutputFile::Open(*options.dump_path);
    if (!file.HasValue()) return file.Error();
    dump.emplace(std::move(file.Value()));
    std::fputs("step,time,id,x,y,vx,vy,angle,omega\n", dump->Stream());
    DumpStep(dump->Stream(), session, ids);
  }

  const auto start = std::chrono::steady_clock::now();
  for (std::int64_t step = 1; step <= options.steps; ++step) {
    session.Step();
    if (Status fault = session.Fault()) return fault;  // the dump's temporary file goes with it
    if (dump && step % options.dump_every == 0) DumpStep(dump->Stream(), session, ids);
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  if (dump) {
    if (Status failed = dump->Commit()) return failed;
  }
  if (options.run.save_state_path) {
    if (Status failed = session.SaveState(*options.run.save_state_path)) return failed;
  }
  std::printf("sim: %s, %zu bodies, %" PRId64 " steps in %.3f s\n", session.SceneDef().name.c_str(),
              session.World().BodyCount(), options.steps, seconds);
  PrintEventSummary(session.SceneDef(), session.Events(), session.EventsLeft(), options.run.list_misses);
  std::printf("state-hash: %016" PRIx64 "\n", session.World().StateHash());
  return std::nullopt;
}

}  // namespace game
