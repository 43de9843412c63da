// game::ParseScene for the `joints` list (contract: "More shapes, compound bodies and joints"):
// each key read into the engine::JointDef expected by hand, each bad input named by its key path,
// and, through BuildWorld and the program, joints that hold their bodies as the keys say.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "game/scene.h"
#include "run_program.h"

namespace {

using engine::JointType;
using engine::Vec2;

std::string DataPath(const std::string& name) { return std::string(BALLBOX_TEST_DATA) + "/" + name; }

// Bodies of every kind, for joints to name: two static, two dynamic (one by its default id
// "body2"), a kinematic one and one that never turns.
const char* kBodies = R"([
  {"id": "floor", "shape": "box", "size": [10, 1], "position": [0, -0.5], "static": true},
  {"id": "a", "shape": "box", "size": [1, 1], "position": [0, 2]},
  {"shape": "circle", "radius": 0.5, "position": [3, 2]},
  {"id": "lift", "shape": "box", "size": [1, 0.2], "position": [5, 0], "kinematic": true},
  {"id": "wall", "shape": "box", "size": [0.2, 3], "position": [-5, 1.5], "static": true},
  {"id": "slider", "shape": "box", "size": [1, 1], "position": [2, 5], "fixed_rotation": true}])";

// A scene of kBodies and the given joints (JSON array text).
std::string SceneWithJoints(const std::string& joints, bool rotation = true) {
  return std::string("{\"rotation\": ") + (rotation ? "true" : "false") + ", \"bodies\": " + kBodies +
         ", \"joints\": " + joints + "}";
}

// A scene of kBodies and one joint (JSON object text).
std::string SceneWithJoint(const std::string& joint, bool rotation = true) {
  return SceneWithJoints("[" + joint + "]", rotation);
}

game::Scene RequireParsed(const std::string& json) {
  game::Expected<game::Scene> scene = game::ParseScene(json, "joints.json", "joints");
  if (!scene.HasValue()) FAIL(scene.Error().message);
  return scene.Value();
}

engine::JointDef OnlyJoint(const std::string& joint, bool rotation = true) {
  const game::Scene scene = RequireParsed(SceneWithJoint(joint, rotation));
  REQUIRE(scene.joints.size() == 1);
  return scene.joints[0].def;
}

// Bad input whose message is "joints.json: " then exactly `rest`.
void RequireError(const std::string& json, const std::string& rest) {
  const game::Expected<game::Scene> scene = game::ParseScene(json, "joints.json", "joints");
  INFO(json);
  REQUIRE_FALSE(scene.HasValue());
  CHECK(scene.Error().exit_code == 2);
  CHECK(scene.Error().message == "joints.json: " + rest);
}

void RequireJointError(const std::string& joint, const std::string& rest, bool rotation = true) {
  RequireError(SceneWithJoint(joint, rotation), rest);
}

bool Same(Vec2 a, Vec2 b) { return a.x == b.x && a.y == b.y; }

bool IsBody(engine::BodyId id, engine::BodyIndex index) { return id.index == index && id.generation == 0; }

}  // namespace

// --- Each key lands in the JointDef.

TEST_CASE("scene joints: a revolute joint with only its required keys", "[scene][joints]") {
  const game::Scene scene = RequireParsed(SceneWithJoint(
      R"({"type": "revolute", "bodies": ["floor", "a"], "anchor": [0.5, 1.5]})"));
  REQUIRE(scene.joints.size() == 1);
  const game::SceneJoint& joint = scene.joints[0];
  CHECK(joint.id == "joint0");
  CHECK_FALSE(joint.id_given);
  const engine::JointDef& def = joint.def;
  CHECK(def.type == JointType::kRevolute);
  CHECK(IsBody(def.body_a, 0));
  CHECK(IsBody(def.body_b, 1));
  CHECK(Same(def.anchor, {0.5, 1.5}));
  CHECK_FALSE(def.collide);
  CHECK_FALSE(def.limits.has_value());
  CHECK_FALSE(def.motor.has_value());
  CHECK_FALSE(def.spring.has_value());
  CHECK_FALSE(def.length.has_value());
  CHECK_FALSE(def.min_length.has_value());
  CHECK_FALSE(def.max_length.has_value());
}

TEST_CASE("scene joints: a revolute joint's limits, motor (max_torque), id and collide", "[scene][joints]") {
  const game::Scene scene = RequireParsed(SceneWithJoint(
      R"({"id": "elbow", "type": "revolute", "bodies": ["a", "body2"], "anchor": [1.5, 2], "collide": true,
          "limits": [-0.25, 1.5], "motor": {"speed": -2.5, "max_torque": 40}})"));
  const game::SceneJoint& joint = scene.joints.at(0);
  CHECK(joint.id == "elbow");
  CHECK(joint.id_given);
  CHECK(IsBody(joint.def.body_a, 1));
  CHECK(IsBody(joint.def.body_b, 2));  // the body without an id, by its default one
  CHECK(joint.def.collide);
  REQUIRE(joint.def.limits.has_value());
  CHECK(joint.def.limits->lower == -0.25);
  CHECK(joint.def.limits->upper == 1.5);
  REQUIRE(joint.def.motor.has_value());
  CHECK(joint.def.motor->speed == -2.5);
  CHECK(joint.def.motor->max_force == 40.0);
}

TEST_CASE("scene joints: a motor's speed defaults to 0 (a brake) and a limit may be a single angle",
          "[scene][joints]") {
  const engine::JointDef def = OnlyJoint(
      R"({"type": "revolute", "bodies": ["a", "body2"], "anchor": [1, 2], "limits": [0.5, 0.5],
          "motor": {"max_torque": 3}})");
  CHECK(def.limits->lower == 0.5);
  CHECK(def.limits->upper == 0.5);
  CHECK(def.motor->speed == 0.0);
  CHECK(def.motor->max_force == 3.0);
}

TEST_CASE("scene joints: a distance joint's anchors go to anchor and anchor_b; length is left to the engine",
          "[scene][joints]") {
  const engine::JointDef def =
      OnlyJoint(R"({"type": "distance", "bodies": ["wall", "a"], "anchors": [[-5, 3], [0, 2.5]]})");
  CHECK(def.type == JointType::kDistance);
  CHECK(IsBody(def.body_a, 4));
  CHECK(IsBody(def.body_b, 1));
  CHECK(Same(def.anchor, {-5, 3}));
  CHECK(Same(def.anchor_b, {0, 2.5}));
  // No length: the engine measures the anchors' distance when it makes the joint.
  CHECK_FALSE(def.length.has_value());
  CHECK_FALSE(def.min_length.has_value());
  CHECK_FALSE(def.max_length.has_value());
  CHECK_FALSE(def.spring.has_value());
}

