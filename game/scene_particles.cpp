// Scene particles (scene_particles.h): soft bodies, fluid blocks and emitters, each read and
// checked in file order. Cross-field checks name the key the file gave (a spacing too large for
// the radius is the spacing's fault when the file sets it, else the radius's), and counts are
// taken with the engine's own arithmetic so that no scene reaches one of its aborts.
#include "game/scene_particles.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <tuple>
#include <utility>

#include "game/limits.h"
#include "render/particle_style.h"

namespace game {

std::size_t SoftBodyParticleCount(const engine::SoftBodyDef& def) {
  // engine/src/particles/soft_bodies.cpp: MakeRing and MakeLattice.
  const double s = def.spacing;
  if (def.shape.type == engine::ShapeType::kCircle) {
    const double ring = def.shape.radius - 0.5 * s;
    return static_cast<std::size_t>(std::max(6.0, std::ceil(2.0 * std::numbers::pi * ring / s - 1e-9)));
  }
  const engine::Vec2 half = def.shape.half_extents;
  const double nx = std::max(1.0, std::ceil((2.0 * half.x - s) / s - 1e-9));
  const double ny = std::max(1.0, std::ceil((2.0 * half.y - s) / s - 1e-9));
  return static_cast<std::size_t>((nx + 1.0) * (ny + 1.0));
}

std::size_t FluidParticleCount(const engine::FluidDef& def) {
  // engine/src/particles/particle_system.cpp, AddFluid: the same loops, counted one row and one
  // column (every row has as many).
  const double s = def.spacing;
  std::size_t rows = 0, columns = 0;
  for (double y = def.region.lower.y + 0.5 * s; y <= def.region.upper.y - 0.5 * s + 1e-9 * s; y += s) ++rows;
  for (double x = def.region.lower.x + 0.5 * s; x <= def.region.upper.x - 0.5 * s + 1e-9 * s; x += s) ++columns;
  return rows * columns;
}

}  // namespace game

