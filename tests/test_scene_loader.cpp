// game::LoadScene: one test per error message (its input in tests/data/scene_*.json), defaults, every key.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "game/default_scene.h"
#include "game/scene.h"

namespace {

std::string DataPath(const std::string& name) { return std::string(BALLBOX_TEST_DATA) + "/" + name; }

// Loads tests/data/`file` and requires bad input whose message is the file's path, ": ", then `rest`.
void RequireSceneError(const std::string& file, const std::string& rest) {
  const std::string path = DataPath(file);
  const game::Expected<game::Scene> scene = game::LoadScene(path);
  REQUIRE_FALSE(scene.HasValue());
  CHECK(scene.Error().exit_code == 2);
  CHECK(scene.Error().message == path + ": " + rest);
}

// Syntax errors read `path:LINE:COLUMN: reason`.
void RequireSyntaxError(const std::string& file, const std::string& line_column, const std::string& reason) {
  const std::string path = DataPath(file);
  const game::Expected<game::Scene> scene = game::LoadScene(path);
  REQUIRE_FALSE(scene.HasValue());
  CHECK(scene.Error().exit_code == 2);
  CHECK(scene.Error().message == path + ":" + line_column + ": " + reason);
}

game::Scene RequireScene(const std::string& path) {
  game::Expected<game::Scene> scene = game::LoadScene(path);
  if (!scene.HasValue()) FAIL(scene.Error().message);
  return scene.Value();
}

bool SameColor(render::Color c, int r, int g, int b) { return c.r == r && c.g == g && c.b == b; }

constexpr double kPi = 3.14159265358979323846;

}  // namespace

// --- Syntax errors: LINE:COLUMN of the character at fault, counted by hand in the file.

TEST_CASE("scene syntax error: trailing comma in an object names its line and column", "[scene]") {
  // Line 4, column 61 is the "}" after "[0, 1], ".
  RequireSyntaxError("scene_syntax_trailing_comma.json", "4:61",
                     "syntax error while parsing object key - unexpected '}'; expected string literal");
}

TEST_CASE("scene syntax error: missing comma between bodies names its line and column", "[scene]") {
  // Line 4, column 5 is the "{" of the second body.
  RequireSyntaxError("scene_syntax_missing_comma.json", "4:5",
                     "syntax error while parsing array - unexpected '{'; expected ']'");
}

TEST_CASE("scene syntax error: unterminated file points just past its end", "[scene]") {
  // The file ends after 60 characters on line 3, with no newline.
  RequireSyntaxError("scene_syntax_unterminated.json", "3:61",
                     "syntax error while parsing array - unexpected end of input; expected ']'");
}

TEST_CASE("scene syntax error: an empty file is 1:1", "[scene]") {
  RequireSyntaxError(
      "scene_empty_file.json", "1:1",
      "syntax error while parsing value - unexpected end of input; expected '[', '{', or a literal");
}

// --- Unknown keys, with a suggestion when one is close.

TEST_CASE("scene unknown key at the top level suggests the key meant", "[scene]") {
  RequireSceneError("scene_unknown_key_top.json", "unknown key \"gravty\" (did you mean \"gravity\"?)");
}

TEST_CASE("scene unknown key in a body names the body", "[scene]") {
  RequireSceneError("scene_unknown_key_body.json",
                    "bodies[1]: unknown key \"raduis\" (did you mean \"radius\"?)");
}

TEST_CASE("scene unknown key with nothing close has no suggestion", "[scene]") {
  RequireSceneError("scene_unknown_key_no_suggestion.json", "bodies[0]: unknown key \"wobble\"");
}

TEST_CASE("scene unknown key in camera", "[scene]") {
  RequireSceneError("scene_unknown_key_camera.json",
                    "camera: unknown key \"centre\" (did you mean \"center\"?)");
}

TEST_CASE("scene unknown key in click", "[scene]") {
  RequireSceneError("scene_unknown_key_click.json",
                    "click: unknown key \"max_impluse\" (did you mean \"max_impulse\"?)");
}

TEST_CASE("scene unknown key in solver", "[scene]") {
  RequireSceneError("scene_unknown_key_solver.json",
                    "solver: unknown key \"iteration\" (did you mean \"iterations\"?)");
}