TEST_CASE("scene joints: a distance joint's length, range and spring", "[scene][joints]") {
  const engine::JointDef def = OnlyJoint(
      R"({"type": "distance", "bodies": ["a", "body2"], "anchors": [[0, 2], [3, 2]], "length": 2.75,
          "min_length": 1, "max_length": 4.5, "spring": {"hertz": 3.5, "damping_ratio": 0.25}})");
  CHECK(*def.length == 2.75);
  CHECK(*def.min_length == 1.0);
  CHECK(*def.max_length == 4.5);
  REQUIRE(def.spring.has_value());
  CHECK(def.spring->hertz == 3.5);
  CHECK(def.spring->damping_ratio == 0.25);
}

TEST_CASE("scene joints: a rope is max_length alone; a spring's damping defaults to 0", "[scene][joints]") {
  const engine::JointDef rope = OnlyJoint(
      R"({"type": "distance", "bodies": ["floor", "a"], "anchors": [[0, 0], [0, 2]], "max_length": 3})");
  CHECK_FALSE(rope.min_length.has_value());
  CHECK(*rope.max_length == 3.0);
  const engine::JointDef spring = OnlyJoint(
      R"({"type": "distance", "bodies": ["floor", "a"], "anchors": [[0, 0], [0, 2]], "spring": {"hertz": 1}})");
  CHECK(spring.spring->hertz == 1.0);
  CHECK(spring.spring->damping_ratio == 0.0);
  // A spring may pull the anchors together, from wherever they start.
  const engine::JointDef zero = OnlyJoint(
      R"({"type": "distance", "bodies": ["floor", "a"], "anchors": [[0, 2], [0, 2]], "length": 0,
          "spring": {"hertz": 2}})");
  CHECK(*zero.length == 0.0);
  // A rope of 1 nm is the shortest.
  const engine::JointDef short_rope = OnlyJoint(
      R"({"type": "distance", "bodies": ["floor", "a"], "anchors": [[0, 0], [0, 2]], "max_length": 1e-9})");
  CHECK(*short_rope.max_length == 1e-9);
}

TEST_CASE("scene joints: a prismatic joint's anchor, axis (as written), limits and motor (max_force)",
          "[scene][joints]") {
  const engine::JointDef def = OnlyJoint(
      R"({"type": "prismatic", "bodies": ["floor", "slider"], "anchor": [2, 5], "axis": [0, 3],
          "limits": [-1, 2.5], "motor": {"speed": 0.75, "max_force": 120}})");
  CHECK(def.type == JointType::kPrismatic);
  CHECK(IsBody(def.body_a, 0));
  CHECK(IsBody(def.body_b, 5));
  CHECK(Same(def.anchor, {2, 5}));
  CHECK(Same(def.axis, {0, 3}));  // any length: the engine makes it a unit vector
  CHECK(def.limits->lower == -1.0);
  CHECK(def.limits->upper == 2.5);
  CHECK(def.motor->speed == 0.75);
  CHECK(def.motor->max_force == 120.0);
}

TEST_CASE("scene joints: a weld joint, rigid or soft", "[scene][joints]") {
  const engine::JointDef rigid = OnlyJoint(R"({"type": "weld", "bodies": ["a", "body2"], "anchor": [1.5, 2]})");
  CHECK(rigid.type == JointType::kWeld);
  CHECK(Same(rigid.anchor, {1.5, 2}));
  CHECK_FALSE(rigid.spring.has_value());
  const engine::JointDef soft = OnlyJoint(
      R"({"type": "weld", "bodies": ["a", "body2"], "anchor": [1.5, 2], "spring": {"hertz": 8, "damping_ratio": 1}})");
  CHECK(soft.spring->hertz == 8.0);
  CHECK(soft.spring->damping_ratio == 1.0);
}

TEST_CASE("scene joints: joints keep file order and name bodies in either order, later ones included",
          "[scene][joints]") {
  const game::Scene scene = RequireParsed(SceneWithJoints(R"([
    {"type": "weld", "bodies": ["slider", "a"], "anchor": [1, 3]},
    {"id": "second", "type": "revolute", "bodies": ["body2", "floor"], "anchor": [3, 2]},
    {"type": "distance", "bodies": ["lift", "a"], "anchors": [[5, 0], [0, 2]]}])"));
  REQUIRE(scene.joints.size() == 3);
  CHECK(scene.joints[0].def.type == JointType::kWeld);
  CHECK(IsBody(scene.joints[0].def.body_a, 5));
  CHECK(IsBody(scene.joints[0].def.body_b, 1));
  CHECK(scene.joints[1].id == "second");
  CHECK(IsBody(scene.joints[1].def.body_a, 2));
  CHECK(IsBody(scene.joints[1].def.body_b, 0));
  CHECK(scene.joints[2].id == "joint2");  // the default id counts every joint
  CHECK(IsBody(scene.joints[2].def.body_a, 3));  // a kinematic body with a dynamic one
  CHECK(game::FindJoint(scene, "second") == std::optional<std::size_t>(1));
  CHECK(game::FindJoint(scene, "joint0") == std::optional<std::size_t>(0));
  CHECK_FALSE(game::FindJoint(scene, "a").has_value());  // a body's id, not a joint's
}

TEST_CASE("scene joints: a joint may share a body's id (joint ids are their own list)", "[scene][joints]") {
  const game::Scene scene =
      RequireParsed(SceneWithJoint(R"({"id": "a", "type": "weld", "bodies": ["a", "body2"], "anchor": [1, 2]})"));
  CHECK(scene.joints.at(0).id == "a");
}

TEST_CASE("scene joints: without rotation, joints of static and fixed_rotation bodies load", "[scene][joints]") {
  const game::Scene scene = RequireParsed(SceneWithJoints(R"([
    {"type": "revolute", "bodies": ["floor", "slider"], "anchor": [2, 5.5]},
    {"type": "prismatic", "bodies": ["wall", "slider"], "anchor": [2, 5], "axis": [1, 0]},
    {"type": "distance", "bodies": ["slider", "floor"], "anchors": [[2, 5], [0, 0]]}])",
                                                          false));
  CHECK(scene.joints.size() == 3);
}

TEST_CASE("scene joints: no joints key and an empty list give no joints", "[scene][joints]") {
  const std::string bodies = std::string("{\"bodies\": ") + kBodies;
  CHECK(RequireParsed(bodies + "}").joints.empty());
  CHECK(RequireParsed(bodies + ", \"joints\": []}").joints.empty());
}

