// game::ParseScene for soft bodies, fluids, emitters and the particle settings: every key read
// into the engine def expected by hand, the engine defs' defaults, every bad value named by its
// key path (in-process and through the program: exit 2, one line, nothing written), and
// BuildWorld making what the scene says in file order.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "game/scene.h"
#include "game/scene_particles.h"
#include "render/particle_style.h"
#include "run_program.h"

namespace {

namespace fs = std::filesystem;
using engine::Vec2;

const char* kBodies = R"([
  {"id": "floor", "shape": "box", "size": [10, 1], "position": [0, -0.5], "static": true},
  {"id": "crate", "shape": "box", "size": [1, 1], "position": [3, 0.5]},
  {"shape": "circle", "radius": 0.5, "position": [-3, 2]}])";

// A scene of kBodies and `rest`, more top-level keys ("soft_bodies": [...], ...).
std::string SceneWith(const std::string& rest) {
  return std::string("{\"bodies\": ") + kBodies + (rest.empty() ? "" : ", " + rest) + "}";
}

game::Scene RequireParsed(const std::string& json) {
  game::Expected<game::Scene> scene = game::ParseScene(json, "particles.json", "particles");
  if (!scene.HasValue()) FAIL(scene.Error().message);
  return scene.Value();
}

// Bad input whose message is "particles.json: " then exactly `rest`.
void RequireError(const std::string& json, const std::string& rest) {
  const game::Expected<game::Scene> scene = game::ParseScene(json, "particles.json", "particles");
  INFO(json);
  REQUIRE_FALSE(scene.HasValue());
  CHECK(scene.Error().exit_code == 2);
  CHECK(scene.Error().message == "particles.json: " + rest);
}

bool Same(Vec2 a, Vec2 b) { return a.x == b.x && a.y == b.y; }
bool SameColor(render::Color c, int r, int g, int b) { return c.r == r && c.g == g && c.b == b; }
bool SameRgba(engine::Rgba c, int r, int g, int b, int a) {
  return c == engine::Rgba{r / 255.0f, g / 255.0f, b / 255.0f, a / 255.0f};
}

const char* kCircle = R"({"shape": "circle", "radius": 0.5, "position": [0, 2]})";

}  // namespace

// --- Each key lands in its def.

TEST_CASE("scene particles: a soft circle with every key", "[scene][particles]") {
  const game::Scene scene = RequireParsed(SceneWith(R"("soft_bodies": [
    {"id": "jelly", "shape": "circle", "radius": 0.75, "position": [1, 2], "angle": 0.25, "velocity": [3, -4],
     "density": 2.5, "spacing": 0.125, "stretch_compliance": 0.001, "area_compliance": 0.02, "pressure": 1.5,
     "damping": 3, "friction": 0.6, "attach_to": "crate", "color": "#c84"}])"));
  REQUIRE(scene.soft_bodies.size() == 1);
  const game::SceneSoftBody& soft = scene.soft_bodies[0];
  CHECK(soft.id == "jelly");
  CHECK(soft.id_given);
  const engine::SoftBodyDef& def = soft.def;
  CHECK(def.shape.type == engine::ShapeType::kCircle);
  CHECK(def.shape.radius == 0.75);
  CHECK(Same(def.position, {1, 2}));
  CHECK(def.angle == 0.25);
  CHECK(Same(def.velocity, {3, -4}));
  CHECK(def.density == 2.5);
  CHECK(def.spacing == 0.125);
  CHECK(def.stretch_compliance == 0.001);
  CHECK(def.shear_compliance == engine::SoftBodyDef{}.shear_compliance);
  CHECK(def.area_compliance == 0.02);
  CHECK(def.pressure == 1.5);
  CHECK(def.damping == 3.0);
  CHECK(def.friction == 0.6);
  REQUIRE(def.attach_to.has_value());
  CHECK(def.attach_to->index == 1);
  CHECK(SameColor(soft.color, 0xcc, 0x88, 0x44));
}

TEST_CASE("scene particles: a soft box with every key", "[scene][particles]") {
  const game::Scene scene = RequireParsed(SceneWith(R"("soft_bodies": [
    {"shape": "box", "size": [2, 0.5], "position": [-1, 3], "spacing": 0.05, "stretch_compliance": 0,
     "shear_compliance": 0.003, "area_compliance": 0.5, "attach_to": "floor", "color": "#102030"}])"));
  const engine::SoftBodyDef& def = scene.soft_bodies.at(0).def;
  CHECK(scene.soft_bodies[0].id == "soft0");
  CHECK_FALSE(scene.soft_bodies[0].id_given);
  CHECK(def.shape.type == engine::ShapeType::kBox);
  CHECK(Same(def.shape.half_extents, {1, 0.25}));
  CHECK(def.spacing == 0.05);
  CHECK(def.stretch_compliance == 0.0);
  CHECK(def.shear_compliance == 0.003);
  CHECK(def.area_compliance == 0.5);
  CHECK(def.attach_to->index == 0);
  CHECK(SameColor(scene.soft_bodies[0].color, 0x10, 0x20, 0x30));
}