TEST_CASE("scene unknown key with a newline in it still gives a one-line message", "[scene]") {
  // Echoed keys are quoted as JSON strings, so "x\ny" stays on one line as "x\\ny".
  const game::Expected<game::Scene> scene = game::LoadScene(DataPath("scene_unknown_key_newline.json"));
  REQUIRE_FALSE(scene.HasValue());
  CHECK(scene.Error().message.find("unknown key") != std::string::npos);
  CHECK(scene.Error().message.find('\n') == std::string::npos);
}

// --- Values of the wrong kind.

TEST_CASE("scene number too large for a double is bad input naming its line, column and key",
          "[scene]") {
  // JSON has no infinity; 1e999 is how a non-finite number reaches the loader. nlohmann reports
  // it as out_of_range 406 with no position; the loader's own parse names where it stands.
  const std::string path = DataPath("scene_non_finite.json");
  game::Expected<game::Scene> scene{game::Failure{}};
  REQUIRE_NOTHROW(scene = game::LoadScene(path));
  REQUIRE_FALSE(scene.HasValue());
  CHECK(scene.Error().exit_code == 2);
  // Line 3, column 36 is the "1" of 1e999, counted by hand in the file.
  CHECK(scene.Error().message == path + ":3:36: bodies[0].radius: the number 1e999 is too large for "
                                        "a double (at most about 1.8e308)");
}

TEST_CASE("scene number too large under a key with a newline: the path quotes the key, one line",
          "[scene]") {
  // Found by fuzz_scene: the key path of an overflowing number held the raw key, newline and all.
  const std::string text = "{\"x\\ndies\": [{\"radius\": 1e999}]}";
  const game::Expected<game::Scene> scene = game::ParseScene(text, "key.json", "key");
  REQUIRE_FALSE(scene.HasValue());
  CHECK(scene.Error().message ==
        "key.json:1:25: \"x\\ndies\"[0].radius: the number 1e999 is too large for a double (at most about 1.8e308)");
}

TEST_CASE("scene error: a key given twice in one object names where", "[scene]") {
  // JSON parsers keep the later value silently; a scene would then run with a value the user
  // may not be looking at.
  RequireSceneError("scene_duplicate_key.json",
                    "bodies[1]: duplicate key \"radius\" (each key may appear once in an object)");
  RequireSceneError("scene_duplicate_top_key.json",
                    "duplicate key \"gravity\" (each key may appear once in an object)");
  RequireSceneError("scene_duplicate_nested_key.json",
                    "camera: duplicate key \"width\" (each key may appear once in an object)");
  // Among thousands of keys in one object (the search must not grow quadratic), the repeat is
  // still found.
  std::string many = "{";
  for (int i = 0; i < 50000; ++i) many += "\"k" + std::to_string(i) + "\": 0, ";
  many += "\"k49999\": 1}";
  const game::Expected<game::Scene> crowded = game::ParseScene(many, "many.json", "many");
  REQUIRE_FALSE(crowded.HasValue());
  CHECK(crowded.Error().message ==
        "many.json: duplicate key \"k49999\" (each key may appear once in an object)");
  // The same key in different objects is fine.
  const game::Expected<game::Scene> twice = game::ParseScene(
      R"({"bodies": [{"shape": "circle", "radius": 1, "position": [0, 0]},
                     {"shape": "circle", "radius": 2, "position": [3, 0]}]})", "s.json", "s");
  REQUIRE(twice.HasValue());
  CHECK(twice.Value().bodies[1].def.shape.radius == 2);
}

TEST_CASE("scene string where a number belongs", "[scene]") {
  RequireSceneError("scene_not_number.json", "bodies[0].radius: must be a number");
}

TEST_CASE("scene bool where a number belongs", "[scene]") {
  RequireSceneError("scene_bool_as_number.json", "dt: must be a number");
}

TEST_CASE("scene vector of the wrong length", "[scene]") {
  RequireSceneError("scene_array_length.json", "gravity: must be an array of 2 numbers");
}

TEST_CASE("scene vector element that is not a number names its index", "[scene]") {
  RequireSceneError("scene_array_element.json", "bodies[0].position[1]: must be a number");
}