TEST_CASE("scene joints: the scene of every joint key in tests/data loads", "[scene][joints]") {
  const game::Expected<game::Scene> loaded = game::LoadScene(DataPath("scene_joints.json"));
  if (!loaded.HasValue()) FAIL(loaded.Error().message);
  const game::Scene& scene = loaded.Value();
  REQUIRE(scene.joints.size() == 7);
  CHECK(scene.joints[0].def.type == JointType::kRevolute);
  CHECK(scene.joints[1].def.collide);
  CHECK(scene.joints[2].def.max_length == std::optional<double>(3.0));
  CHECK(scene.joints[3].def.spring->hertz == 2.0);
  CHECK(scene.joints[4].def.type == JointType::kPrismatic);
  CHECK(scene.joints[5].def.type == JointType::kWeld);
  CHECK(scene.joints[6].id == "cloth");
}

// --- Bad input, named by key path.

TEST_CASE("scene joints error: joints that is not a list, a joint that is not an object", "[scene][joints]") {
  RequireError(std::string("{\"bodies\": ") + kBodies + ", \"joints\": {}}", "joints: must be an array");
  RequireError(SceneWithJoints("[3]"), "joints[0]: must be an object");
}

TEST_CASE("scene joints error: unknown keys, with a suggestion", "[scene][joints]") {
  RequireJointError(R"({"type": "revolute", "bodies": ["floor", "a"], "anchr": [0, 0]})",
                    "joints[0]: unknown key \"anchr\" (did you mean \"anchor\"?)");
  RequireJointError(R"({"type": "revolute", "bodies": ["floor", "a"], "anchor": [0, 0], "colide": true})",
                    "joints[0]: unknown key \"colide\" (did you mean \"collide\"?)");
  RequireJointError(R"({"type": "revolute", "bodies": ["floor", "a"], "anchor": [0, 0], "target": [0, 0]})",
                    "joints[0]: unknown key \"target\"");
  RequireJointError(
      R"({"type": "revolute", "bodies": ["floor", "a"], "anchor": [0, 0], "motor": {"sped": 1, "max_torque": 1}})",
      "joints[0].motor: unknown key \"sped\" (did you mean \"speed\"?)");
  RequireJointError(
      R"({"type": "weld", "bodies": ["floor", "a"], "anchor": [0, 0], "spring": {"hertz": 1, "damping": 1}})",
      "joints[0].spring: unknown key \"damping\"");
}

TEST_CASE("scene joints error: a key of another joint type", "[scene][joints]") {
  RequireJointError(R"({"type": "revolute", "bodies": ["floor", "a"], "anchor": [0, 0], "axis": [1, 0]})",
                    "joints[0].axis: applies to prismatic joints only; a revolute joint has \"anchor\" and "
                    "optional \"limits\" and \"motor\"");
  RequireJointError(R"({"type": "distance", "bodies": ["floor", "a"], "anchor": [0, 0]})",
                    "joints[0].anchor: applies to revolute, prismatic and weld joints only; a distance joint has "
                    "\"anchors\" and optional \"length\", \"min_length\", \"max_length\" and \"spring\"");
  RequireJointError(R"({"type": "weld", "bodies": ["floor", "a"], "anchor": [0, 0], "limits": [0, 1]})",
                    "joints[0].limits: applies to revolute and prismatic joints only; a weld joint has "
                    "\"anchor\" and an optional \"spring\"");
  RequireJointError(
      R"({"type": "revolute", "bodies": ["floor", "a"], "anchor": [0, 0], "spring": {"hertz": 1}})",
      "joints[0].spring: applies to distance and weld joints only; a revolute joint has \"anchor\" and optional "
      "\"limits\" and \"motor\"");
  RequireJointError(
      R"({"type": "prismatic", "bodies": ["floor", "a"], "anchor": [0, 0], "axis": [1, 0], "max_length": 2})",
      "joints[0].max_length: applies to distance joints only; a prismatic joint has \"anchor\", \"axis\" and "
      "optional \"limits\" and \"motor\"");
  RequireJointError(
      R"({"type": "revolute", "bodies": ["floor", "a"], "anchor": [0, 0], "motor": {"max_force": 1}})",
      "joints[0].motor.max_force: applies to prismatic joints only; a revolute joint's motor has \"speed\" "
      "(rad/s) and \"max_torque\" (N·m)");
  RequireJointError(
      R"({"type": "prismatic", "bodies": ["floor", "a"], "anchor": [0, 0], "axis": [1, 0],
          "motor": {"max_torque": 1}})",
      "joints[0].motor.max_torque: applies to revolute joints only; a prismatic joint's motor has \"speed\" "
      "(m/s) and \"max_force\" (N)");
}

TEST_CASE("scene joints error: missing required keys", "[scene][joints]") {
  RequireJointError(R"({"bodies": ["floor", "a"], "anchor": [0, 0]})",
                    "joints[0]: needs a \"type\" (\"revolute\", \"distance\", \"prismatic\" or \"weld\")");
  RequireJointError(R"({"type": "revolute", "anchor": [0, 0]})",
                    "joints[0]: needs \"bodies\" [id, id]: the ids of the two bodies it joins");
  RequireJointError(R"({"type": "revolute", "bodies": ["floor", "a"]})",
                    "joints[0]: needs an \"anchor\" [x, y]: the world point both bodies share");
  RequireJointError(R"({"type": "weld", "bodies": ["floor", "a"]})",
                    "joints[0]: needs an \"anchor\" [x, y]: the world point where the bodies are held together");
  RequireJointError(R"({"type": "prismatic", "bodies": ["floor", "a"], "axis": [1, 0]})",
                    "joints[0]: needs an \"anchor\" [x, y]: a world point on the line the second body slides along");
  RequireJointError(R"({"type": "prismatic", "bodies": ["floor", "a"], "anchor": [0, 0]})",
                    "joints[0]: needs an \"axis\" [x, y]: the direction the second body slides along");
  RequireJointError(R"({"type": "distance", "bodies": ["floor", "a"]})",
                    "joints[0]: needs \"anchors\" [[x, y], [x, y]]: a world point on each body");
  RequireJointError(
      R"({"type": "revolute", "bodies": ["floor", "a"], "anchor": [0, 0], "motor": {"speed": 1}})",
      "joints[0].motor: needs \"max_torque\", the most it applies; a revolute joint's motor has \"speed\" (rad/s) "
      "and \"max_torque\" (N·m)");
  RequireJointError(
      R"({"type": "prismatic", "bodies": ["floor", "a"], "anchor": [0, 0], "axis": [1, 0], "motor": {}})",
      "joints[0].motor: needs \"max_force\", the most it applies; a prismatic joint's motor has \"speed\" (m/s) "
      "and \"max_force\" (N)");
  RequireJointError(
      R"({"type": "weld", "bodies": ["floor", "a"], "anchor": [0, 0], "spring": {"damping_ratio": 1}})",
      "joints[0].spring: needs \"hertz\" (> 0), the spring's natural frequency");
}

