// `ballbox sim --dump`: the bodies' CSV (the contract's), and beside it, for a scene with soft
// bodies, fluid or emitters, the particles' CSV (docs/scene-format.md#the-particle-dump).
#pragma once

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "game/session.h"

namespace game {

/// An id as a CSV field: quoted (RFC 4180) when it holds a comma, a quote or a line break.
std::string CsvField(const std::string& text);

inline constexpr const char* kBodyDumpHeader = "step,time,id,x,y,vx,vy,angle,omega\n";
inline constexpr const char* kParticleDumpHeader = "step,time,kind,source,particle,x,y,vx,vy\n";

/// One row per body at the session's current step, bodies in scene order; `ids` are CsvFields.
void DumpBodies(std::FILE* out, const Session& session, const std::vector<std::string>& ids);

/// Where the particles' dump goes beside the bodies' `dump_path`: "x.csv" -> "x.particles.csv",
/// any other name + ".particles.csv"; nothing when `dump_path` is a device or pipe
/// (/dev/stdout), which has no "beside".
std::optional<std::string> ParticleDumpPath(const std::string& dump_path);

/// One row per particle at the session's current step, in the state hash's order: soft bodies
/// in scene order, effect particles oldest first, then the fluid block by block.
void DumpParticles(std::FILE* out, const Session& session);

}  // namespace game