TEST_CASE("scene string where a bool belongs", "[scene]") {
  RequireSceneError("scene_bad_bool.json", "bodies[0].static: must be true or false");
}

TEST_CASE("scene number where a string belongs", "[scene]") {
  RequireSceneError("scene_bad_string.json", "bodies[0].id: must be a string");
}

TEST_CASE("scene solver that is not an object", "[scene]") {
  RequireSceneError("scene_solver_not_object.json", "solver: must be an object");
}

TEST_CASE("scene camera that is not an object", "[scene]") {
  RequireSceneError("scene_camera_not_object.json", "camera: must be an object");
}

TEST_CASE("scene body that is not an object", "[scene]") {
  RequireSceneError("scene_body_not_object.json", "bodies[0]: must be an object");
}

// --- Ranges.

TEST_CASE("scene zero radius names the body by index", "[scene]") {
  RequireSceneError("scene_bad_radius.json", "bodies[2].radius: must be > 0");
}

TEST_CASE("scene negative radius", "[scene]") {
  RequireSceneError("scene_negative_radius.json", "bodies[0].radius: must be > 0");
}

TEST_CASE("scene zero box width", "[scene]") {
  RequireSceneError("scene_bad_width.json", "bodies[0].size[0]: must be > 0");
}

TEST_CASE("scene negative box height", "[scene]") {
  RequireSceneError("scene_bad_height.json", "bodies[0].size[1]: must be > 0");
}

TEST_CASE("scene zero mass", "[scene]") {
  RequireSceneError("scene_bad_mass.json", "bodies[1].mass: must be > 0");
}

TEST_CASE("scene negative density", "[scene]") {
  RequireSceneError("scene_bad_density.json", "bodies[0].density: must be > 0");
}

TEST_CASE("scene zero dt", "[scene]") { RequireSceneError("scene_zero_dt.json", "dt: must be > 0"); }

TEST_CASE("scene negative restitution", "[scene]") {
  RequireSceneError("scene_negative_restitution.json", "bodies[0].restitution: must be >= 0");
}

TEST_CASE("scene negative click impulse", "[scene]") {
  RequireSceneError("scene_negative_max_impulse.json", "click.max_impulse: must be >= 0");
}

TEST_CASE("scene solver iterations that are not whole", "[scene]") {
  RequireSceneError("scene_iterations_fraction.json",
                    "solver.iterations: must be a whole number from 1 to 1000");
}

TEST_CASE("scene solver iterations above 1000", "[scene]") {
  RequireSceneError("scene_iterations_too_many.json",
                    "solver.iterations: must be a whole number from 1 to 1000");
}

TEST_CASE("scene solver method that does not exist", "[scene]") {
  RequireSceneError("scene_unknown_solver_method.json",
                    "solver.method: unknown value \"soft\" (expected one of \"substep\", \"sequential_impulse\", \"seed\")");
}

TEST_CASE("scene solver substeps of 0", "[scene]") {
  RequireSceneError("scene_substeps_zero.json", "solver.substeps: must be > 0");
}

TEST_CASE("scene sleep that is not true or false", "[scene]") {
  RequireSceneError("scene_sleep_not_bool.json", "sleep: must be true or false");
}

TEST_CASE("scene solver iterations of 0", "[scene]") {
  RequireSceneError("scene_iterations_zero.json", "solver.iterations: must be > 0");
}

TEST_CASE("scene position correction above 1", "[scene]") {
  RequireSceneError("scene_position_correction_above_one.json",
                    "solver.position_correction: must be from 0 to 1");
}

// --- Rules between keys.

TEST_CASE("scene mass and density together", "[scene]") {
  RequireSceneError("scene_mass_and_density.json", "bodies[0]: give \"mass\" or \"density\", not both");
}

TEST_CASE("scene duplicate explicit id names both bodies", "[scene]") {
  RequireSceneError("scene_duplicate_id.json", "bodies[2].id: duplicate id \"ball\" (also bodies[0])");
}

TEST_CASE("scene explicit id clashing with an earlier default id", "[scene]") {
  RequireSceneError("scene_duplicate_default_id.json",
                    "bodies[1].id: duplicate id \"body0\" (also bodies[0])");
}