TEST_CASE("scene particles: a soft body's unset keys are the engine's defaults", "[scene][particles]") {
  const game::Scene scene = RequireParsed(SceneWith(std::string("\"soft_bodies\": [") + kCircle + ", " + kCircle + "]"));
  const engine::SoftBodyDef engine_default;
  for (std::size_t i = 0; i < 2; ++i) {
    const engine::SoftBodyDef& def = scene.soft_bodies.at(i).def;
    CHECK(def.angle == engine_default.angle);
    CHECK(Same(def.velocity, engine_default.velocity));
    CHECK(def.density == engine_default.density);
    CHECK(def.spacing == engine_default.spacing);
    CHECK(def.stretch_compliance == engine_default.stretch_compliance);
    CHECK(def.shear_compliance == engine_default.shear_compliance);
    CHECK(def.area_compliance == engine_default.area_compliance);
    CHECK(def.pressure == engine_default.pressure);
    CHECK(def.damping == engine_default.damping);
    CHECK(def.friction == engine_default.friction);
    CHECK_FALSE(def.attach_to.has_value());
    CHECK(scene.soft_bodies[i].id == "soft" + std::to_string(i));
    CHECK(scene.soft_bodies[i].color == render::kSoftBodyColor);  // the renderer's default
  }
}

TEST_CASE("scene particles: a fluid with every key, and the defaults", "[scene][particles]") {
  const game::Scene scene = RequireParsed(SceneWith(R"("fluids": [
    {"id": "pool", "region": [[1, 2], [-1, 0.5]], "spacing": 0.1, "density": 800, "velocity": [0.5, -1],
     "viscosity": 0.2, "vorticity": 0.3, "friction": 0.4, "color": "#08f"},
    {"region": [[2, 0], [3, 1]]}, {"region": [[4, 0], [5, 1]], "color": "#0088ff"}])"));
  REQUIRE(scene.fluids.size() == 3);
  const engine::FluidDef& def = scene.fluids[0].def;
  CHECK(scene.fluids[0].id == "pool");
  CHECK(Same(def.region.lower, {-1, 0.5}));  // two opposite corners, in either order
  CHECK(Same(def.region.upper, {1, 2}));
  CHECK(def.spacing == 0.1);
  CHECK(def.density == 800.0);
  CHECK(Same(def.velocity, {0.5, -1}));
  CHECK(def.viscosity == 0.2);
  CHECK(def.vorticity == 0.3);
  CHECK(def.friction == 0.4);
  CHECK(SameColor(scene.fluids[0].color, 0x00, 0x88, 0xff));
  CHECK(scene.fluids[0].particles == 20 * 15);

  const engine::FluidDef engine_default;
  const engine::FluidDef& second = scene.fluids[1].def;
  CHECK(scene.fluids[1].id == "fluid1");
  CHECK(second.spacing == 0.1);  // the first block's: every block shares it
  CHECK(second.density == engine_default.density);
  CHECK(Same(second.velocity, engine_default.velocity));
  CHECK(second.viscosity == engine_default.viscosity);
  CHECK(second.vorticity == engine_default.vorticity);
  CHECK(second.friction == engine_default.friction);
  CHECK(scene.fluids[1].color == scene.fluids[0].color);  // one liquid: the first block's colour
  CHECK(scene.fluids[2].color == scene.fluids[0].color);  // the same colour written another way

  const game::Scene alone = RequireParsed(SceneWith(R"("fluids": [{"region": [[0, 0], [1, 1]]}])"));
  CHECK(alone.fluids.at(0).def.spacing == engine_default.spacing);
  CHECK(alone.fluids[0].particles == 400);
  CHECK(alone.fluids[0].color == render::kFluidColor);  // the renderer's default
}

TEST_CASE("scene particles: an emitter with every key", "[scene][particles]") {
  const game::Scene scene = RequireParsed(SceneWith(R"("emitters": [
    {"id": "torch", "position": [0.5, 0.25], "body": "crate", "direction": 1.25, "spread": 0.5, "speed": 3,
     "speed_spread": 1, "rate": 250, "lifetime": 2, "lifetime_spread": 0.5, "size": [0.05, 0.4],
     "color": ["#ff8000ff", "#f004"], "blend": "alpha", "drag": 1.5, "buoyancy": 1.25, "restitution": 0.1,
     "friction": 0.7, "collide": false, "seed": 123456789, "max_particles": 2500}])"));
  REQUIRE(scene.emitters.size() == 1);
  CHECK(scene.emitters[0].id == "torch");
  const engine::EmitterDef& def = scene.emitters[0].def;
  CHECK(Same(def.position, {0.5, 0.25}));
  REQUIRE(def.body.has_value());
  CHECK(def.body->index == 1);
  CHECK(def.direction == 1.25);
  CHECK(def.spread == 0.5);
  CHECK(def.speed == 3.0);
  CHECK(def.speed_spread == 1.0);
  CHECK(def.rate == 250.0);
  CHECK(def.lifetime == 2.0);
  CHECK(def.lifetime_spread == 0.5);
  CHECK(def.size_start == 0.05);
  CHECK(def.size_end == 0.4);
  CHECK(SameRgba(def.color_start, 0xff, 0x80, 0x00, 0xff));
  CHECK(SameRgba(def.color_end, 0xff, 0x00, 0x00, 0x44));
  CHECK(def.blend == engine::EffectBlend::kAlpha);
  CHECK(def.drag == 1.5);
  CHECK(def.buoyancy == 1.25);
  CHECK(def.restitution == 0.1);
  CHECK(def.friction == 0.7);
  CHECK_FALSE(def.collide);
  CHECK(def.seed == 123456789u);
  CHECK(def.max_particles == 2500u);
}

