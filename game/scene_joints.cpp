// Scene joints (scene_joints.h): each joint's keys, read and checked in file order. A key of
// another joint type is named as misplaced rather than unknown, so the message says where it
// belongs; the checks on the bodies are World::CreateJoint's preconditions plus the contract's
// rule that a joint in an axis-aligned scene joins only bodies that cannot turn.
#include "game/scene_joints.h"

#include <string_view>

#include "engine/joint.h"
#include "game/limits.h"

namespace game::scene_values {

namespace {

using engine::JointType;

// Every key a joint of some type takes; what a joint of one type takes is Takes().
constexpr const char* kTypeKeys[] = {"anchor", "anchors", "axis",       "limits",     "motor",
                                     "length", "min_length", "max_length", "spring"};

JointType ReadJointType(const Json& value, const std::string& path) {
  return ReadChoice<JointType>(value, path,
                               {{"revolute", JointType::kRevolute},
                                {"distance", JointType::kDistance},
                                {"prismatic", JointType::kPrismatic},
                                {"weld", JointType::kWeld}});
}

bool Takes(JointType type, std::string_view key) {
  switch (type) {
    case JointType::kRevolute: return key == "anchor" || key == "limits" || key == "motor";
    case JointType::kPrismatic: return key == "anchor" || key == "axis" || key == "limits" || key == "motor";
    case JointType::kDistance:
      return key == "anchors" || key == "length" || key == "min_length" || key == "max_length" || key == "spring";
    case JointType::kWeld: return key == "anchor" || key == "spring";
    case JointType::kTarget: return false;
  }
  return false;
}

// Which joint types take a key, for the message when another type has it.
const char* Owners(std::string_view key) {
  if (key == "anchor") return "revolute, prismatic and weld joints";
  if (key == "axis") return "prismatic joints";
  if (key == "limits" || key == "motor") return "revolute and prismatic joints";
  if (key == "spring") return "distance and weld joints";
  return "distance joints";  // anchors, length, min_length, max_length
}

const char* WhatItHas(JointType type) {
  switch (type) {
    case JointType::kRevolute: return "a revolute joint has \"anchor\" and optional \"limits\" and \"motor\"";
    case JointType::kPrismatic:
      return "a prismatic joint has \"anchor\", \"axis\" and optional \"limits\" and \"motor\"";
    case JointType::kDistance:
      return "a distance joint has \"anchors\" and optional \"length\", \"min_length\", \"max_length\" and "
             "\"spring\"";
    case JointType::kWeld: return "a weld joint has \"anchor\" and an optional \"spring\"";
    case JointType::kTarget: break;
  }
  return "";
}

// [lower, upper] with lower <= upper; `unit` names what they measure.
engine::JointLimits ReadLimits(const Json& value, const std::string& path, const char* unit) {
  if (!value.is_array() || value.size() != 2) {
    throw SceneError{path, std::string("must be [lower, upper], 2 numbers in ") + unit};
  }
  const engine::JointLimits limits{ReadNumber(value[0], path + "[0]"), ReadNumber(value[1], path + "[1]")};
  if (limits.lower > limits.upper) throw SceneError{path, "the lower limit must not be above the upper one"};
  return limits;
}

// {speed, max_torque} on a revolute joint, {speed, max_force} on a prismatic one: both caps
// become JointMotor::max_force, so each type takes only the word for what it applies.
engine::JointMotor ReadMotor(const Json& value, const std::string& path, JointType type) {
  if (!value.is_object()) throw SceneError{path, "must be an object"};
  const bool revolute = type == JointType::kRevolute;
  const char* cap = revolute ? "max_torque" : "max_force";
  const char* other_cap = revolute ? "max_force" : "max_torque";
  const char* has = revolute ? "a revolute joint's motor has \"speed\" (rad/s) and \"max_torque\" (N·m)"
                             : "a prismatic joint's motor has \"speed\" (m/s) and \"max_force\" (N)";
  if (Find(value, other_cap)) {
    throw SceneError{Join(path, other_cap),
                     std::string("applies to ") + (revolute ? "prismatic" : "revolute") + " joints only; " + has};
  }
  RejectUnknownKeys(value, path, {"speed", cap});
  engine::JointMotor motor;
  const Json* max = Find(value, cap);
  if (!max) throw SceneError{path, std::string("needs \"") + cap + "\", the most it applies; " + has};
  motor.max_force = ReadNonNegative(*max, Join(path, cap));
  if (const Json* v = Find(value, "speed")) motor.speed = ReadNumber(*v, Join(path, "speed"));
  return motor;
}

engine::JointSpring ReadJointSpring(const Json& value, const std::string& path) {
  if (!value.is_object()) throw SceneError{path, "must be an object"};
  RejectUnknownKeys(value, path, {"hertz", "damping_ratio"});
  engine::JointSpring spring;
  const Json* hertz = Find(value, "hertz");
  if (!hertz) throw SceneError{path, "needs \"hertz\" (> 0), the spring's natural frequency"};
  spring.hertz = ReadPositive(*hertz, Join(path, "hertz"));
  if (const Json* v = Find(value, "damping_ratio")) spring.damping_ratio = ReadNonNegative(*v, Join(path, "damping_ratio"));
  return spring;
}

// The world point a joint of this type is placed by (revolute, prismatic, weld).
engine::Vec2 ReadAnchor(const Json& joint, const std::string& path, const char* what) {
  const Json* anchor = Find(joint, "anchor");
  if (!anchor) throw SceneError{path, std::string("needs an \"anchor\" [x, y]: ") + what};
  return ReadVec2(*anchor, Join(path, "anchor"));
}

void ReadDistanceKeys(const Json& joint, const std::string& path, engine::JointDef* def) {
  auto key = [&](const char* k) { return Join(path, k); };
  const Json* anchors = Find(joint, "anchors");
  if (!anchors) throw SceneError{path, "needs \"anchors\" [[x, y], [x, y]]: a world point on each body"};
  if (!anchors->is_array() || anchors->size() != 2) {
    throw SceneError{key("anchors"), "must be [[x, y], [x, y]]: a world point on each body"};
  }
  def->anchor = ReadVec2((*anchors)[0], key("anchors") + "[0]");
  def->anchor_b = ReadVec2((*anchors)[1], key("anchors") + "[1]");
  // No length: the engine takes the anchors' distance at the start, as the contract says.
  if (const Json* v = Find(joint, "length")) def->length = ReadNonNegative(*v, key("length"));
  if (const Json* v = Find(joint, "min_length")) def->min_length = ReadNonNegative(*v, key("min_length"));
  if (const Json* v = Find(joint, "max_length")) def->max_length = ReadNonNegative(*v, key("max_length"));
  if (def->min_length && def->max_length && *def->min_length > *def->max_length) {
    throw SceneError{key("min_length"), "must not be above \"max_length\""};
  }
  if (const Json* v = Find(joint, "spring")) def->spring = ReadJointSpring(*v, key("spring"));
  // A joint that holds its anchors (next to) together has no line to pull along: the engine's
  // solver breaks down there (docs/limits.md). Springs may pull them together.
  if (def->max_length && !(*def->max_length >= kMinBodySize)) throw SceneError{key("max_length"), TooSmall()};
  if (def->min_length || def->max_length || def->spring) return;
  if (def->length && !(*def->length >= kMinBodySize)) {
    throw SceneError{key("length"), "must be at least 1e-09 m unless the joint has a range or a spring; anchors "
                                    "held together are a revolute joint (docs/limits.md)"};
  }
  // The engine's own default, computed the same way.
  if (!def->length && !(engine::Length(def->anchor_b - def->anchor) >= kMinBodySize)) {
    throw SceneError{key("anchors"), "are within 1e-09 m of each other, the length the joint would hold: give a "
                                     "\"length\", or use a revolute joint to hold them together (docs/limits.md)"};
  }
}

void ReadTypeKeys(const Json& joint, const std::string& path, engine::JointDef* def) {
  auto key = [&](const char* k) { return Join(path, k); };
  switch (def->type) {
    case JointType::kRevolute:
      def->anchor = ReadAnchor(joint, path, "the world point both bodies share");
      if (const Json* v = Find(joint, "limits")) def->limits = ReadLimits(*v, key("limits"), "rad");
      if (const Json* v = Find(joint, "motor")) def->motor = ReadMotor(*v, key("motor"), def->type);
      break;
    case JointType::kPrismatic: {
      def->anchor = ReadAnchor(joint, path, "a world point on the line the second body slides along");
      const Json* axis = Find(joint, "axis");
      if (!axis) throw SceneError{path, "needs an \"axis\" [x, y]: the direction the second body slides along"};
      def->axis = ReadVec2(*axis, key("axis"));
      // Any length will do, but the engine must be able to make it a unit vector.
      if (!(engine::Length(def->axis) >= kMinBodySize)) {
        throw SceneError{key("axis"), "must be a direction, not [0, 0] (at least 1e-09 long, docs/limits.md)"};
      }
      if (const Json* v = Find(joint, "limits")) def->limits = ReadLimits(*v, key("limits"), "m");
      if (const Json* v = Find(joint, "motor")) def->motor = ReadMotor(*v, key("motor"), def->type);
      break;
    }
    case JointType::kDistance: ReadDistanceKeys(joint, path, def); break;
    case JointType::kWeld:
      def->anchor = ReadAnchor(joint, path, "the world point where the bodies are held together");
      if (const Json* v = Find(joint, "spring")) def->spring = ReadJointSpring(*v, key("spring"));
      break;
    case JointType::kTarget: break;
  }
}

const char* Kind(const engine::BodyDef& body) {
  if (body.is_static) return "static";
  if (body.is_kinematic) return "kinematic";
  return "dynamic";
}

// `bodies` [id, id]: two different bodies, at least one of which forces move, and, in an
// axis-aligned scene, none that could turn.
void ReadJointBodies(const Json& joint, const std::string& path, const std::vector<SceneBody>& bodies,
                     const std::map<std::string, std::size_t>& body_ids, bool rotation, engine::JointDef* def) {
  const std::string key = Join(path, "bodies");
  const Json* pair = Find(joint, "bodies");
  if (!pair) throw SceneError{path, "needs \"bodies\" [id, id]: the ids of the two bodies it joins"};
  if (!pair->is_array() || pair->size() != 2) {
    throw SceneError{key, "must be [id, id]: the ids of the two bodies it joins"};
  }
  std::size_t index[2] = {0, 0};
  for (std::size_t k = 0; k < 2; ++k) {
    const std::string at = key + "[" + std::to_string(k) + "]";
    const std::string id = ReadString((*pair)[k], at);
    const auto it = body_ids.find(id);
    if (it == body_ids.end()) throw SceneError{at, "no body has the id " + Quote(id)};
    index[k] = it->second;
  }
  const SceneBody& a = bodies[index[0]];
  const SceneBody& b = bodies[index[1]];
  if (index[0] == index[1]) {
    throw SceneError{key + "[1]", "is " + Quote(a.id) + " again: a joint joins two different bodies"};
  }
  const auto immovable = [](const engine::BodyDef& body) { return body.is_static || body.is_kinematic; };
  if (immovable(a.def) && immovable(b.def)) {
    throw SceneError{key, "joins " + Quote(a.id) + " (" + Kind(a.def) + ") and " + Quote(b.id) + " (" + Kind(b.def) +
                              "): a joint needs a dynamic body, one that forces move"};
  }
  if (!rotation) {
    for (const SceneBody* body : {&a, &b}) {
      if (body->def.is_static || body->def.fixed_rotation) continue;
      throw SceneError{path, "needs \"rotation\": true in the scene, unless every body it joins is static or has "
                             "\"fixed_rotation\": true (" + Quote(body->id) + " is neither)"};
    }
  }
  // Bodies are made in scene order in a fresh world, so a body's slot is its index.
  def->body_a = engine::BodyId{static_cast<engine::BodyIndex>(index[0])};
  def->body_b = engine::BodyId{static_cast<engine::BodyIndex>(index[1])};
}

SceneJoint ReadJoint(const Json& joint, const std::string& path, std::size_t index,
                     const std::vector<SceneBody>& bodies, const std::map<std::string, std::size_t>& body_ids,
                     bool rotation) {
  if (!joint.is_object()) throw SceneError{path, "must be an object"};
  RejectUnknownKeys(joint, path,
                    {"type", "bodies", "id", "collide", "anchor", "anchors", "axis", "limits", "motor", "length",
                     "min_length", "max_length", "spring"});
  auto key = [&](const char* k) { return Join(path, k); };
  const Json* type = Find(joint, "type");
  if (!type) throw SceneError{path, "needs a \"type\" (\"revolute\", \"distance\", \"prismatic\" or \"weld\")"};
  SceneJoint out;
  engine::JointDef& def = out.def;
  def.type = ReadJointType(*type, key("type"));
  for (const char* k : kTypeKeys) {
    if (Find(joint, k) && !Takes(def.type, k)) {
      throw SceneError{key(k), std::string("applies to ") + Owners(k) + " only; " + WhatItHas(def.type)};
    }
  }

  out.id = "joint" + std::to_string(index);
  out.id_given = Find(joint, "id") != nullptr;
  if (const Json* v = Find(joint, "id")) {
    out.id = ReadString(*v, key("id"));
    if (out.id.empty()) throw SceneError{key("id"), "must not be empty"};
  }
  ReadJointBodies(joint, path, bodies, body_ids, rotation, &def);
  if (const Json* v = Find(joint, "collide")) def.collide = ReadBool(*v, key("collide"));
  ReadTypeKeys(joint, path, &def);
  return out;
}

}  // namespace

std::vector<SceneJoint> ReadJoints(const Json& joints, const std::vector<SceneBody>& bodies,
                                   const std::map<std::string, std::size_t>& body_ids, bool rotation) {
  if (!joints.is_array()) throw SceneError{"joints", "must be an array"};
  if (joints.size() > kMaxJoints) {
    throw SceneError{"joints", std::to_string(joints.size()) + " joints, more than the limit of " +
                                   std::to_string(kMaxJoints) + " (docs/limits.md)"};
  }
  std::vector<SceneJoint> out;
  out.reserve(joints.size());
  std::map<std::string, std::size_t> first_use;  // ordered: no hash-map order anywhere
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const std::string path = "joints[" + std::to_string(i) + "]";
    SceneJoint joint = ReadJoint(joints[i], path, i, bodies, body_ids, rotation);
    const auto [it, inserted] = first_use.emplace(joint.id, i);
    if (!inserted) {
      const std::string other = "joints[" + std::to_string(it->second) + "]";
      if (!joint.id_given) {
        throw SceneError{path, "its default id " + Quote(joint.id) + " is taken by " + other +
                                   "; give one of them an \"id\""};
      }
      throw SceneError{Join(path, "id"), "duplicate id " + Quote(joint.id) + " (also " + other + ")"};
    }
    out.push_back(std::move(joint));
  }
  return out;
}

}  // namespace game::scene_values