TEST_CASE("scene default id clashing with an earlier explicit id names the body, not a missing key",
          "[scene]") {
  // bodies[1] has no "id" key; its default "body1" is taken by bodies[0]. The message points at
  // bodies[1] itself, not at a "bodies[1].id" key that is not in the file.
  const std::string path = DataPath("scene_duplicate_default_id_later.json");
  const game::Expected<game::Scene> scene = game::LoadScene(path);
  REQUIRE_FALSE(scene.HasValue());
  const std::string& message = scene.Error().message;
  CHECK(message.rfind(path + ": bodies[1]: ", 0) == 0);
  CHECK(message.find("\"body1\"") != std::string::npos);
  CHECK(message.find("bodies[0]") != std::string::npos);
}

TEST_CASE("scene unknown shape lists the shapes", "[scene]") {
  RequireSceneError("scene_unknown_shape.json",
                    "bodies[0].shape: unknown value \"triangle\" (expected one of \"circle\", \"box\", "
                    "\"polygon\", \"capsule\", \"segment\")");
}

TEST_CASE("scene body without a shape", "[scene]") {
  RequireSceneError("scene_missing_shape.json",
                    "bodies[0]: needs a \"shape\" (\"circle\", \"box\", \"polygon\", \"capsule\" or "
                    "\"segment\") or \"shapes\" (a list of them)");
}

TEST_CASE("scene circle without a radius", "[scene]") {
  RequireSceneError("scene_missing_radius.json", "bodies[0]: a circle needs a \"radius\"");
}

TEST_CASE("scene box without a size", "[scene]") {
  RequireSceneError("scene_missing_size.json", "bodies[0]: a box needs a \"size\" [width, height]");
}

TEST_CASE("scene body without a position", "[scene]") {
  RequireSceneError("scene_missing_position.json", "bodies[0]: needs a \"position\" [x, y]");
}

TEST_CASE("scene radius on a box", "[scene]") {
  RequireSceneError("scene_radius_on_box.json",
                    "bodies[0].radius: applies to circles, capsules and polygons only; a box has a \"size\"");
}

TEST_CASE("scene size on a circle", "[scene]") {
  RequireSceneError("scene_size_on_circle.json",
                    "bodies[0].size: applies to boxes only; a circle has a \"radius\"");
}

TEST_CASE("scene static body with a mass", "[scene]") {
  RequireSceneError("scene_static_mass.json",
                    "bodies[0].mass: a static body takes no mass, density or velocity");
}

TEST_CASE("scene static body with a density", "[scene]") {
  RequireSceneError("scene_static_density.json",
                    "bodies[0].density: a static body takes no mass, density or velocity");
}

TEST_CASE("scene static body with a velocity", "[scene]") {
  RequireSceneError("scene_static_velocity.json",
                    "bodies[0].velocity: a static body takes no mass, density or velocity");
}

TEST_CASE("scene body both static and kinematic", "[scene][kinematic]") {
  RequireSceneError("scene_static_kinematic.json", "bodies[1].kinematic: a body cannot be both static and kinematic");
}

TEST_CASE("scene kinematic body with a mass or a density", "[scene][kinematic]") {
  RequireSceneError("scene_kinematic_mass.json",
                    "bodies[0].mass: a kinematic body takes no mass or density (nothing pushes it)");
  RequireSceneError("scene_kinematic_density.json",
                    "bodies[0].density: a kinematic body takes no mass or density (nothing pushes it)");
}

TEST_CASE("scene kinematic that is not true or false", "[scene][kinematic]") {
  RequireSceneError("scene_kinematic_bad_bool.json", "bodies[0].kinematic: must be true or false");
}

TEST_CASE("scene kinematic angular velocity without rotation", "[scene][kinematic]") {
  RequireSceneError("scene_kinematic_angular_without_rotation.json",
                    "bodies[0].angular_velocity: needs \"rotation\": true in the scene");
}

TEST_CASE("scene angle without rotation", "[scene]") {
  RequireSceneError("scene_angle_without_rotation.json",
                    "bodies[1].angle: needs \"rotation\": true in the scene");
}