namespace game::scene_values {

namespace {

std::string Number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

// A count in whole numbers; an estimate past 1e15 in three digits.
std::string Limit(double v) {
  char text[48];
  std::snprintf(text, sizeof text, v < 1e15 ? "%.0f" : "%.3g", v);
  return text;
}

// `list`, the root's `name` ("soft_bodies", "fluids", "emitters"), as an array of at most `limit`
// items, each read by `read(item, path, index)`; ids unique within the list, defaulting to
// `prefix`<index>.
template <class Item, class Read>
std::vector<Item> ReadList(const Json& list, const std::string& name, const char* prefix, std::size_t limit,
                           Read read) {
  if (!list.is_array()) throw SceneError{name, "must be an array"};
  if (list.size() > limit) {
    const std::string noun = name == "soft_bodies" ? "soft bodies" : name;
    throw SceneError{name, std::to_string(list.size()) + " " + noun + ", more than the limit of " + std::to_string(limit) +
                               " (docs/limits.md)"};
  }
  std::vector<Item> out;
  std::map<std::string, std::size_t> first_use;  // ordered: no hash-map order anywhere
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string path = name + "[" + std::to_string(i) + "]";
    const Json& item = list[i];
    if (!item.is_object()) throw SceneError{path, "must be an object"};
    Item made = read(item, path, i);
    made.id = prefix + std::to_string(i);
    made.id_given = Find(item, "id") != nullptr;
    if (made.id_given) {
      made.id = ReadString(item.at("id"), Join(path, "id"));
      if (made.id.empty()) throw SceneError{Join(path, "id"), "must not be empty"};
    }
    const auto [it, inserted] = first_use.emplace(made.id, i);
    if (!inserted) {
      const std::string other = name + "[" + std::to_string(it->second) + "]";
      if (!made.id_given) {
        throw SceneError{path, "its default id " + Quote(made.id) + " is taken by " + other + "; give one of them an \"id\""};
      }
      throw SceneError{Join(path, "id"), "duplicate id " + Quote(made.id) + " (also " + other + ")"};
    }
    out.push_back(std::move(made));
  }
  return out;
}

// A body named by id (`attach_to`, an emitter's `body`), as BodyId{its index}.
engine::BodyId ReadBodyRef(const Json& value, const std::string& path,
                           const std::map<std::string, std::size_t>& body_ids) {
  const std::string id = ReadString(value, path);
  const auto it = body_ids.find(id);
  if (it == body_ids.end()) throw SceneError{path, "no body has the id " + Quote(id)};
  return engine::BodyId{static_cast<engine::BodyIndex>(it->second)};  // bodies take slots in scene order
}

// Adds `count` particles to the scene's total, naming `path` when it passes kMaxParticles.
void CountParticles(double count, const std::string& path, std::size_t* total) {
  if (count + static_cast<double>(*total) > static_cast<double>(kMaxParticles)) {
    throw SceneError{path, "makes " + Limit(count) + " particles, which takes the scene's soft-body and fluid particles to " +
                               Limit(count + static_cast<double>(*total)) + ", more than the limit of " +
                               std::to_string(kMaxParticles) + " (docs/limits.md)"};
  }
  *total += static_cast<std::size_t>(count);
}

// A spacing a double can resolve where the particles lie, `reach` from the origin. `path` is
// the spacing's when the file gave it, else the placement's (`position`, `region`).
void CheckResolved(double spacing, double reach, const std::string& path, bool spacing_given) {
  if (spacing >= kMinRelativeSpacing * reach) return;
  if (spacing_given) {
    throw SceneError{path, "is " + Number(spacing) + " m, less than 1e-9 of the particles' distance from the origin (" +
                               Number(reach) + " m): a double cannot keep them apart (docs/limits.md)"};
  }
  throw SceneError{path, "puts the particles " + Number(reach) + " m from the origin, where their spacing (" +
                             Number(spacing) + " m) is less than 1e-9 of that: a double cannot keep them apart (docs/limits.md)"};
}

// --- Soft bodies.

// The shape keys: a circle's `radius` or a box's `size`, and the keys of one shape only.
void ReadSoftShape(const Json& soft, const std::string& path, engine::SoftBodyDef* def) {
  auto key = [&](const char* k) { return Join(path, k); };
  const Json* shape = Find(soft, "shape");
  if (!shape) throw SceneError{path, "needs a \"shape\" (\"circle\" or \"box\")"};
  def->shape.type = ReadChoice<engine::ShapeType>(*shape, key("shape"),
                                                 {{"circle", engine::ShapeType::kCircle}, {"box", engine::ShapeType::kBox}});
  const bool circle = def->shape.type == engine::ShapeType::kCircle;
  const char* has = circle ? "a soft circle has \"radius\" and optional \"pressure\""
                           : "a soft box has \"size\" and optional \"shear_compliance\"";
  for (const char* k : {"radius", "pressure"}) {
    if (!circle && Find(soft, k)) throw SceneError{key(k), std::string("applies to soft circles only; ") + has};
  }
  for (const char* k : {"size", "shear_compliance"}) {
    if (circle && Find(soft, k)) throw SceneError{key(k), std::string("applies to soft boxes only; ") + has};
  }
  if (circle) {
    const Json* radius = Find(soft, "radius");
    if (!radius) throw SceneError{path, "needs a \"radius\" (a soft circle)"};
    def->shape.radius = ReadPositive(*radius, key("radius"));
    if (!(def->shape.radius >= kMinBodySize)) throw SceneError{key("radius"), TooSmall()};
  } else {
    const Json* size = Find(soft, "size");
    if (!size) throw SceneError{path, "needs a \"size\" [width, height] (a soft box)"};
    const engine::Vec2 s = ReadVec2(*size, key("size"));
    for (int k = 0; k < 2; ++k) {
      const std::string at = key("size") + "[" + std::to_string(k) + "]";
      const double side = k == 0 ? s.x : s.y;
      if (!(side > 0.0)) throw SceneError{at, "must be > 0"};
      if (!(side >= kMinBodySize)) throw SceneError{at, TooSmall()};
    }
    def->shape.half_extents = 0.5 * s;
  }
}

// The spacing against the shape, by the engine's own tests (World::CreateSoftBody), and the
// mass each particle gets.
void CheckSoftSpacing(const Json& soft, const std::string& path, const engine::SoftBodyDef& def) {
  const bool circle = def.shape.type == engine::ShapeType::kCircle;
  const bool spacing_given = Find(soft, "spacing") != nullptr;
  const std::string spacing_text = Number(def.spacing) + (spacing_given ? "" : ", the default");
  const engine::Vec2 half = def.shape.half_extents;
  if (circle && !(def.shape.radius > def.spacing)) {
    if (spacing_given) throw SceneError{Join(path, "spacing"), "must be less than the radius (" + Number(def.shape.radius) + ")"};
    throw SceneError{Join(path, "radius"), "must be larger than the spacing (" + spacing_text + ")"};
  }
  if (!circle && !(2.0 * std::min(half.x, half.y) > def.spacing)) {
    if (spacing_given) throw SceneError{Join(path, "spacing"), "must be less than the box's shorter side (" + Number(2.0 * std::min(half.x, half.y)) + ")"};
    throw SceneError{Join(path, "size"), "both sides must be longer than the spacing (" + spacing_text + ")"};
  }
  const double extent = circle ? def.shape.radius : engine::Length(half);
  CheckResolved(def.spacing, std::max(std::abs(def.position.x), std::abs(def.position.y)) + extent,
                Join(path, spacing_given ? "spacing" : "position"), spacing_given);
  const double bound = circle ? 2.0 * std::numbers::pi * def.shape.radius / def.spacing
                              : (2.0 * half.x / def.spacing + 1.0) * (2.0 * half.y / def.spacing + 1.0);
  if (!(bound <= kMaxSoftBodyParticles)) {
    throw SceneError{Join(path, spacing_given ? "spacing" : (circle ? "radius" : "size")),
                     "makes about " + Limit(bound) + " particles, more than the limit of " + Limit(kMaxSoftBodyParticles) +
                         " in one soft body (" + (circle ? "2π·radius" : "(width / spacing + 1)·(height / spacing + 1)") +
                         (circle ? " / spacing" : "") + "; docs/limits.md)"};
  }
  const double area = circle ? std::numbers::pi * def.shape.radius * def.shape.radius : 4.0 * half.x * half.y;
  const double mass = def.density * area / static_cast<double>(SoftBodyParticleCount(def));
  if (!(mass >= kMinBodyMass)) {
    throw SceneError{path, "its particles' mass, density * area / particles (" + Number(mass) +
                               " kg), must be at least 1e-12 kg (docs/limits.md)"};
  }
}

// The numbers every soft body takes, whatever its shape.
void ReadSoftNumbers(const Json& soft, const std::string& path, engine::SoftBodyDef* def) {
  auto key = [&](const char* k) { return Join(path, k); };
  const Json* position = Find(soft, "position");
  if (!position) throw SceneError{path, "needs a \"position\" [x, y]"};
  def->position = ReadVec2(*position, key("position"));
  if (const Json* v = Find(soft, "angle")) def->angle = ReadNumber(*v, key("angle"));
  if (const Json* v = Find(soft, "velocity")) def->velocity = ReadVec2(*v, key("velocity"));
  if (const Json* v = Find(soft, "density")) def->density = ReadPositive(*v, key("density"));
  if (const Json* v = Find(soft, "spacing")) {
    def->spacing = ReadPositive(*v, key("spacing"));
    if (!(def->spacing >= kMinBodySize)) throw SceneError{key("spacing"), TooSmall()};
  }
  const std::pair<const char*, double*> non_negative[] = {
      {"stretch_compliance", &def->stretch_compliance}, {"shear_compliance", &def->shear_compliance},
      {"area_compliance", &def->area_compliance},       {"damping", &def->damping},
      {"friction", &def->friction}};
  for (const auto& [k, out] : non_negative) {
    if (const Json* v = Find(soft, k)) *out = ReadNonNegative(*v, key(k));
  }
  if (const Json* v = Find(soft, "pressure")) def->pressure = ReadPositive(*v, key("pressure"));
}

SceneSoftBody ReadSoftBody(const Json& soft, const std::string& path,
                           const std::map<std::string, std::size_t>& body_ids) {
  RejectUnknownKeys(soft, path,
                    {"id", "shape", "radius", "size", "position", "angle", "velocity", "density", "spacing",
                     "stretch_compliance", "shear_compliance", "area_compliance", "pressure", "damping", "friction",
                     "attach_to", "color"});
  SceneSoftBody out;
  ReadSoftShape(soft, path, &out.def);
  ReadSoftNumbers(soft, path, &out.def);
  CheckSoftSpacing(soft, path, out.def);
  if (const Json* v = Find(soft, "attach_to")) out.def.attach_to = ReadBodyRef(*v, Join(path, "attach_to"), body_ids);
  out.color = render::kSoftBodyColor;
  if (const Json* v = Find(soft, "color")) out.color = ReadColor(*v, Join(path, "color"));
  return out;
}

// --- Fluid.

// [[x0, y0], [x1, y1]]: two opposite corners, in either order.
engine::AABB ReadRegion(const Json& fluid, const std::string& path) {
  const std::string key = Join(path, "region");
  const Json* region = Find(fluid, "region");
  if (!region) throw SceneError{path, "needs a \"region\" [[x0, y0], [x1, y1]]: two opposite corners of the block"};
  if (!region->is_array() || region->size() != 2) {
    throw SceneError{key, "must be [[x0, y0], [x1, y1]]: two opposite corners of the block"};
  }
  const engine::Vec2 a = ReadVec2((*region)[0], key + "[0]");
  const engine::Vec2 b = ReadVec2((*region)[1], key + "[1]");
  return {{std::min(a.x, b.x), std::min(a.y, b.y)}, {std::max(a.x, b.x), std::max(a.y, b.y)}};
}

// The lattice the block makes: room for a particle, a spacing a double resolves there, a mass
// the engine can divide by, and its count within the scene's limit.
void CheckFluidLattice(const Json& fluid, const std::string& path, SceneFluid* out, std::size_t* particles) {
  auto key = [&](const char* k) { return Join(path, k); };
  const engine::FluidDef& def = out->def;
  const engine::Vec2 extent = def.region.upper - def.region.lower;
  if (!(std::min(extent.x, extent.y) >= def.spacing)) {
    throw SceneError{key("region"), "is " + Number(extent.x) + " by " + Number(extent.y) +
                                        " m; each side must be at least the spacing (" + Number(def.spacing) +
                                        ") to hold a particle"};
  }
  const double reach = std::max({std::abs(def.region.lower.x), std::abs(def.region.lower.y),
                                 std::abs(def.region.upper.x), std::abs(def.region.upper.y)});
  const bool spacing_given = Find(fluid, "spacing") != nullptr;
  CheckResolved(def.spacing, reach, spacing_given ? key("spacing") : key("region"), spacing_given);
  // A particle's mass is about density × spacing² (the kernel sums to about 1 / spacing²).
  if (!(def.density * def.spacing * def.spacing >= kMinBodyMass)) {
    throw SceneError{path, "its particles' mass, about density * spacing^2, must be at least 1e-12 kg (docs/limits.md)"};
  }
  // Counted by the side, so a block of 1e18 particles is refused before it is counted out.
  const double side_bound = (extent.x / def.spacing + 1.0) * (extent.y / def.spacing + 1.0);
  if (side_bound > static_cast<double>(2 * kMaxParticles)) CountParticles(side_bound, path, particles);
  out->particles = FluidParticleCount(def);
  if (out->particles == 0) throw SceneError{key("region"), "holds no particle at this spacing (" + Number(def.spacing) + ")"};
  CountParticles(static_cast<double>(out->particles), path, particles);
}

// "#rrggbb", as a message quotes a colour.
std::string Hex(render::Color c) {
  char text[8];
  std::snprintf(text, sizeof text, "#%02x%02x%02x", c.r, c.g, c.b);
  return text;
}

// `first`: the first block, or null when this is the first; a later block takes its spacing
// and colour.
SceneFluid ReadFluid(const Json& fluid, const std::string& path, const SceneFluid* first, std::size_t* particles) {
  RejectUnknownKeys(fluid, path,
                    {"id", "region", "spacing", "density", "velocity", "viscosity", "vorticity", "friction", "color"});
  auto key = [&](const char* k) { return Join(path, k); };
  SceneFluid out;
  engine::FluidDef& def = out.def;
  def.region = ReadRegion(fluid, path);
  // Every block shares the first one's spacing (the engine's kernel has one size).
  if (first) def.spacing = first->def.spacing;
  if (const Json* v = Find(fluid, "spacing")) {
    const double spacing = ReadPositive(*v, key("spacing"));
    if (!(spacing >= kMinBodySize)) throw SceneError{key("spacing"), TooSmall()};
    if (first && spacing != def.spacing) {
      throw SceneError{key("spacing"), "is " + Number(spacing) + ", but fluids[0] has " + Number(def.spacing) +
                                           ": every fluid shares one spacing (leave it out to take the first's)"};
    }
    def.spacing = spacing;
  }
  if (const Json* v = Find(fluid, "density")) def.density = ReadPositive(*v, key("density"));
  if (const Json* v = Find(fluid, "velocity")) def.velocity = ReadVec2(*v, key("velocity"));
  if (const Json* v = Find(fluid, "viscosity")) {
    def.viscosity = ReadNonNegative(*v, key("viscosity"));
    if (def.viscosity > 1.0) throw SceneError{key("viscosity"), "must be from 0 to 1"};
  }
  if (const Json* v = Find(fluid, "vorticity")) def.vorticity = ReadNonNegative(*v, key("vorticity"));
  if (const Json* v = Find(fluid, "friction")) def.friction = ReadNonNegative(*v, key("friction"));
  CheckFluidLattice(fluid, path, &out, particles);
  // Every block shares the first one's colour too: the renderer draws the fluid as one liquid.
  out.color = first ? first->color : render::kFluidColor;
  if (const Json* v = Find(fluid, "color")) {
    const render::Color color = ReadColor(*v, key("color"));
    if (first && color != out.color) {
      throw SceneError{key("color"), "is " + Quote(Hex(color)) + ", but fluids[0] has " + Quote(Hex(out.color)) +
                                         ": every fluid is drawn as one liquid in one colour (leave it out to take the first's)"};
    }
    out.color = color;
  }
  return out;
}

// --- Emitters.

// A value given once for the whole life or as [start, end]: `size`, `color`.
template <class T, class Read>
std::pair<T, T> ReadStartEnd(const Json& value, const std::string& path, Read read) {
  if (!value.is_array()) {
    const T both = read(value, path);
    return {both, both};
  }
  if (value.size() != 2) throw SceneError{path, "must be one value, or [start, end]"};
  return {read(value[0], path + "[0]"), read(value[1], path + "[1]")};
}

// A spread within ± its mean's value: `speed_spread` against `speed`, `lifetime_spread`
// against `lifetime`, naming whichever the file gave.
void CheckSpread(const Json& emitter, const std::string& path, const char* mean_key, double mean,
                 const char* spread_key, double spread) {
  if (spread <= mean) return;
  if (Find(emitter, spread_key)) {
    throw SceneError{Join(path, spread_key), "must not be larger than " + std::string(mean_key) + " (" + Number(mean) + ")"};
  }
  throw SceneError{Join(path, mean_key), "must be at least " + std::string(spread_key) + " (" + Number(spread) +
                                             ", the default); give a smaller \"" + spread_key + "\""};
}

void ReadEmitterMotion(const Json& emitter, const std::string& path, engine::EmitterDef* def) {
  auto key = [&](const char* k) { return Join(path, k); };
  const std::pair<const char*, double*> non_negative[] = {
      {"spread", &def->spread},     {"speed", &def->speed},       {"speed_spread", &def->speed_spread},
      {"rate", &def->rate},         {"lifetime_spread", &def->lifetime_spread}, {"drag", &def->drag},
      {"restitution", &def->restitution}, {"friction", &def->friction}};
  for (const auto& [k, out] : non_negative) {
    if (const Json* v = Find(emitter, k)) *out = ReadNonNegative(*v, key(k));
  }
  if (const Json* v = Find(emitter, "direction")) def->direction = ReadNumber(*v, key("direction"));
  if (const Json* v = Find(emitter, "lifetime")) def->lifetime = ReadPositive(*v, key("lifetime"));
  if (const Json* v = Find(emitter, "buoyancy")) def->buoyancy = ReadNumber(*v, key("buoyancy"));
  if (const Json* v = Find(emitter, "collide")) def->collide = ReadBool(*v, key("collide"));
  CheckSpread(emitter, path, "speed", def->speed, "speed_spread", def->speed_spread);
  CheckSpread(emitter, path, "lifetime", def->lifetime, "lifetime_spread", def->lifetime_spread);
}

void ReadEmitterLooks(const Json& emitter, const std::string& path, engine::EmitterDef* def) {
  auto key = [&](const char* k) { return Join(path, k); };
  if (const Json* v = Find(emitter, "size")) {
    std::tie(def->size_start, def->size_end) = ReadStartEnd<double>(*v, key("size"), ReadNonNegative);
  }
  if (const Json* v = Find(emitter, "color")) {
    std::tie(def->color_start, def->color_end) = ReadStartEnd<engine::Rgba>(*v, key("color"), ReadRgba);
  }
  if (const Json* v = Find(emitter, "blend")) {
    def->blend = ReadChoice<engine::EffectBlend>(
        *v, key("blend"), {{"additive", engine::EffectBlend::kAdditive}, {"alpha", engine::EffectBlend::kAlpha}});
  }
}

SceneEmitter ReadEmitter(const Json& emitter, const std::string& path,
                         const std::map<std::string, std::size_t>& body_ids) {
  RejectUnknownKeys(emitter, path,
                    {"id", "position", "body", "direction", "spread", "speed", "speed_spread", "rate", "lifetime",
                     "lifetime_spread", "size", "color", "blend", "drag", "buoyancy", "restitution", "friction",
                     "collide", "seed", "max_particles"});
  auto key = [&](const char* k) { return Join(path, k); };
  SceneEmitter out;
  engine::EmitterDef& def = out.def;
  if (const Json* v = Find(emitter, "body")) def.body = ReadBodyRef(*v, key("body"), body_ids);
  const Json* position = Find(emitter, "position");
  // On a body the position defaults to the body's own; alone, an emitter needs a place.
  if (!position && !def.body) throw SceneError{path, "needs a \"position\" [x, y] (or a \"body\" to ride on)"};
  if (position) def.position = ReadVec2(*position, key("position"));
  ReadEmitterMotion(emitter, path, &def);
  ReadEmitterLooks(emitter, path, &def);
  if (const Json* v = Find(emitter, "seed")) {
    def.seed = static_cast<std::uint64_t>(ReadWhole(*v, key("seed"), 0, kMaxSceneMagnitude));
  }
  if (const Json* v = Find(emitter, "max_particles")) {
    def.max_particles = static_cast<std::uint32_t>(ReadWhole(*v, key("max_particles"), 1, kMaxEffectParticles));
  }
  return out;
}

}  // namespace