TEST_CASE("scene joints error: wrong JSON types", "[scene][joints]") {
  RequireJointError(R"({"type": 1, "bodies": ["floor", "a"], "anchor": [0, 0]})", "joints[0].type: must be a string");
  RequireJointError(R"({"type": "hinge", "bodies": ["floor", "a"], "anchor": [0, 0]})",
                    "joints[0].type: unknown value \"hinge\" (expected one of \"revolute\", \"distance\", "
                    "\"prismatic\", \"weld\")");
  RequireJointError(R"({"type": "revolute", "bodies": "floor", "anchor": [0, 0]})",
                    "joints[0].bodies: must be [id, id]: the ids of the two bodies it joins");
  RequireJointError(R"({"type": "revolute", "bodies": ["floor", "a", "body2"], "anchor": [0, 0]})",
                    "joints[0].bodies: must be [id, id]: the ids of the two bodies it joins");
  RequireJointError(R"({"type": "revolute", "bodies": ["floor", 1], "anchor": [0, 0]})",
                    "joints[0].bodies[1]: must be a string");
  RequireJointError(R"({"type": "revolute", "bodies": ["floor", "a"], "anchor": "here"})",
                    "joints[0].anchor: must be an array of 2 numbers");
  RequireJointError(R"({"type": "revolute", "bodies": ["floor", "a"], "anchor": [0, "1"]})",
                    "joints[0].anchor[1]: must be a number");
  RequireJointError(R"({"type": "revolute", "bodies": ["floor", "a"], "anchor": [0, 0], "collide": 1})",
                    "joints[0].collide: must be true or false");
  RequireJointError(R"({"type": "revolute", "bodies": ["floor", "a"], "anchor": [0, 0], "id": 7})",
                    "joints[0].id: must be a string");
  RequireJointError(R"({"type": "revolute", "bodies": ["floor", "a"], "anchor": [0, 0], "limits": 1})",
                    "joints[0].limits: must be [lower, upper], 2 numbers in rad");
  RequireJointError(
      R"({"type": "prismatic", "bodies": ["floor", "a"], "anchor": [0, 0], "axis": [1, 0], "limits": [1]})",
      "joints[0].limits: must be [lower, upper], 2 numbers in m");
  RequireJointError(R"({"type": "revolute", "bodies": ["floor", "a"], "anchor": [0, 0], "limits": [0, null]})",
                    "joints[0].limits[1]: must be a number");
  RequireJointError(R"({"type": "revolute", "bodies": ["floor", "a"], "anchor": [0, 0], "motor": [1, 2]})",
                    "joints[0].motor: must be an object");
  RequireJointError(R"({"type": "weld", "bodies": ["floor", "a"], "anchor": [0, 0], "spring": 5})",
                    "joints[0].spring: must be an object");
  RequireJointError(R"({"type": "distance", "bodies": ["floor", "a"], "anchors": [0, 0]})",
                    "joints[0].anchors[0]: must be an array of 2 numbers");
  RequireJointError(R"({"type": "distance", "bodies": ["floor", "a"], "anchors": [[0, 0]]})",
                    "joints[0].anchors: must be [[x, y], [x, y]]: a world point on each body");
  RequireJointError(R"({"type": "distance", "bodies": ["floor", "a"], "anchors": [[0, 0], [1, 1]], "length": "1"})",
                    "joints[0].length: must be a number");
}

TEST_CASE("scene joints error: numbers too large or not finite", "[scene][joints]") {
  RequireJointError(R"({"type": "revolute", "bodies": ["floor", "a"], "anchor": [2e9, 0]})",
                    "joints[0].anchor[0]: must be between -1e9 and 1e9 (docs/limits.md)");
  RequireJointError(
      R"({"type": "revolute", "bodies": ["floor", "a"], "anchor": [0, 0], "motor": {"speed": -1e10, "max_torque": 1}})",
      "joints[0].motor.speed: must be between -1e9 and 1e9 (docs/limits.md)");
  // JSON has no NaN or infinity; a number that overflows a double is where one could come from.
  const std::string json = SceneWithJoint(
      R"({"type": "distance", "bodies": ["floor", "a"], "anchors": [[0, 0], [1, 1]], "max_length": 1e999})");
  const game::Expected<game::Scene> scene = game::ParseScene(json, "joints.json", "joints");
  REQUIRE_FALSE(scene.HasValue());
  CHECK(scene.Error().exit_code == 2);
  // The line and column of the number's first character, counted from 1.
  const std::size_t at = json.find("1e999");
  const std::size_t line_start = json.rfind('\n', at) + 1;  // npos + 1 is 0 on the first line
  const std::string where = std::to_string(1 + std::count(json.begin(), json.begin() + at, '\n')) + ":" +
                            std::to_string(at - line_start + 1);
  CHECK(scene.Error().message == "joints.json:" + where +
                                     ": joints[0].max_length: the number 1e999 is too large for a double (at most "
                                     "about 1.8e308)");
}

TEST_CASE("scene joints error: an unknown body id, a body joined to itself", "[scene][joints]") {
  RequireJointError(R"({"type": "revolute", "bodies": ["floor", "ball"], "anchor": [0, 0]})",
                    "joints[0].bodies[1]: no body has the id \"ball\"");
  RequireJointError(R"({"type": "revolute", "bodies": ["body1", "a"], "anchor": [0, 0]})",
                    "joints[0].bodies[0]: no body has the id \"body1\"");  // body1 is called "a"
  RequireJointError(R"({"type": "weld", "bodies": ["a", "a"], "anchor": [0, 0]})",
                    "joints[0].bodies[1]: is \"a\" again: a joint joins two different bodies");
}

TEST_CASE("scene joints error: two bodies that nothing moves", "[scene][joints]") {
  RequireJointError(R"({"type": "weld", "bodies": ["floor", "wall"], "anchor": [0, 0]})",
                    "joints[0].bodies: joins \"floor\" (static) and \"wall\" (static): a joint needs a dynamic "
                    "body, one that forces move");
  RequireJointError(R"({"type": "distance", "bodies": ["lift", "floor"], "anchors": [[5, 0], [0, 0]]})",
                    "joints[0].bodies: joins \"lift\" (kinematic) and \"floor\" (static): a joint needs a dynamic "
                    "body, one that forces move");
  const std::string two_lifts = R"({"rotation": true, "bodies": [
    {"id": "l1", "shape": "box", "size": [1, 1], "position": [0, 0], "kinematic": true},
    {"id": "l2", "shape": "box", "size": [1, 1], "position": [3, 0], "kinematic": true}],
    "joints": [{"type": "revolute", "bodies": ["l1", "l2"], "anchor": [1, 0]}]})";
  RequireError(two_lifts,
               "joints[0].bodies: joins \"l1\" (kinematic) and \"l2\" (kinematic): a joint needs a dynamic body, "
               "one that forces move");
}