TEST_CASE("scene angular velocity without rotation", "[scene]") {
  RequireSceneError("scene_angular_velocity_without_rotation.json",
                    "bodies[0].angular_velocity: needs \"rotation\": true in the scene");
}

TEST_CASE("scene colour of the wrong length", "[scene]") {
  RequireSceneError("scene_bad_color_length.json",
                    "bodies[0].color: must be a colour \"#rgb\" or \"#rrggbb\", got \"#12345\"");
}

TEST_CASE("scene colour with a non-hex digit", "[scene]") {
  RequireSceneError("scene_bad_color_digit.json",
                    "bodies[0].color: must be a colour \"#rgb\" or \"#rrggbb\", got \"#12g\"");
}

TEST_CASE("scene unknown integrator lists the integrators", "[scene]") {
  RequireSceneError(
      "scene_unknown_integrator.json",
      "integrator: unknown value \"leapfrog\" (expected one of \"semi_implicit_euler\", "
      "\"explicit_euler\", \"velocity_verlet\", \"midpoint\", \"rk4\")");
}

TEST_CASE("scene unknown broad phase lists the broad phases", "[scene]") {
  RequireSceneError(
      "scene_unknown_broad_phase.json",
      "broad_phase: unknown value \"grid\" (expected one of \"auto\", \"all_pairs\", \"sweep_and_prune\", "
      "\"uniform_grid\", \"quadtree\", \"aabb_tree\")");
}

TEST_CASE("scene broad_phase names every broad phase", "[scene]") {
  const std::pair<const char*, engine::BroadPhaseType> names[] = {
      {"auto", engine::BroadPhaseType::kAuto},
      {"all_pairs", engine::BroadPhaseType::kAllPairs},
      {"sweep_and_prune", engine::BroadPhaseType::kSweepAndPrune},
      {"uniform_grid", engine::BroadPhaseType::kUniformGrid},
      {"quadtree", engine::BroadPhaseType::kQuadtree},
      {"aabb_tree", engine::BroadPhaseType::kAabbTree},
  };
  for (const auto& [name, type] : names) {
    const std::string json = std::string(R"({"broad_phase": ")") + name + R"(", "bodies": []})";
    const game::Expected<game::Scene> scene = game::ParseScene(json, "<test>", "test");
    INFO(name);
    REQUIRE(scene.HasValue());
    CHECK(scene.Value().world.broad_phase == type);
  }
}

// --- Structure.

TEST_CASE("scene without bodies", "[scene]") {
  RequireSceneError("scene_missing_bodies.json", "a scene needs \"bodies\" (an array)");
}

TEST_CASE("scene whose bodies are not an array", "[scene]") {
  RequireSceneError("scene_bodies_not_array.json", "bodies: must be an array");
}

TEST_CASE("scene whose root is not an object", "[scene]") {
  RequireSceneError("scene_root_array.json", "a scene must be a JSON object");
}

TEST_CASE("scene empty name", "[scene]") {
  RequireSceneError("scene_empty_name.json", "name: must not be empty");
}

TEST_CASE("scene empty id", "[scene]") {
  RequireSceneError("scene_empty_id.json", "bodies[0].id: must not be empty");
}

TEST_CASE("scene file that does not exist", "[scene]") {
  RequireSceneError("scene_does_not_exist.json", "cannot open: No such file or directory");
}

TEST_CASE("scene path that is a directory", "[scene]") {
  const std::string path = BALLBOX_TEST_DATA;
  const game::Expected<game::Scene> scene = game::LoadScene(path);
  REQUIRE_FALSE(scene.HasValue());
  CHECK(scene.Error().exit_code == 2);
  CHECK(scene.Error().message == path + ": is a directory, not a file");
}

// --- What loads, and the defaults the contract gives.

TEST_CASE("scene defaults: name, world, click, camera", "[scene]") {
  const game::Scene scene = RequireScene(DataPath("scene_defaults.json"));
  CHECK(scene.name == "scene_defaults");  // the file's stem
  CHECK(scene.world.gravity.x == 0.0);
  CHECK(scene.world.gravity.y == -9.8);
  CHECK(scene.world.dt == 1.0 / 60.0);
  CHECK_FALSE(scene.world.rotation);
  CHECK(scene.click_max_impulse == 10.0);
  CHECK_FALSE(scene.camera.center.has_value());
  CHECK_FALSE(scene.camera.width.has_value());
  // The project's own defaults (docs/scene-format.md).
  CHECK(scene.world.solver == engine::ContactSolver::kSubstep);
  CHECK(scene.world.substeps == 0);             // automatic: the world picks 4, or 8 with rotation
  CHECK(scene.world.velocity_iterations == 0);  // automatic too
  CHECK(game::BuildWorld(scene).Def().substeps == 4);
  CHECK(game::BuildWorld(scene).Def().velocity_iterations == 1);
  CHECK(scene.world.sleeping);
  CHECK(scene.world.restitution_threshold == 1.0);
}

TEST_CASE("scene defaults: a body's id, velocity, angle, material and colour", "[scene]") {
  const game::Scene scene = RequireScene(DataPath("scene_defaults.json"));
  REQUIRE(scene.bodies.size() == 3);
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const game::SceneBody& body = scene.bodies[i];
    CHECK(body.id == "body" + std::to_string(i));
    CHECK(body.def.velocity.x == 0.0);
    CHECK(body.def.velocity.y == 0.0);
    CHECK(body.def.angle == 0.0);
    CHECK(body.def.angular_velocity == 0.0);
    CHECK(body.def.restitution == 0.2);
    CHECK(body.def.friction == 0.3);
    CHECK_FALSE(body.def.fixed_rotation);
    CHECK_FALSE(body.def.bullet);
  }
  CHECK(scene.bodies[0].color == render::PaletteColor(0));
  CHECK(scene.bodies[1].color == render::PaletteColor(1));
  CHECK(scene.bodies[2].color == render::kStaticColor);
}

