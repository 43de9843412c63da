// Scene particles: the top-level `soft_bodies`, `fluids` and `emitters` lists and the `particles`
// settings (docs/scene-format.md#soft-bodies), read and checked at the edge so that everything a
// scene file can give meets the engine's preconditions (World::CreateSoftBody, AddFluid,
// CreateEmitter) and the particle limits of docs/limits.md.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "engine/particles.h"
#include "engine/world_def.h"
#include "game/scene.h"
#include "game/scene_values.h"

namespace game {

/// How many particles the engine makes of a soft body (a box's lattice, a circle's ring), by
/// the engine's own arithmetic. Valid for a def the loader accepted.
std::size_t SoftBodyParticleCount(const engine::SoftBodyDef& def);

/// How many particles World::AddFluid makes of a block, by the engine's own arithmetic.
std::size_t FluidParticleCount(const engine::FluidDef& def);

}  // namespace game

namespace game::scene_values {

/// The root's `particles` object: `substep` and `iterations` into world->particles.
void ReadParticleSettings(const Json& value, const std::string& path, engine::WorldDef* world);

/// The root's lists. `body_ids` maps each body's id to its index in the scene's bodies. Each throws
/// SceneError naming the key path of the first fault; `particles` counts the soft-body and
/// fluid particles so far, against kMaxParticles.
std::vector<SceneSoftBody> ReadSoftBodies(const Json& list, const std::map<std::string, std::size_t>& body_ids,
                                          std::size_t* particles);
std::vector<SceneFluid> ReadFluids(const Json& list, std::size_t* particles);
std::vector<SceneEmitter> ReadEmitters(const Json& list, const std::map<std::string, std::size_t>& body_ids);

/// The checks that need the whole scene: a scene with soft bodies or fluid steps them in at
/// most kMaxParticleSubsteps substeps a step (`dt` against `particles.substep`).
void CheckParticleSubsteps(const Json& root, const Scene& scene);

}  // namespace game::scene_values