void ReadParticleSettings(const Json& value, const std::string& path, engine::WorldDef* world) {
  if (!value.is_object()) throw SceneError{path, "must be an object"};
  RejectUnknownKeys(value, path, {"substep", "iterations"});
  if (const Json* v = Find(value, "substep")) world->particles.substep = ReadPositive(*v, Join(path, "substep"));
  if (const Json* v = Find(value, "iterations")) {
    world->particles.iterations = static_cast<int>(ReadWhole(*v, Join(path, "iterations"), 1, kMaxParticleIterations));
  }
}

std::vector<SceneSoftBody> ReadSoftBodies(const Json& list, const std::map<std::string, std::size_t>& body_ids,
                                          std::size_t* particles) {
  return ReadList<SceneSoftBody>(list, "soft_bodies", "soft", kMaxSoftBodies,
                                 [&](const Json& soft, const std::string& path, std::size_t) {
                                   SceneSoftBody out = ReadSoftBody(soft, path, body_ids);
                                   CountParticles(static_cast<double>(SoftBodyParticleCount(out.def)), path, particles);
                                   return out;
                                 });
}

std::vector<SceneFluid> ReadFluids(const Json& list, std::size_t* particles) {
  std::optional<SceneFluid> first;  // the first block, once read
  return ReadList<SceneFluid>(list, "fluids", "fluid", kMaxParticles,
                              [&](const Json& fluid, const std::string& path, std::size_t) {
                                SceneFluid out = ReadFluid(fluid, path, first ? &*first : nullptr, particles);
                                if (!first) first = out;
                                return out;
                              });
}