TEST_CASE("scene defaults: shapes and sizes", "[scene]") {
  const game::Scene scene = RequireScene(DataPath("scene_defaults.json"));
  REQUIRE(scene.bodies.size() == 3);
  CHECK(scene.bodies[0].def.shape.type == engine::ShapeType::kCircle);
  CHECK(scene.bodies[0].def.shape.radius == 0.5);
  CHECK(scene.bodies[1].def.shape.type == engine::ShapeType::kBox);
  CHECK(scene.bodies[1].def.shape.half_extents.x == 1.0);
  CHECK(scene.bodies[1].def.shape.half_extents.y == 1.5);
  CHECK(scene.bodies[1].def.position.x == 1.0);
  CHECK(scene.bodies[1].def.position.y == 2.0);
  CHECK(scene.bodies[2].def.is_static);
}

TEST_CASE("scene defaults: density 1 gives mass = area in the built world", "[scene]") {
  const game::Scene scene = RequireScene(DataPath("scene_defaults.json"));
  const engine::World world = game::BuildWorld(scene);
  REQUIRE(world.BodyCount() == 3);
  CHECK(world.Info({0}).mass == Approx(kPi * 0.5 * 0.5).epsilon(1e-14));
  CHECK(world.Info({0}).inv_mass == Approx(1.0 / (kPi * 0.25)).epsilon(1e-14));
  CHECK(world.Info({1}).mass == Approx(2.0 * 3.0).epsilon(1e-14));
  CHECK(world.Info({2}).inv_mass == 0.0);  // static: infinite mass
  CHECK(world.Info({2}).is_static);
  CHECK(world.State({0}).position.y == 1.0);
}