TEST_CASE("scene joints error: a joint that needs rotation in an axis-aligned scene", "[scene][joints]") {
  const std::string needs_rotation =
      ": needs \"rotation\": true in the scene, unless every body it joins is static or has \"fixed_rotation\": "
      "true ";
  RequireJointError(R"({"type": "revolute", "bodies": ["floor", "a"], "anchor": [0, 1.5]})",
                    "joints[0]" + needs_rotation + "(\"a\" is neither)", false);
  RequireJointError(R"({"type": "weld", "bodies": ["slider", "body2"], "anchor": [3, 3]})",
                    "joints[0]" + needs_rotation + "(\"body2\" is neither)", false);
  // A kinematic body is not static: it needs fixed_rotation too, as the contract words the rule.
  RequireJointError(R"({"type": "distance", "bodies": ["lift", "slider"], "anchors": [[5, 0], [2, 5]]})",
                    "joints[0]" + needs_rotation + "(\"lift\" is neither)", false);
  // Named by the joint's place in the list.
  RequireError(SceneWithJoints(R"([{"type": "weld", "bodies": ["floor", "slider"], "anchor": [2, 5]},
                                   {"type": "weld", "bodies": ["a", "slider"], "anchor": [1, 4]}])",
                               false),
               "joints[1]" + needs_rotation + "(\"a\" is neither)");
}

TEST_CASE("scene joints error: limits with lower above upper", "[scene][joints]") {
  RequireJointError(R"({"type": "revolute", "bodies": ["floor", "a"], "anchor": [0, 0], "limits": [0.5, -0.5]})",
                    "joints[0].limits: the lower limit must not be above the upper one");
  RequireJointError(
      R"({"type": "prismatic", "bodies": ["floor", "a"], "anchor": [0, 0], "axis": [1, 0], "limits": [2, 1.999]})",
      "joints[0].limits: the lower limit must not be above the upper one");
}

TEST_CASE("scene joints error: negative lengths, min_length above max_length", "[scene][joints]") {
  const std::string start = R"({"type": "distance", "bodies": ["floor", "a"], "anchors": [[0, 0], [0, 2]], )";
  RequireJointError(start + R"("length": -1})", "joints[0].length: must be >= 0");
  RequireJointError(start + R"("min_length": -0.5})", "joints[0].min_length: must be >= 0");
  RequireJointError(start + R"("max_length": -2})", "joints[0].max_length: must be >= 0");
  RequireJointError(start + R"("min_length": 3, "max_length": 2})",
                    "joints[0].min_length: must not be above \"max_length\"");
}

// The engine's solver finds no line to pull along between anchors held (next to) together.
TEST_CASE("scene joints error: a distance joint that would hold its anchors together", "[scene][joints]") {
  const std::string start = R"({"type": "distance", "bodies": ["floor", "a"], )";
  const std::string rigid_length =
      "joints[0].length: must be at least 1e-09 m unless the joint has a range or a spring; anchors held together "
      "are a revolute joint (docs/limits.md)";
  RequireJointError(start + R"("anchors": [[0, 0], [0, 2]], "length": 0})", rigid_length);
  RequireJointError(start + R"("anchors": [[0, 0], [0, 2]], "length": 1e-10})", rigid_length);
  RequireJointError(start + R"("anchors": [[0, 0], [0, 2]], "max_length": 0})",
                    "joints[0].max_length: must be at least 1e-09 m (docs/limits.md)");
  RequireJointError(start + R"("anchors": [[0, 0], [0, 2]], "min_length": 0, "max_length": 5e-10,
                                "spring": {"hertz": 1}})",
                    "joints[0].max_length: must be at least 1e-09 m (docs/limits.md)");
  const std::string same_point =
      "joints[0].anchors: are within 1e-09 m of each other, the length the joint would hold: give a \"length\", "
      "or use a revolute joint to hold them together (docs/limits.md)";
  RequireJointError(start + R"("anchors": [[0, 2], [0, 2]]})", same_point);
  RequireJointError(start + R"("anchors": [[0, 2], [0, 2.0000000000000004]]})", same_point);
  // Anchors together are fine when the joint does not hold them there.
  CHECK(OnlyJoint(start + R"("anchors": [[0, 2], [0, 2]], "length": 1})").length == std::optional<double>(1.0));
  CHECK(OnlyJoint(start + R"("anchors": [[0, 2], [0, 2]], "min_length": 1})").min_length == std::optional<double>(1.0));
}

TEST_CASE("scene joints error: spring hertz <= 0, damping ratio < 0", "[scene][joints]") {
  const std::string weld = R"({"type": "weld", "bodies": ["floor", "a"], "anchor": [0, 0], "spring": )";
  RequireJointError(weld + R"({"hertz": 0}})", "joints[0].spring.hertz: must be > 0");
  RequireJointError(weld + R"({"hertz": -1}})", "joints[0].spring.hertz: must be > 0");
  RequireJointError(weld + R"({"hertz": 1, "damping_ratio": -0.1}})", "joints[0].spring.damping_ratio: must be >= 0");
  RequireJointError(
      R"({"type": "distance", "bodies": ["floor", "a"], "anchors": [[0, 0], [0, 2]], "spring": {"hertz": 0}})",
      "joints[0].spring.hertz: must be > 0");
}

TEST_CASE("scene joints error: motor caps below 0", "[scene][joints]") {
  RequireJointError(
      R"({"type": "revolute", "bodies": ["floor", "a"], "anchor": [0, 0], "motor": {"speed": 1, "max_torque": -1}})",
      "joints[0].motor.max_torque: must be >= 0");
  RequireJointError(
      R"({"type": "prismatic", "bodies": ["floor", "a"], "anchor": [0, 0], "axis": [1, 0],
          "motor": {"speed": 1, "max_force": -0.001}})",
      "joints[0].motor.max_force: must be >= 0");
}

TEST_CASE("scene joints error: a prismatic axis of no direction", "[scene][joints]") {
  const std::string start = R"({"type": "prismatic", "bodies": ["floor", "a"], "anchor": [0, 0], "axis": )";
  const std::string message = "joints[0].axis: must be a direction, not [0, 0] (at least 1e-09 long, docs/limits.md)";
  RequireJointError(start + "[0, 0]}", message);
  RequireJointError(start + "[0, -0]}", message);
  // Its square underflows to 0: no unit vector can be made of it.
  RequireJointError(start + "[1e-200, 1e-200]}", message);
  CHECK(OnlyJoint(start + "[1e-9, 0]}").axis.x == 1e-9);
}