std::vector<SceneEmitter> ReadEmitters(const Json& list, const std::map<std::string, std::size_t>& body_ids) {
  double kept_alive = 0.0;
  return ReadList<SceneEmitter>(list, "emitters", "emitter", kMaxEmitters,
                                [&](const Json& emitter, const std::string& path, std::size_t) {
                                  SceneEmitter out = ReadEmitter(emitter, path, body_ids);
                                  kept_alive += out.def.max_particles;
                                  if (kept_alive > kMaxEffectParticles) {
                                    throw SceneError{Join(path, "max_particles"),
                                                     "takes the emitters' max_particles to " + Limit(kept_alive) +
                                                         ", more than the limit of " + Limit(kMaxEffectParticles) +
                                                         " effect particles alive at once (docs/limits.md)"};
                                  }
                                  return out;
                                });
}

void CheckParticleSubsteps(const Json& root, const Scene& scene) {
  if (scene.soft_bodies.empty() && scene.fluids.empty()) return;
  const engine::WorldDef& world = scene.world;
  if (!(world.dt >= kMinParticleDt)) {
    throw SceneError{"dt", "must be at least 1e-09 s in a scene with soft bodies or fluid (docs/limits.md)"};
  }
  // engine/src/particles/particle_system.cpp, Step: ceil(dt / substep) substeps.
  const double substeps = std::ceil(world.dt / world.particles.substep - 1e-9);
  if (substeps <= kMaxParticleSubsteps) return;
  const Json* settings = Find(root, "particles");
  const bool substep_given = settings && settings->is_object() && Find(*settings, "substep");
  throw SceneError{substep_given ? "particles.substep" : "dt",
                   "makes " + Limit(substeps) + " particle substeps a step (dt / particles.substep" +
                       (substep_given ? "" : ", 1/" + Limit(1.0 / engine::ParticleSettings{}.substep) + " s by default") +
                       "), more than the limit of " +
                       Limit(kMaxParticleSubsteps) + " (docs/limits.md)"};
}

}  // namespace game::scene_values