TEST_CASE("scene particles: an emitter's defaults, one size and one colour for the whole life",
          "[scene][particles]") {
  const game::Scene scene = RequireParsed(SceneWith(R"("emitters": [
    {"position": [1, 2]}, {"body": "body2", "size": 0.2, "color": "#8888"}, {"position": [0, 0], "color": "#123456"}])"));
  const engine::EmitterDef engine_default;
  const engine::EmitterDef& def = scene.emitters.at(0).def;
  CHECK(scene.emitters[0].id == "emitter0");
  CHECK(Same(def.position, {1, 2}));
  CHECK_FALSE(def.body.has_value());
  CHECK(def.direction == engine_default.direction);
  CHECK(def.spread == engine_default.spread);
  CHECK(def.speed == engine_default.speed);
  CHECK(def.speed_spread == engine_default.speed_spread);
  CHECK(def.rate == engine_default.rate);
  CHECK(def.lifetime == engine_default.lifetime);
  CHECK(def.lifetime_spread == engine_default.lifetime_spread);
  CHECK(def.size_start == engine_default.size_start);
  CHECK(def.size_end == engine_default.size_end);
  CHECK(def.color_start == engine_default.color_start);
  CHECK(def.color_end == engine_default.color_end);
  CHECK(def.blend == engine_default.blend);
  CHECK(def.drag == engine_default.drag);
  CHECK(def.buoyancy == engine_default.buoyancy);
  CHECK(def.restitution == engine_default.restitution);
  CHECK(def.friction == engine_default.friction);
  CHECK(def.collide == engine_default.collide);
  CHECK(def.seed == engine_default.seed);
  CHECK(def.max_particles == engine_default.max_particles);

  const engine::EmitterDef& riding = scene.emitters.at(1).def;
  CHECK(riding.body->index == 2);  // the body without an id, by its default one
  CHECK(Same(riding.position, {0, 0}));  // on its body's origin
  CHECK(riding.size_start == 0.2);
  CHECK(riding.size_end == 0.2);
  CHECK(SameRgba(riding.color_start, 0x88, 0x88, 0x88, 0x88));
  CHECK(riding.color_end == riding.color_start);
  CHECK(SameRgba(scene.emitters.at(2).def.color_start, 0x12, 0x34, 0x56, 0xff));  // opaque without alpha digits
}

TEST_CASE("scene particles: the particle settings and the click's particle keys", "[scene][particles]") {
  const game::Scene scene = RequireParsed(SceneWith(
      R"("particles": {"substep": 0.002, "iterations": 3}, "click": {"particle_radius": 0.75, "particle_speed": 2.5})"));
  CHECK(scene.world.particles.substep == 0.002);
  CHECK(scene.world.particles.iterations == 3);
  CHECK(scene.particle_click.radius == 0.75);
  CHECK(scene.particle_click.speed == 2.5);
  CHECK(scene.click_max_impulse == 10.0);
  const game::Scene plain = RequireParsed(SceneWith(""));
  const engine::ParticleSettings engine_default;
  CHECK(plain.world.particles.substep == engine_default.substep);
  CHECK(plain.world.particles.iterations == engine_default.iterations);
  CHECK(plain.particle_click.radius == 1.0);
  CHECK(plain.particle_click.speed == 5.0);
  CHECK_FALSE(plain.HasParticles());
  CHECK(RequireParsed(SceneWith(R"("soft_bodies": [], "fluids": [], "emitters": [])")).HasParticles() == false);
}

// --- Bad values, each named by its key path.