TEST_CASE("scene joints error: ids must be unique among joints and not empty", "[scene][joints]") {
  RequireError(SceneWithJoints(R"([{"id": "hinge", "type": "weld", "bodies": ["floor", "a"], "anchor": [0, 0]},
                                   {"id": "hinge", "type": "weld", "bodies": ["floor", "body2"], "anchor": [0, 0]}])"),
               "joints[1].id: duplicate id \"hinge\" (also joints[0])");
  RequireError(SceneWithJoints(R"([{"id": "joint1", "type": "weld", "bodies": ["floor", "a"], "anchor": [0, 0]},
                                   {"type": "weld", "bodies": ["floor", "body2"], "anchor": [0, 0]}])"),
               "joints[1]: its default id \"joint1\" is taken by joints[0]; give one of them an \"id\"");
  RequireJointError(R"({"id": "", "type": "weld", "bodies": ["floor", "a"], "anchor": [0, 0]})",
                    "joints[0].id: must not be empty");
}

TEST_CASE("scene joints error: the first fault in file order is the one named", "[scene][joints]") {
  RequireError(SceneWithJoints(R"([{"type": "weld", "bodies": ["floor", "a"], "anchor": [0, 0]},
                                   {"type": "weld", "bodies": ["floor", "nobody"], "anchor": [0, 0]},
                                   {"type": "weld", "bodies": ["floor", "a"]}])"),
               "joints[1].bodies[1]: no body has the id \"nobody\"");
}

TEST_CASE("scene joints: bad input exits 2 with one line naming the file and key path, writing nothing",
          "[scene][joints][cli]") {
  const auto dir = testing::FreshTestDir("scene_joints", "exit_2");
  const auto scene = dir / "bad.json";
  {
    std::FILE* f = std::fopen(scene.c_str(), "w");
    REQUIRE(f);
    std::fputs(R"({"rotation": true, "bodies": [
      {"id": "post", "shape": "box", "size": [0.2, 2], "position": [0, 1], "static": true},
      {"id": "door", "shape": "box", "size": [1, 2], "position": [0.6, 1]}],
      "joints": [
        {"type": "revolute", "bodies": ["post", "door"], "anchor": [0.1, 1], "limits": [0, 1.5]},
        {"type": "revolute", "bodies": ["post", "door"], "anchor": [0.1, 1], "axis": [0, 1]}]})",
               f);
    std::fclose(f);
  }
  const testing::ProgramRun run =
      testing::Ballbox("sim '" + scene.string() + "' --steps 1 --dump d.csv --save-state s.bin", dir);
  CHECK(run.exit_code == 2);
  CHECK(run.err == "error: " + scene.string() +
                       ": joints[1].axis: applies to prismatic joints only; a revolute joint has \"anchor\" and "
                       "optional \"limits\" and \"motor\"\n");
  CHECK(run.out.empty());
  CHECK(testing::SortedNames(dir) == std::vector<std::string>{"bad.json"});
}

TEST_CASE("scene joints: a hundred thousand joints load; one more is refused before any is read",
          "[scene][joints][limits]") {
  const std::string joint = R"({"type": "weld", "bodies": ["a", "body2"], "anchor": [1, 2]})";
  std::string json = std::string("{\"rotation\": true, \"bodies\": ") + kBodies + ", \"joints\": [" + joint;
  for (int i = 1; i < 100'000; ++i) json += "," + joint;
  const game::Scene at_limit = RequireParsed(json + "]}");
  CHECK(at_limit.joints.size() == 100'000);
  CHECK(at_limit.joints.back().id == "joint99999");
  // Empty objects would each be an error; the count is checked first.
  RequireError(json + ",{}]}", "joints: 100001 joints, more than the limit of 100000 (docs/limits.md)");
}

// --- Through BuildWorld and the engine: the joints hold their bodies as the keys say.

namespace {

engine::World BuildScene(const std::string& json) { return game::BuildWorld(RequireParsed(json)); }

double Gap(const engine::JointFrame& frame) { return engine::Length(frame.anchor_b - frame.anchor_a); }

bool AllFinite(const engine::World& world) {
  for (const engine::BodyId id : world.BodyIds()) {
    const engine::BodyState& s = world.State(id);
    for (const double v : {s.position.x, s.position.y, s.velocity.x, s.velocity.y, s.angle, s.angular_velocity}) {
      if (!std::isfinite(v)) return false;
    }
  }
  return true;
}

constexpr engine::JointId kFirstJoint{0, 0};

}  // namespace

TEST_CASE("scene joints: BuildWorld makes the joints in file order, as the scene gives them", "[scene][joints]") {
  const game::Scene scene = RequireParsed(SceneWithJoints(R"([
    {"type": "weld", "bodies": ["slider", "a"], "anchor": [1, 3]},
    {"type": "revolute", "bodies": ["body2", "floor"], "anchor": [3, 2], "limits": [-1, 1], "collide": true},
    {"type": "distance", "bodies": ["lift", "a"], "anchors": [[5, 0], [0, 2]], "max_length": 7}])"));
  const engine::World world = game::BuildWorld(scene);
  REQUIRE(world.JointIds().size() == 3);
  for (std::size_t i = 0; i < 3; ++i) {
    INFO("joint " << i);
    const engine::JointId id = world.JointIds()[i];
    CHECK(id.index == i);
    const engine::JointDef& made = world.GetJointDef(id);
    const engine::JointDef& given = scene.joints[i].def;
    CHECK(made.type == given.type);
    CHECK(made.body_a == given.body_a);
    CHECK(made.body_b == given.body_b);
    CHECK(made.collide == given.collide);
    CHECK(made.limits.has_value() == given.limits.has_value());
    CHECK(made.max_length == given.max_length);
  }
}

TEST_CASE("scene joints: a scene without joints builds the same world with or without an empty list",
          "[scene][joints]") {
  const std::string bodies = R"({"rotation": true, "bodies": [
    {"shape": "box", "size": [10, 1], "position": [0, -0.5], "static": true},
    {"shape": "box", "size": [1, 1], "position": [0.2, 3], "angle": 0.3},
    {"shape": "circle", "radius": 0.5, "position": [0, 5], "velocity": [1, 0]}])";
  engine::World without = BuildScene(bodies + "}");
  engine::World empty = BuildScene(bodies + ", \"joints\": []}");
  CHECK(empty.JointIds().empty());
  for (int step = 0; step < 240; ++step) {
    without.Step();
    empty.Step();
  }
  CHECK(empty.StateHash() == without.StateHash());
}