TEST_CASE("scene with every documented and extra key reads each value", "[scene]") {
  const game::Scene scene = RequireScene(DataPath("scene_every_key.json"));
  CHECK(scene.name == "every key");
  CHECK((scene.world.gravity.x == 1.5 && scene.world.gravity.y == -3.25));
  CHECK(scene.world.dt == 0.01);
  CHECK(scene.world.rotation);
  REQUIRE(scene.camera.center.has_value());
  CHECK((scene.camera.center->x == 2.0 && scene.camera.center->y == 4.5));
  CHECK(scene.camera.width == 12.0);
  CHECK(scene.click_max_impulse == 7.5);
  CHECK(scene.world.integrator == engine::Integrator::kExplicitEuler);
  CHECK(scene.world.broad_phase == engine::BroadPhaseType::kSweepAndPrune);
  CHECK(scene.world.velocity_iterations == 7);
  CHECK(scene.world.restitution_threshold == 0.5);
  CHECK(scene.world.linear_slop == 0.01);
  CHECK(scene.world.position_correction == 0.3);
  CHECK(scene.world.solver == engine::ContactSolver::kSequentialImpulse);
  CHECK(scene.world.substeps == 3);
  CHECK(scene.world.max_push_out_speed == 2.5);
  CHECK_FALSE(scene.world.sleeping);
}

TEST_CASE("scene with every key reads each body value", "[scene]") {
  const game::Scene scene = RequireScene(DataPath("scene_every_key.json"));
  REQUIRE(scene.bodies.size() == 3);
  const engine::BodyDef& ball = scene.bodies[0].def;
  CHECK(scene.bodies[0].id == "ball");
  CHECK(ball.shape.radius == 0.7);
  CHECK((ball.position.x == -1.0 && ball.position.y == 3.0));
  CHECK((ball.velocity.x == 2.0 && ball.velocity.y == -1.0));
  CHECK(ball.angle == 0.25);
  CHECK(ball.angular_velocity == -1.5);
  CHECK(ball.density == 4.0);
  CHECK(ball.restitution == 0.8);
  CHECK(ball.friction == 0.1);
  CHECK(ball.fixed_rotation);
  CHECK(ball.bullet);
  const engine::BodyDef& crate = scene.bodies[1].def;
  CHECK(scene.bodies[1].id == "crate");
  CHECK((crate.shape.half_extents.x == 0.5 && crate.shape.half_extents.y == 0.25));
  CHECK(crate.mass == 2.0);
  CHECK_FALSE(crate.is_static);
  const engine::BodyDef& floor = scene.bodies[2].def;
  CHECK(floor.is_static);
  CHECK(floor.restitution == 0.0);
  CHECK(floor.friction == 0.9);
}

TEST_CASE("scene kinematic bodies: read with their velocities, grey, moving at their own velocity",
          "[scene][kinematic]") {
  const game::Scene scene = RequireScene(DataPath("scene_kinematic.json"));
  REQUIRE(scene.bodies.size() == 5);
  const engine::BodyDef& platform = scene.bodies[1].def;
  CHECK(platform.is_kinematic);
  CHECK_FALSE(platform.is_static);
  CHECK((platform.velocity.x == 1.5 && platform.velocity.y == 0.25));
  CHECK(platform.angular_velocity == 0.5);
  CHECK(scene.bodies[2].def.is_kinematic);
  CHECK(scene.bodies[2].def.velocity.x == 0.0);
  CHECK_FALSE(scene.bodies[0].def.is_kinematic);  // the default
  CHECK_FALSE(scene.bodies[4].def.is_kinematic);  // given false
  // Nothing pushes them, as nothing pushes a static body: the same grey, unless given a colour.
  CHECK(scene.bodies[1].color == render::kStaticColor);
  CHECK(scene.bodies[2].color == render::kStaticColor);
  CHECK(SameColor(scene.bodies[3].color, 0xcc, 0x88, 0x44));
  CHECK(scene.bodies[4].color == render::PaletteColor(4));

  engine::World world = game::BuildWorld(scene);
  CHECK(world.Info({1}).is_kinematic);
  CHECK(world.Info({1}).inv_mass == 0.0);
  CHECK(world.Info({1}).inv_inertia == 0.0);
  for (int step = 0; step < 60; ++step) world.Step();
  const engine::BodyState& s = world.State({1});
  CHECK(s.position.x == Approx(-6 + 1.5).epsilon(1e-12));
  CHECK(s.position.y == Approx(3 + 0.25).epsilon(1e-12));
  CHECK(s.angle == Approx(0.5).epsilon(1e-12));
  CHECK(world.State({2}).position.x == 6.0);  // at rest, it stays
  CHECK(world.State({2}).position.y == 3.0);
  CHECK(world.State({3}).position.y == Approx(7.0).epsilon(1e-12));  // no gravity on it
}