TEST_CASE("scene particles: every bad soft body value is named by its key path", "[scene][particles]") {
  const std::pair<const char*, const char*> cases[] = {
      {R"([{"shape": "circle", "radius": 0.5, "position": [0, 0], "densty": 1}])",
       R"(soft_bodies[0]: unknown key "densty" (did you mean "density"?))"},
      {R"([{"radius": 0.5, "position": [0, 0]}])", R"(soft_bodies[0]: needs a "shape" ("circle" or "box"))"},
      {R"([{"shape": "polygon", "position": [0, 0]}])",
       R"(soft_bodies[0].shape: unknown value "polygon" (expected one of "circle", "box"))"},
      {R"([{"shape": "circle", "position": [0, 0]}])", R"(soft_bodies[0]: needs a "radius" (a soft circle))"},
      {R"([{"shape": "box", "position": [0, 0]}])", R"(soft_bodies[0]: needs a "size" [width, height] (a soft box))"},
      {R"([{"shape": "box", "size": [1, 1], "radius": 0.5, "position": [0, 0]}])",
       R"(soft_bodies[0].radius: applies to soft circles only; a soft box has "size" and optional "shear_compliance")"},
      {R"([{"shape": "box", "size": [1, 1], "pressure": 2, "position": [0, 0]}])",
       R"(soft_bodies[0].pressure: applies to soft circles only; a soft box has "size" and optional "shear_compliance")"},
      {R"([{"shape": "circle", "radius": 0.5, "shear_compliance": 0.1, "position": [0, 0]}])",
       R"(soft_bodies[0].shear_compliance: applies to soft boxes only; a soft circle has "radius" and optional "pressure")"},
      {R"([{"shape": "circle", "radius": -1, "position": [0, 0]}])", "soft_bodies[0].radius: must be > 0"},
      {R"([{"shape": "circle", "radius": 1e-10, "position": [0, 0]}])",
       "soft_bodies[0].radius: must be at least 1e-09 m (docs/limits.md)"},
      {R"([{"shape": "box", "size": [1, 0], "position": [0, 0]}])", "soft_bodies[0].size[1]: must be > 0"},
      {R"([{"shape": "box", "size": [1], "position": [0, 0]}])", "soft_bodies[0].size: must be an array of 2 numbers"},
      {R"([{"shape": "circle", "radius": 0.5}])", R"(soft_bodies[0]: needs a "position" [x, y])"},
      {R"([{"shape": "circle", "radius": 0.5, "position": [0, "1"]}])", "soft_bodies[0].position[1]: must be a number"},
      {R"([{"shape": "circle", "radius": 0.5, "position": [0, 0], "velocity": [1e10, 0]}])",
       "soft_bodies[0].velocity[0]: must be between -1e9 and 1e9 (docs/limits.md)"},
      {R"([{"shape": "circle", "radius": 0.5, "position": [0, 0], "density": 0}])", "soft_bodies[0].density: must be > 0"},
      {R"([{"shape": "circle", "radius": 0.5, "position": [0, 0], "spacing": 0.5}])",
       "soft_bodies[0].spacing: must be less than the radius (0.5)"},
      {R"([{"shape": "circle", "radius": 0.05, "position": [0, 0]}])",
       "soft_bodies[0].radius: must be larger than the spacing (0.1, the default)"},
      {R"([{"shape": "box", "size": [1, 0.08], "position": [0, 0]}])",
       "soft_bodies[0].size: both sides must be longer than the spacing (0.1, the default)"},
      {R"([{"shape": "box", "size": [1, 0.5], "position": [0, 0], "spacing": 0.5}])",
       "soft_bodies[0].spacing: must be less than the box's shorter side (0.5)"},
      {R"([{"shape": "circle", "radius": 0.5, "position": [0, 0], "stretch_compliance": -1}])",
       "soft_bodies[0].stretch_compliance: must be >= 0"},
      {R"([{"shape": "box", "size": [1, 1], "position": [0, 0], "shear_compliance": -1}])",
       "soft_bodies[0].shear_compliance: must be >= 0"},
      {R"([{"shape": "circle", "radius": 0.5, "position": [0, 0], "area_compliance": "soft"}])",
       "soft_bodies[0].area_compliance: must be a number"},
      {R"([{"shape": "circle", "radius": 0.5, "position": [0, 0], "pressure": 0}])", "soft_bodies[0].pressure: must be > 0"},
      {R"([{"shape": "circle", "radius": 0.5, "position": [0, 0], "damping": -0.5}])", "soft_bodies[0].damping: must be >= 0"},
      {R"([{"shape": "circle", "radius": 0.5, "position": [0, 0], "friction": null}])", "soft_bodies[0].friction: must be a number"},
      {R"([{"shape": "circle", "radius": 0.5, "position": [0, 0], "attach_to": "flor"}])",
       R"(soft_bodies[0].attach_to: no body has the id "flor")"},
      {R"([{"shape": "circle", "radius": 0.5, "position": [0, 0], "attach_to": 0}])", "soft_bodies[0].attach_to: must be a string"},
      {R"([{"shape": "circle", "radius": 0.5, "position": [0, 0], "color": "#12345"}])",
       R"(soft_bodies[0].color: must be a colour "#rgb" or "#rrggbb", got "#12345")"},
      {R"([{"shape": "circle", "radius": 0.5, "position": [0, 0], "id": ""}])", "soft_bodies[0].id: must not be empty"},
      {R"([{"id": "a", "shape": "circle", "radius": 0.5, "position": [0, 0]}, {"id": "a", "shape": "circle", "radius": 0.5, "position": [2, 0]}])",
       R"(soft_bodies[1].id: duplicate id "a" (also soft_bodies[0]))"},
      {R"([{"id": "soft1", "shape": "circle", "radius": 0.5, "position": [0, 0]}, {"shape": "circle", "radius": 0.5, "position": [2, 0]}])",
       R"(soft_bodies[1]: its default id "soft1" is taken by soft_bodies[0]; give one of them an "id")"},
      {R"({"shape": "circle"})", "soft_bodies: must be an array"},
      {R"([3])", "soft_bodies[0]: must be an object"},
      {R"([{"shape": "circle", "radius": 0.5, "position": [0, 0]}, {"shape": "circle", "radius": 0.5, "position": [2, 0], "spacing": 0}])",
       "soft_bodies[1].spacing: must be > 0"},
  };
  for (const auto& [list, message] : cases) RequireError(SceneWith(std::string("\"soft_bodies\": ") + list), message);
}

TEST_CASE("scene particles: a soft body's particle count, mass and spacing limits", "[scene][particles][limits]") {
  RequireError(SceneWith(R"("soft_bodies": [{"shape": "circle", "radius": 100, "position": [0, 0], "spacing": 0.001}])"),
               "soft_bodies[0].spacing: makes about 628319 particles, more than the limit of 100000 in one soft body "
               "(2π·radius / spacing; docs/limits.md)");
  RequireError(SceneWith(R"("soft_bodies": [{"shape": "box", "size": [40, 40], "position": [0, 0]}])"),
               "soft_bodies[0].size: makes about 160801 particles, more than the limit of 100000 in one soft body "
               "((width / spacing + 1)·(height / spacing + 1); docs/limits.md)");
  // (31 / 0.1 + 1)² = 96721, under the engine's own bound.
  RequireParsed(SceneWith(R"("soft_bodies": [{"shape": "box", "size": [31, 31], "position": [0, 0]}])"));
  RequireError(SceneWith(R"("soft_bodies": [{"shape": "circle", "radius": 0.001, "position": [0, 0], "spacing": 0.0001,
                                            "density": 1e-6}])"),
               "soft_bodies[0]: its particles' mass, density * area / particles (5.23599e-14 kg), must be at least "
               "1e-12 kg (docs/limits.md)");
  RequireError(SceneWith(R"("soft_bodies": [{"shape": "circle", "radius": 1, "position": [1e9, 0]}])"),
               "soft_bodies[0].position: puts the particles 1e+09 m from the origin, where their spacing (0.1 m) is "
               "less than 1e-9 of that: a double cannot keep them apart (docs/limits.md)");
  RequireError(SceneWith(R"("soft_bodies": [{"shape": "circle", "radius": 1, "position": [1000, 0], "spacing": 1e-7}])"),
               "soft_bodies[0].spacing: is 1e-07 m, less than 1e-9 of the particles' distance from the origin (1001 m): "
               "a double cannot keep them apart (docs/limits.md)");
}