TEST_CASE("scene joints: a revolute pendulum keeps its anchors together and swings down to the bottom",
          "[scene][joints]") {
  // A bob 2 m from its pivot, released level with it: with no friction it swings down to 2 m below.
  engine::World world = BuildScene(R"({"rotation": true, "bodies": [
    {"id": "pivot", "shape": "box", "size": [0.2, 0.2], "position": [0, 5], "static": true},
    {"id": "bob", "shape": "circle", "radius": 0.2, "position": [2, 5]}],
    "joints": [{"type": "revolute", "bodies": ["pivot", "bob"], "anchor": [0, 5]}]})");
  const engine::BodyId bob{1};
  double lowest = 5.0, widest_gap = 0.0;
  for (int step = 0; step < 180; ++step) {
    world.Step();
    lowest = std::min(lowest, world.State(bob).position.y);
    widest_gap = std::max(widest_gap, Gap(world.Joint(kFirstJoint)));
    INFO("step " << step);
    REQUIRE(engine::Length(world.State(bob).position - Vec2{0, 5}) == Approx(2.0).margin(0.01));
  }
  CHECK(widest_gap < 0.01);
  CHECK(lowest == Approx(3.0).margin(0.02));
}

TEST_CASE("scene joints: collide false lets the joined bodies overlap, collide true pushes them apart",
          "[scene][joints]") {
  // A ball half inside a wall, tied to it by a slack rope: the rope pulls nothing, so only a
  // contact could move the ball.
  auto ball_x_after = [](const char* collide) {
    engine::World world = BuildScene(std::string(R"({"gravity": [0, 0], "rotation": true, "bodies": [
      {"id": "wall", "shape": "box", "size": [1, 4], "position": [0, 0], "static": true},
      {"id": "ball", "shape": "circle", "radius": 0.5, "position": [0.6, 0]}],
      "joints": [{"type": "distance", "bodies": ["wall", "ball"], "anchors": [[0, 0], [0.6, 0]],
                  "max_length": 5, "collide": )") + collide + "}]}");
    for (int step = 0; step < 60; ++step) world.Step();
    return world.State(engine::BodyId{1}).position.x;
  };
  CHECK(ball_x_after("false") == 0.6);
  CHECK(ball_x_after("true") > 0.95);  // out of the wall, whose face is at 0.5
}

TEST_CASE("scene joints: a distance joint holds the length it starts with", "[scene][joints]") {
  // Anchors 3 across and 4 down from each other: the default length is 5.
  engine::World world = BuildScene(R"({"rotation": true, "bodies": [
    {"id": "hook", "shape": "box", "size": [0.2, 0.2], "position": [0, 8], "static": true},
    {"id": "load", "shape": "box", "size": [0.5, 0.5], "position": [3, 3.75]}],
    "joints": [{"type": "distance", "bodies": ["hook", "load"], "anchors": [[0, 8], [3, 4]]}]})");
  const engine::JointFrame start = world.Joint(kFirstJoint);
  CHECK(start.translation == Approx(5.0).margin(1e-12));
  for (int step = 0; step < 180; ++step) world.Step();
  const engine::JointFrame end = world.Joint(kFirstJoint);
  CHECK(end.translation == Approx(5.0).margin(0.01));
  CHECK(Gap(end) == Approx(5.0).margin(0.01));
  CHECK(world.State(engine::BodyId{1}).position.x < 2.5);  // it swung
}

TEST_CASE("scene joints: a prismatic motor drives the body along its axis up to its limit", "[scene][joints]") {
  // No gravity: only the motor (1 m/s along [3, 4] / 5) moves the block, until the upper limit 1.5 m.
  engine::World world = BuildScene(R"({"gravity": [0, 0], "rotation": true, "bodies": [
    {"id": "base", "shape": "box", "size": [0.5, 0.5], "position": [0, 0], "static": true},
    {"id": "block", "shape": "box", "size": [0.5, 0.5], "position": [2, 2]}],
    "joints": [{"type": "prismatic", "bodies": ["base", "block"], "anchor": [2, 2], "axis": [3, 4],
                "limits": [-1, 1.5], "motor": {"speed": 1, "max_force": 1000}}]})");
  const engine::BodyId block{1};
  for (int step = 0; step < 60; ++step) world.Step();  // 1 s
  CHECK(world.Joint(kFirstJoint).translation == Approx(1.0).margin(0.02));
  CHECK(world.State(block).position.x == Approx(2.6).margin(0.02));
  CHECK(world.State(block).position.y == Approx(2.8).margin(0.02));
  for (int step = 0; step < 120; ++step) world.Step();  // 3 s: it would be at 3 m without the limit
  CHECK(world.Joint(kFirstJoint).translation == Approx(1.5).margin(0.01));
  CHECK(world.State(block).angle == Approx(0.0).margin(1e-6));
}

TEST_CASE("scene joints: a revolute joint's limits stop a falling arm", "[scene][joints]") {
  // A 2 m arm hinged at its left end falls; its angle may not go below -0.4 rad.
  engine::World world = BuildScene(R"({"rotation": true, "bodies": [
    {"id": "post", "shape": "box", "size": [0.2, 0.2], "position": [0, 5], "static": true},
    {"id": "arm", "shape": "box", "size": [2, 0.2], "position": [1, 5]}],
    "joints": [{"type": "revolute", "bodies": ["post", "arm"], "anchor": [0, 5], "limits": [-0.4, 0.4]}]})");
  double least = 0.0;
  for (int step = 0; step < 180; ++step) {
    world.Step();
    least = std::min(least, world.Joint(kFirstJoint).angle);
  }
  CHECK(least > -0.42);
  CHECK(world.Joint(kFirstJoint).angle == Approx(-0.4).margin(0.01));
  CHECK(world.State(engine::BodyId{1}).angle == Approx(-0.4).margin(0.01));
}

TEST_CASE("scene joints: an axis-aligned scene of fixed-rotation bodies holds its rope", "[scene][joints]") {
  engine::World world = BuildScene(R"({"bodies": [
    {"id": "ceiling", "shape": "box", "size": [4, 0.2], "position": [0, 6], "static": true},
    {"id": "crate", "shape": "box", "size": [1, 1], "position": [1.5, 3], "fixed_rotation": true}],
    "joints": [{"type": "distance", "bodies": ["ceiling", "crate"], "anchors": [[0, 5.9], [1.5, 3.5]],
                "max_length": 3}]})");
  double longest = 0.0;
  for (int step = 0; step < 240; ++step) {
    world.Step();
    longest = std::max(longest, Gap(world.Joint(kFirstJoint)));
  }
  CHECK(longest < 3.01);  // it starts at 2.83 and falls until the rope is taut
  CHECK(Gap(world.Joint(kFirstJoint)) == Approx(3.0).margin(0.01));
  CHECK(world.State(engine::BodyId{1}).angle == 0.0);
}