TEST_CASE("scene colours #rgb and #rrggbb decode to bytes", "[scene]") {
  const game::Scene scene = RequireScene(DataPath("scene_every_key.json"));
  REQUIRE(scene.bodies.size() == 3);
  CHECK(SameColor(scene.bodies[0].color, 0xcc, 0x88, 0x44));  // "#c84"
  CHECK(SameColor(scene.bodies[1].color, 0x1a, 0x2b, 0x3c));  // "#1a2B3c", mixed case
  CHECK(SameColor(scene.bodies[2].color, 0xff, 0xff, 0xff));  // "#FFF"
}

TEST_CASE("scene with every key builds a world with the given masses", "[scene]") {
  const engine::World world = game::BuildWorld(RequireScene(DataPath("scene_every_key.json")));
  REQUIRE(world.BodyCount() == 3);
  CHECK(world.Info({0}).mass == Approx(4.0 * kPi * 0.7 * 0.7).epsilon(1e-14));
  CHECK(world.Info({1}).mass == 2.0);
  CHECK(world.Info({1}).inv_mass == 0.5);
  CHECK(world.Info({2}).inv_mass == 0.0);
  CHECK(world.Def().dt == 0.01);
}

TEST_CASE("scene limits that are allowed: 0 and 1 where the range is closed", "[scene]") {
  const game::Scene scene = RequireScene(DataPath("scene_limits.json"));
  CHECK(scene.click_max_impulse == 0.0);
  CHECK(scene.world.velocity_iterations == 1000);
  CHECK(scene.world.restitution_threshold == 0.0);
  CHECK(scene.world.linear_slop == 0.0);
  CHECK(scene.world.position_correction == 1.0);
  REQUIRE(scene.bodies.size() == 1);
  CHECK(scene.bodies[0].def.restitution == 0.0);
  CHECK(scene.bodies[0].def.friction == 0.0);
}

TEST_CASE("ParseScene uses the default name and the given label", "[scene]") {
  const game::Expected<game::Scene> good = game::ParseScene(R"({"bodies": []})", "label.json", "fallback");
  REQUIRE(good.HasValue());
  CHECK(good.Value().name == "fallback");
  const game::Expected<game::Scene> bad = game::ParseScene(R"({"bodies": 3})", "label.json", "fallback");
  REQUIRE_FALSE(bad.HasValue());
  CHECK(bad.Error().message == "label.json: bodies: must be an array");
}

TEST_CASE("every scene in assets/ loads, and so does the embedded default", "[scene]") {
  std::vector<std::string> paths = {std::string(BALLBOX_ASSETS) + "/default.json"};
  const std::filesystem::path scenes = std::filesystem::path(BALLBOX_ASSETS) / "scenes";
  if (std::filesystem::is_directory(scenes)) {
    for (const auto& entry : std::filesystem::directory_iterator(scenes)) {
      if (entry.path().extension() == ".json") paths.push_back(entry.path().string());
    }
  }
  for (const std::string& path : paths) {
    INFO(path);
    const game::Expected<game::Scene> scene = game::LoadScene(path);
    CHECK(scene.HasValue());
    if (!scene.HasValue()) FAIL_CHECK(scene.Error().message);
  }
  const game::Expected<game::Scene> embedded =
      game::ParseScene(game::DefaultSceneJson(), "<default>", "default");
  REQUIRE(embedded.HasValue());
  CHECK(embedded.Value().name == "default");
  CHECK_FALSE(embedded.Value().bodies.empty());
}

TEST_CASE("scene solver method names the sequential-impulse solver, and \"seed\" as its old name",
          "[scene]") {
  for (const char* name : {"sequential_impulse", "seed"}) {
    const std::string json = std::string(R"({"solver": {"method": ")") + name +
                             R"("}, "bodies": [{"shape": "circle", "radius": 1, "position": [0, 0]}]})";
    const game::Expected<game::Scene> scene = game::ParseScene(json, "<test>", "test");
    INFO(name);
    REQUIRE(scene.HasValue());
    CHECK(scene.Value().world.solver == engine::ContactSolver::kSequentialImpulse);
  }
}