TEST_CASE("scene particles: every bad fluid value is named by its key path", "[scene][particles]") {
  const std::pair<const char*, const char*> cases[] = {
      {R"([{"region": [[0, 0], [1, 1]], "densty": 1}])", R"(fluids[0]: unknown key "densty" (did you mean "density"?))"},
      {R"([{"spacing": 0.1}])", R"(fluids[0]: needs a "region" [[x0, y0], [x1, y1]]: two opposite corners of the block)"},
      {R"([{"region": [[0, 0]]}])", "fluids[0].region: must be [[x0, y0], [x1, y1]]: two opposite corners of the block"},
      {R"([{"region": [[0, 0], 1]}])", "fluids[0].region[1]: must be an array of 2 numbers"},
      {R"([{"region": [[0, 0], [1, 0.01]]}])",
       "fluids[0].region: is 1 by 0.01 m; each side must be at least the spacing (0.05) to hold a particle"},
      {R"([{"region": [[0, 0], [1, 1]]}, {"region": [[2, 0], [3, 1]], "spacing": 0.1}])",
       "fluids[1].spacing: is 0.1, but fluids[0] has 0.05: every fluid shares one spacing (leave it out to take the first's)"},
      {R"([{"region": [[0, 0], [1, 1]], "spacing": -0.1}])", "fluids[0].spacing: must be > 0"},
      {R"([{"region": [[0, 0], [1, 1]], "density": 0}])", "fluids[0].density: must be > 0"},
      {R"([{"region": [[0, 0], [1, 1]], "velocity": 3}])", "fluids[0].velocity: must be an array of 2 numbers"},
      {R"([{"region": [[0, 0], [1, 1]], "viscosity": 1.5}])", "fluids[0].viscosity: must be from 0 to 1"},
      {R"([{"region": [[0, 0], [1, 1]], "viscosity": -0.1}])", "fluids[0].viscosity: must be >= 0"},
      {R"([{"region": [[0, 0], [1, 1]], "vorticity": -1}])", "fluids[0].vorticity: must be >= 0"},
      {R"([{"region": [[0, 0], [1, 1]], "friction": -1}])", "fluids[0].friction: must be >= 0"},
      {R"([{"region": [[0, 0], [1, 1]], "color": "blue"}])", R"(fluids[0].color: must be a colour "#rgb" or "#rrggbb", got "blue")"},
      {R"([{"region": [[0, 0], [1, 1]], "color": "#08f"}, {"region": [[2, 0], [3, 1]], "color": "#f00"}])",
       R"(fluids[1].color: is "#ff0000", but fluids[0] has "#0088ff": every fluid is drawn as one liquid in one )"
       R"(colour (leave it out to take the first's))"},
      {R"([{"region": [[0, 0], [1, 1]]}, {"region": [[2, 0], [3, 1]], "color": "#f00"}])",
       R"(fluids[1].color: is "#ff0000", but fluids[0] has "#2f86d6": every fluid is drawn as one liquid in one )"
       R"(colour (leave it out to take the first's))"},
      {R"([{"region": [[0, 0], [1, 1]], "density": 1e-9, "spacing": 0.01}])",
       "fluids[0]: its particles' mass, about density * spacing^2, must be at least 1e-12 kg (docs/limits.md)"},
      {R"([{"region": [[0, 0], [1001, 1000]], "spacing": 1}])",
       "fluids[0]: makes 1001000 particles, which takes the scene's soft-body and fluid particles to 1001000, more "
       "than the limit of 1000000 (docs/limits.md)"},
      {R"([{"region": [[0, 0], [1e5, 1e5]], "spacing": 1e-3}])",
       "fluids[0]: makes 1e+16 particles, which takes the scene's soft-body and fluid particles to 1e+16, more than the "
       "limit of 1000000 (docs/limits.md)"},
      {R"([{"region": [[1e9, 0], [999999999, 1]], "spacing": 0.5}])",
       "fluids[0].spacing: is 0.5 m, less than 1e-9 of the particles' distance from the origin (1e+09 m): a double "
       "cannot keep them apart (docs/limits.md)"},
      {R"([{"id": "pool", "region": [[0, 0], [1, 1]]}, {"id": "pool", "region": [[2, 0], [3, 1]]}])",
       R"(fluids[1].id: duplicate id "pool" (also fluids[0]))"},
  };
  for (const auto& [list, message] : cases) RequireError(SceneWith(std::string("\"fluids\": ") + list), message);
}

TEST_CASE("scene particles: every bad emitter value is named by its key path", "[scene][particles]") {
  const std::pair<const char*, const char*> cases[] = {
      {R"([{"position": [0, 0], "rat": 5}])", R"(emitters[0]: unknown key "rat" (did you mean "rate"?))"},
      {R"([{"rate": 5}])", R"(emitters[0]: needs a "position" [x, y] (or a "body" to ride on))"},
      {R"([{"body": "crat"}])", R"(emitters[0].body: no body has the id "crat")"},
      {R"([{"position": [0, 0], "direction": "up"}])", "emitters[0].direction: must be a number"},
      {R"([{"position": [0, 0], "spread": -0.1}])", "emitters[0].spread: must be >= 0"},
      {R"([{"position": [0, 0], "speed": 1, "speed_spread": 2}])", "emitters[0].speed_spread: must not be larger than speed (1)"},
      {R"([{"position": [0, 0], "speed": 0.2}])",
       R"(emitters[0].speed: must be at least speed_spread (0.5, the default); give a smaller "speed_spread")"},
      {R"([{"position": [0, 0], "rate": -1}])", "emitters[0].rate: must be >= 0"},
      {R"([{"position": [0, 0], "lifetime": 0}])", "emitters[0].lifetime: must be > 0"},
      {R"([{"position": [0, 0], "lifetime": 0.1}])",
       R"(emitters[0].lifetime: must be at least lifetime_spread (0.3, the default); give a smaller "lifetime_spread")"},
      {R"([{"position": [0, 0], "lifetime": 1, "lifetime_spread": 1.5}])",
       "emitters[0].lifetime_spread: must not be larger than lifetime (1)"},
      {R"([{"position": [0, 0], "size": [0.1]}])", "emitters[0].size: must be one value, or [start, end]"},
      {R"([{"position": [0, 0], "size": [0.1, -1]}])", "emitters[0].size[1]: must be >= 0"},
      {R"([{"position": [0, 0], "size": -1}])", "emitters[0].size: must be >= 0"},
      {R"([{"position": [0, 0], "color": "#ff8000f"}])",
       R"(emitters[0].color: must be a colour "#rgb", "#rgba", "#rrggbb" or "#rrggbbaa", got "#ff8000f")"},
      {R"([{"position": [0, 0], "color": ["#fff", 3]}])", "emitters[0].color[1]: must be a string"},
      {R"([{"position": [0, 0], "blend": "add"}])", R"(emitters[0].blend: unknown value "add" (expected one of "additive", "alpha"))"},
      {R"([{"position": [0, 0], "drag": -1}])", "emitters[0].drag: must be >= 0"},
      {R"([{"position": [0, 0], "buoyancy": true}])", "emitters[0].buoyancy: must be a number"},
      {R"([{"position": [0, 0], "restitution": -1}])", "emitters[0].restitution: must be >= 0"},
      {R"([{"position": [0, 0], "friction": -1}])", "emitters[0].friction: must be >= 0"},
      {R"([{"position": [0, 0], "collide": "yes"}])", "emitters[0].collide: must be true or false"},
      {R"([{"position": [0, 0], "seed": 1.5}])", "emitters[0].seed: must be a whole number from 0 to 1000000000"},
      {R"([{"position": [0, 0], "seed": -1}])", "emitters[0].seed: must be a whole number from 0 to 1000000000"},
      {R"([{"position": [0, 0], "max_particles": 0}])", "emitters[0].max_particles: must be a whole number from 1 to 1000000"},
      {R"([{"position": [0, 0], "max_particles": 600000}, {"position": [1, 0], "max_particles": 600000}])",
       "emitters[1].max_particles: takes the emitters' max_particles to 1200000, more than the limit of 1000000 effect "
       "particles alive at once (docs/limits.md)"},
      {R"([{"id": 7, "position": [0, 0]}])", "emitters[0].id: must be a string"},
  };
  for (const auto& [list, message] : cases) RequireError(SceneWith(std::string("\"emitters\": ") + list), message);
}

TEST_CASE("scene particles: bad particle settings, click keys and steps", "[scene][particles]") {
  const std::string soft = std::string(", \"soft_bodies\": [") + kCircle + "]";
  const std::pair<std::string, const char*> cases[] = {
      {R"("particles": 3)", "particles: must be an object"},
      {R"("particles": {"substeps": 2})", R"(particles: unknown key "substeps" (did you mean "substep"?))"},
      {R"("particles": {"substep": 0})", "particles.substep: must be > 0"},
      {R"("particles": {"iterations": 0})", "particles.iterations: must be a whole number from 1 to 1000"},
      {R"("particles": {"iterations": 2.5})", "particles.iterations: must be a whole number from 1 to 1000"},
      {R"("click": {"particle_radius": 0})", "click.particle_radius: must be > 0"},
      {R"("click": {"particle_speed": -1})", "click.particle_speed: must be >= 0"},
      {R"("click": {"particle_sped": 1})", R"(click: unknown key "particle_sped" (did you mean "particle_speed"?))"},
      {R"("particles": {"substep": 1e-6})" + soft,
       "particles.substep: makes 16667 particle substeps a step (dt / particles.substep), more than the limit of 1000 "
       "(docs/limits.md)"},
      {R"("dt": 5, "fluids": [{"region": [[0, 0], [1, 1]]}])",
       "dt: makes 2400 particle substeps a step (dt / particles.substep, 1/480 s by default), more than the limit of "
       "1000 (docs/limits.md)"},
      {R"("dt": 1e-10)" + soft, "dt: must be at least 1e-09 s in a scene with soft bodies or fluid (docs/limits.md)"},
      {R"("soft_budies": [])", R"(unknown key "soft_budies" (did you mean "soft_bodies"?))"},
      {R"("fluid": [])", R"(unknown key "fluid" (did you mean "fluids"?))"},
  };
  for (const auto& [rest, message] : cases) RequireError(SceneWith(rest), message);
  // Settings with nothing to step, and the most substeps and passes a step, are fine.
  RequireParsed(SceneWith(R"("dt": 5, "particles": {"substep": 1e-6})"));
  RequireParsed(SceneWith(R"("dt": 0.1, "particles": {"substep": 1e-4, "iterations": 1000})" + soft));
}

TEST_CASE("scene particles: the list limits, from both sides", "[scene][particles][limits]") {
  const auto many = [](const std::string& item, std::size_t n) {
    std::string list = "[";
    for (std::size_t i = 0; i < n; ++i) list += (i ? ", " : "") + item;
    return list + "]";
  };
  const std::string soft = R"({"shape": "circle", "radius": 0.15, "position": [0, 0]})";
  CHECK(RequireParsed(SceneWith("\"soft_bodies\": " + many(soft, 10000))).soft_bodies.size() == 10000);
  RequireError(SceneWith("\"soft_bodies\": " + many(soft, 10001)),
               "soft_bodies: 10001 soft bodies, more than the limit of 10000 (docs/limits.md)");
  const std::string emitter = R"({"position": [0, 0], "max_particles": 100})";
  CHECK(RequireParsed(SceneWith("\"emitters\": " + many(emitter, 10000))).emitters.size() == 10000);
  RequireError(SceneWith("\"emitters\": " + many(emitter, 10001)),
               "emitters: 10001 emitters, more than the limit of 10000 (docs/limits.md)");
  // A million effect particles alive at once, and a million soft-body and fluid particles.
  RequireParsed(SceneWith(R"("emitters": [{"position": [0, 0], "max_particles": 400000},
                                          {"position": [1, 0], "max_particles": 600000}])"));
  const game::Scene full = RequireParsed(SceneWith(R"("fluids": [{"region": [[0, 0], [999, 1000]], "spacing": 1},
    {"region": [[0, 2000], [1000, 2001]]}])"));
  CHECK(full.fluids[0].particles + full.fluids[1].particles == 1000000);
  RequireError(SceneWith(R"("fluids": [{"region": [[0, 0], [999, 1000]], "spacing": 1}],
                            "soft_bodies": [{"shape": "box", "size": [40, 30], "position": [0, -40], "spacing": 1}])"),
               "fluids[0]: makes 999000 particles, which takes the scene's soft-body and fluid particles to 1000200, more "
               "than the limit of 1000000 (docs/limits.md)");  // after the soft box's 40 × 30
}

// --- What BuildWorld makes.

TEST_CASE("scene particles: BuildWorld makes the soft bodies, fluids and emitters in file order",
          "[scene][particles]") {
  const game::Scene scene = RequireParsed(SceneWith(R"(
    "particles": {"substep": 0.005, "iterations": 2},
    "soft_bodies": [{"shape": "box", "size": [0.6, 0.3], "position": [3, 1.1], "attach_to": "crate"},
                    {"shape": "circle", "radius": 0.3, "position": [0, 3], "spacing": 0.05}],
    "fluids": [{"region": [[-4, 0], [-3, 0.5]], "spacing": 0.1}, {"region": [[4, 0], [4.35, 0.2]], "density": 500}],
    "emitters": [{"position": [1, 1], "rate": 10}, {"body": "crate", "seed": 3}])"));
  engine::World world = game::BuildWorld(scene);
  CHECK(world.Def().particles.substep == 0.005);
  CHECK(world.Def().particles.iterations == 2);
  REQUIRE(world.SoftBodyIds().size() == 2);
  for (std::size_t i = 0; i < 2; ++i) {
    CHECK(world.SoftBodyIds()[i].index == i);
    CHECK(world.GetSoftBodyDef(world.SoftBodyIds()[i]).spacing == scene.soft_bodies[i].def.spacing);
    CHECK(world.SoftBodyPositions(world.SoftBodyIds()[i]).size() == game::SoftBodyParticleCount(scene.soft_bodies[i].def));
  }
  // A 0.6 × 0.3 box at 0.1: the lattice half a spacing in, 5 × 2 cells.
  CHECK(world.SoftBodyPositions(world.SoftBodyIds()[0]).size() == 6 * 3);
  CHECK(world.FluidPositions().size() == 50 + 3 * 2);
  CHECK(scene.fluids[0].particles == 50);
  CHECK(scene.fluids[1].particles == 6);
  CHECK(world.FluidRestDensities()[49] == 1000.0);
  CHECK(world.FluidRestDensities()[50] == 500.0);
  REQUIRE(world.EmitterIds().size() == 2);
  CHECK(world.GetEmitterDef(world.EmitterIds()[0]).rate == 10.0);
  CHECK(world.GetEmitterDef(world.EmitterIds()[1]).body->index == 1);
  for (int step = 0; step < 30; ++step) world.Step();
  CHECK_FALSE(world.Fault().has_value());
}

TEST_CASE("scene particles: the counts the loader takes are the particles the engine makes", "[scene][particles]") {
  // Blocks of many sizes, places and spacings, some a hair over or under a whole number of
  // spacings: FluidParticleCount must follow AddFluid's own loop exactly.
  const double spacings[] = {0.05, 0.1, 0.03, 1.0 / 3.0, 0.07};
  int checked = 0;
  for (const double s : spacings) {
    engine::World world{engine::WorldDef{}};
    std::size_t total = 0;
    for (int k = 0; k < 12; ++k) {
      engine::FluidDef def;
      def.spacing = s;
      const double x0 = -3.7 + 1.3 * k, y0 = 0.1 * k - 0.45;
      const double w = s * (1 + k) + (k % 3 == 0 ? 1e-12 : k % 3 == 1 ? -1e-12 : 0.37 * s);
      const double h = s * (2 + k / 2) + (k % 2 ? 3e-13 : -3e-13);
      def.region = {{x0, y0}, {x0 + w, y0 + h}};
      const std::size_t expected = game::FluidParticleCount(def);
      if (expected == 0) continue;
      const std::size_t made = world.AddFluid(def);
      CHECK(made == expected);
      total += made;
      ++checked;
    }
    CHECK(world.FluidPositions().size() == total);
  }
  CHECK(checked > 40);
  for (const double s : spacings) {
    for (const double size : {0.35, 0.5, 1.0, 1.7, 2.0 / 3.0}) {
      if (!(size > s)) continue;
      engine::World world{engine::WorldDef{}};
      engine::SoftBodyDef circle;
      circle.shape = {engine::ShapeType::kCircle, size, {}};
      circle.spacing = s;
      CHECK(world.SoftBodyPositions(world.CreateSoftBody(circle)).size() == game::SoftBodyParticleCount(circle));
      engine::SoftBodyDef box = circle;
      box.shape = {engine::ShapeType::kBox, 0, {0.5 * size, 0.25 * size + s}};
      CHECK(world.SoftBodyPositions(world.CreateSoftBody(box)).size() == game::SoftBodyParticleCount(box));
    }
  }
}

// --- Through the program.

TEST_CASE("ballbox sim: a bad particle scene is exit 2, one line naming the file and key path, nothing written",
          "[scene][particles][exe]") {
  const fs::path dir = testing::FreshTestDir("scene_particles", "bad");
  const std::pair<const char*, const char*> cases[] = {
      {R"("soft_bodies": [{"shape": "circle", "radius": 0.5, "position": [0, 0]}, {"shape": "circle", "radius": 0.5, "position": [2, 0], "spacing": 0}])",
       "soft_bodies[1].spacing: must be > 0"},
      {R"("fluids": [{"region": [[0, 0], [1, 1]], "densty": 1000}])", R"(fluids[0]: unknown key "densty" (did you mean "density"?))"},
      {R"("emitters": [{"position": [0, 0], "color": ["#ff8000ff", "#ff000g00"]}])",
       R"(emitters[0].color[1]: must be a colour "#rgb", "#rgba", "#rrggbb" or "#rrggbbaa", got "#ff000g00")"},
      {R"("particles": {"iterations": 0})", "particles.iterations: must be a whole number from 1 to 1000"},
  };
  int index = 0;
  for (const auto& [rest, message] : cases) {
    const std::string name = "bad" + std::to_string(index++) + ".json";
    {
      std::ofstream(dir / name) << SceneWith(rest);
    }
    const testing::ProgramRun run = testing::Ballbox("sim " + name + " --steps 10 --dump out.csv", dir);
    INFO(name);
    CHECK(run.exit_code == 2);
    CHECK(run.out.empty());
    CHECK(run.err == "error: " + name + ": " + message + "\n");
    CHECK_FALSE(fs::exists(dir / "out.csv"));
    CHECK_FALSE(fs::exists(dir / "out.particles.csv"));
  }
}