TEST_CASE("scene joints: joints at the loader's edges step without faults", "[scene][joints]") {
  // Lengths of 0, a limit it starts outside, a motor with no force, a 1 nm axis, springs at
  // 1e-9 and 1e9 Hz, a kinematic partner, in an axis-aligned scene.
  const game::Expected<game::Scene> scene = game::LoadScene(DataPath("scene_joint_edges.json"));
  if (!scene.HasValue()) FAIL(scene.Error().message);
  engine::World world = game::BuildWorld(scene.Value());
  CHECK(world.JointIds().size() == scene.Value().joints.size());
  for (int step = 0; step < 120; ++step) world.Step();
  CHECK(AllFinite(world));
}

TEST_CASE("scene joints: the example scene in docs/scene-format.md is assets/scenes/joints.json, and it works",
          "[scene][joints]") {
  const std::string doc = testing::ReadFile(std::string(BALLBOX_ASSETS) + "/../docs/scene-format.md");
  const std::size_t section = doc.find("\n## Joints\n");
  REQUIRE(section != std::string::npos);
  const std::size_t start = doc.find("```json\n", section);
  REQUIRE(start != std::string::npos);
  const std::size_t end = doc.find("```\n", start + 8);
  const game::Scene documented = RequireParsed(doc.substr(start + 8, end - start - 8));
  const game::Expected<game::Scene> asset = game::LoadScene(std::string(BALLBOX_ASSETS) + "/scenes/joints.json");
  if (!asset.HasValue()) FAIL(asset.Error().message);
  const game::Scene& scene = asset.Value();
  REQUIRE(documented.joints.size() == scene.joints.size());
  REQUIRE(documented.bodies.size() == scene.bodies.size());
  for (std::size_t i = 0; i < scene.joints.size(); ++i) {
    INFO("joint " << i);
    CHECK(documented.joints[i].id == scene.joints[i].id);
    CHECK(documented.joints[i].def.type == scene.joints[i].def.type);
    CHECK(Same(documented.joints[i].def.anchor, scene.joints[i].def.anchor));
    CHECK(Same(documented.joints[i].def.anchor_b, scene.joints[i].def.anchor_b));
  }
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) CHECK(Same(documented.bodies[i].def.position, scene.bodies[i].def.position));

  // What the page says it shows, over 10 s.
  engine::World world = game::BuildWorld(scene);
  const engine::JointId pivot{static_cast<std::uint32_t>(*game::FindJoint(scene, "pivot"))};
  const engine::JointId cord{static_cast<std::uint32_t>(*game::FindJoint(scene, "cord"))};
  const engine::JointId hinge{static_cast<std::uint32_t>(*game::FindJoint(scene, "hinge"))};
  const engine::BodyId bob{2}, cart{4};
  double bob_lowest = 10.0, cord_longest = 0.0, pivot_gap = 0.0, hinge_gap = 0.0, lean = 0.0;
  for (int step = 0; step < 600; ++step) {
    world.Step();
    bob_lowest = std::min(bob_lowest, world.State(bob).position.y);
    cord_longest = std::max(cord_longest, Gap(world.Joint(cord)));
    pivot_gap = std::max(pivot_gap, Gap(world.Joint(pivot)));
    hinge_gap = std::max(hinge_gap, Gap(world.Joint(hinge)));
    lean = std::max(lean, std::abs(world.Joint(hinge).angle));
  }
  CHECK(AllFinite(world));
  CHECK(pivot_gap < 0.01);
  CHECK(hinge_gap < 0.01);
  CHECK(bob_lowest == Approx(6.0 - std::sqrt(8.0)).margin(0.03));  // down to the full rod length below the pivot
  CHECK(cord_longest < 2.01);
  CHECK(lean < 0.62);
  CHECK(world.State(cart).position.x < -2.0);  // driven left at 1 m/s to its lower limit, at x = -3
  CHECK(world.State(cart).position.x > -3.02);
}

TEST_CASE("scene joints: a scene with joints saves and resumes to the same state", "[scene][joints][cli]") {
  const auto dir = testing::FreshTestDir("scene_joints", "resume");
  const std::string scene = "'" + DataPath("scene_joints.json") + "'";
  auto last_line = [](const std::string& out) {
    const std::size_t end = out.find_last_not_of('\n');
    return out.substr(out.rfind('\n', end) + 1, end - out.rfind('\n', end));
  };
  const testing::ProgramRun straight = testing::Ballbox("sim " + scene + " --steps 150", dir);
  REQUIRE(straight.exit_code == 0);
  const testing::ProgramRun first = testing::Ballbox("sim " + scene + " --steps 90 --save-state s.state", dir);
  REQUIRE(first.exit_code == 0);
  const testing::ProgramRun resumed = testing::Ballbox("sim " + scene + " --load-state s.state --steps 60", dir);
  REQUIRE(resumed.exit_code == 0);
  CHECK(last_line(straight.out).rfind("state-hash: ", 0) == 0);
  CHECK(last_line(resumed.out) == last_line(straight.out));
  CHECK(last_line(first.out) != last_line(straight.out));  // the joints moved the bodies on
}

TEST_CASE("scene joints: a state saved from a scene does not load into one whose joints differ",
          "[scene][joints][cli]") {
  const auto dir = testing::FreshTestDir("scene_joints", "other_joints");
  std::string text = testing::ReadFile(DataPath("scene_joints.json"));
  const std::size_t speed = text.find("\"speed\": 0.5");
  REQUIRE(speed != std::string::npos);
  text.replace(speed, 12, "\"speed\": 0.6");  // the shoulder's motor only
  {
    std::FILE* f = std::fopen((dir / "other.json").c_str(), "w");
    REQUIRE(f);
    std::fputs(text.c_str(), f);
    std::fclose(f);
  }
  const testing::ProgramRun save =
      testing::Ballbox("sim '" + DataPath("scene_joints.json") + "' --steps 10 --save-state s.state", dir);
  REQUIRE(save.exit_code == 0);
  const testing::ProgramRun load = testing::Ballbox("sim other.json --load-state s.state --steps 10", dir);
  CHECK(load.exit_code == 2);
  CHECK(load.err ==
        "error: s.state: saved from another scene (a state loads only into the scene it was saved from)\n");
}
