// Engine-neutral scenes for the side-by-side benchmark (accuracy.md §3, two analytic ones and
// jointed chains and grids), the interface every engine adapter implements, and figures measured
// from body states alone.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "bench/scene_rules.h"
#include "engine/math.h"

namespace peers {

using bench::kBallDrop;
using bench::kBallRadius;
using bench::kBallRestitution;
using bench::kCradleSpeed;
using engine::Vec2;

enum class Kind : std::uint8_t { kCircle, kBox };

struct BodySpec {
  Kind kind = Kind::kBox;
  Vec2 half{0.5, 0.5};  ///< boxes: half extents, m
  double radius = 0.5;  ///< circles, m
  Vec2 position;
  Vec2 velocity;
  bool is_static = false;
  double mass = 0;      ///< kg, set explicitly in every engine (not left to its density rules)
  double inertia = 0;   ///< kg·m² about the centre
  /// A box handed to the engine as a general convex polygon (its four corners), not as a box:
  /// ballbox's polygon path instead of its box path. Box2D and Chipmunk collide boxes as
  /// polygons anyway, so for them it is the same body.
  bool as_polygon = false;
  /// > 0: never collides with a body of the same group (ballbox's and Box2D's negative group
  /// index, Chipmunk's shape-filter group); 0: collides with everything.
  int group = 0;
};

/// A revolute joint: the two bodies (scene indices, at most one static) share a point and turn
/// freely about it. The bodies stop colliding with each other, in every engine (ballbox's joints
/// by default, Box2D's collideConnected false, Chipmunk's collideBodies false).
struct JointSpec {
  std::size_t body_a = 0;
  std::size_t body_b = 0;
  Vec2 anchor;  ///< the shared point, world, at the start (every body starts unturned)
};

/// One scene as every engine builds it: the same bodies, one material for every shape (so the
/// engines' different mixing rules give the same pair values), 60 Hz.
struct SceneSpec {
  std::string name;
  Vec2 gravity{0, -9.8};
  double dt = 1.0 / 60.0;
  int steps = 600;
  /// false: nothing turns (ballbox's axis-aligned world; the peers' bodies get fixed rotation)
  bool rotation = false;
  double friction = 0.6;
  double restitution = 0.2;
  std::vector<BodySpec> bodies;
  std::vector<JointSpec> joints;
  engine::AABB bounds{{-1e9, -1e9}, {1e9, 1e9}};  ///< a dynamic body outside has escaped
};

/// What every engine reports back, in scene order (statics included).
struct State {
  Vec2 position;
  Vec2 velocity;
  double angle = 0;
  double angular_velocity = 0;
};

class PhysicsEngine {
 public:
  virtual ~PhysicsEngine() = default;
  virtual std::string Name() const = 0;
  /// The solver settings, stated beside every figure.
  virtual std::string Settings(const SceneSpec& scene) const = 0;
  virtual void Build(const SceneSpec& scene) = 0;
  virtual void Step() = 0;
  virtual void Read(std::vector<State>& out) const = 0;
  /// The joints the engine holds, so a test can see every adapter built the scene's.
  virtual std::size_t JointCount() const = 0;
};

using EngineFactory = std::function<std::unique_ptr<PhysicsEngine>()>;

// --- Building scenes: the parameters of bench/stress_scenes.h, written once for every engine.

inline BodySpec Box(Vec2 center, Vec2 size, double density = 1.0, bool is_static = false) {
  BodySpec b;
  b.kind = Kind::kBox;
  b.half = 0.5 * size;
  b.position = center;
  b.is_static = is_static;
  if (!is_static) {
    b.mass = density * size.x * size.y;
    b.inertia = b.mass * (size.x * size.x + size.y * size.y) / 12.0;
  }
  return b;
}

inline BodySpec Circle(Vec2 center, double radius, Vec2 velocity = {}) {
  BodySpec b;
  b.kind = Kind::kCircle;
  b.radius = radius;
  b.half = {radius, radius};
  b.position = center;
  b.velocity = velocity;
  b.mass = 3.14159265358979323846 * radius * radius;
  b.inertia = 0.5 * b.mass * radius * radius;
  return b;
}

inline void AddPyramid(SceneSpec& s, int base, double overlap = 0.0, bool polygons = false) {
  s.bodies.push_back(Box({0, -0.5}, {2.0 * base + 20, 1}, 1, true));
  s.bodies.back().as_polygon = polygons;
  const double pitch = 1.0 - overlap;
  for (int row = 0; row < base; ++row) {
    const int n = base - row;
    for (int i = 0; i < n; ++i) {
      s.bodies.push_back(Box({(i - 0.5 * (n - 1)) * pitch, 0.5 + row * pitch}, {1, 1}));
      s.bodies.back().as_polygon = polygons;
    }
  }
  s.bounds = {{-base - 10.0, -1}, {base + 10.0, base + 10.0}};
}

/// A closed box container of inner size width × height, walls 1 m thick.
inline void AddContainer(SceneSpec& s, double width, double height, double bottom = 0.0) {
  s.bodies.push_back(Box({0, bottom - 0.5}, {width + 2, 1}, 1, true));
  s.bodies.push_back(Box({-0.5 * (width + 1), bottom + 0.5 * height}, {1, height}, 1, true));
  s.bodies.push_back(Box({0.5 * (width + 1), bottom + 0.5 * height}, {1, height}, 1, true));
  s.bodies.push_back(Box({0, bottom + height + 0.5}, {width + 2, 1}, 1, true));
  s.bounds = {{-0.5 * width, bottom}, {0.5 * width, bottom + height}};
}

/// `count` bodies on a jittered grid from the container's floor with random velocities of up to
/// 1 m/s: circles of `size` radius, or boxes of `size` half extent (stress::AddCirclePour's rule).
inline void AddPour(SceneSpec& s, int count, double size, double width, bool boxes, std::uint64_t seed = 1) {
  bench::JitteredGrid(count, size, width, seed, [&](Vec2 at, Vec2 velocity) {
    BodySpec b = boxes ? Box(at, {2 * size, 2 * size}) : Circle(at, size);
    b.velocity = velocity;
    s.bodies.push_back(b);
  });
}

/// A square container for `count` bodies of `size` poured as above, about half full when settled.
inline SceneSpec ScalingScene(int count, bool boxes) {
  SceneSpec s;
  s.name = std::string(boxes ? "box pile " : "circle pour ") + std::to_string(count);
  const double size = 0.25, pitch = 2.3 * size;
  const double width = pitch * (std::ceil(std::sqrt(static_cast<double>(count))) + 2);
  const int per_row = static_cast<int>((width - pitch) / pitch);
  const double height = pitch * (count / per_row + 3);
  AddContainer(s, width, height);
  AddPour(s, count, size, width, boxes);
  return s;
}

// --- Figures from states alone, so every engine is judged by the same yardstick.

struct Figure {
  std::string name;
  std::string unit;
  double value = std::numeric_limits<double>::quiet_NaN();
};

inline bool Finite(const State& s) {
  return std::isfinite(s.position.x) && std::isfinite(s.position.y) && std::isfinite(s.velocity.x) &&
         std::isfinite(s.velocity.y) && std::isfinite(s.angle) && std::isfinite(s.angular_velocity);
}

/// How deep two bodies overlap (negative: the gap along the best separating axis), from their
/// outlines: circles exactly, boxes (turned or not) by the separating-axis test.
inline double Penetration(const BodySpec& a, const State& sa, const BodySpec& b, const State& sb) {
  if (a.kind == Kind::kCircle && b.kind == Kind::kCircle) {
    return a.radius + b.radius - engine::Length(sb.position - sa.position);
  }
  if (a.kind == Kind::kBox && b.kind == Kind::kCircle) return Penetration(b, sb, a, sa);
  if (a.kind == Kind::kCircle) {
    const engine::Rot q = engine::MakeRot(sb.angle);
    const Vec2 local = engine::InvRotate(q, sa.position - sb.position);
    const Vec2 clamped{engine::Clamp(local.x, -b.half.x, b.half.x), engine::Clamp(local.y, -b.half.y, b.half.y)};
    if (clamped == local) {  // centre inside the box: out through the nearest face
      return a.radius + std::min(b.half.x - std::abs(local.x), b.half.y - std::abs(local.y));
    }
    return a.radius - engine::Length(local - clamped);
  }
  const engine::Rot qa = engine::MakeRot(sa.angle), qb = engine::MakeRot(sb.angle);
  const Vec2 axes[4] = {engine::Rotate(qa, {1, 0}), engine::Rotate(qa, {0, 1}), engine::Rotate(qb, {1, 0}),
                        engine::Rotate(qb, {0, 1})};
  const Vec2 d = sb.position - sa.position;
  double depth = std::numeric_limits<double>::infinity();
  for (const Vec2& n : axes) {
    const auto extent = [&](const BodySpec& body, engine::Rot q) {
      return std::abs(engine::Dot(engine::Rotate(q, {body.half.x, 0}), n)) +
             std::abs(engine::Dot(engine::Rotate(q, {0, body.half.y}), n));
    };
    depth = std::min(depth, extent(a, qa) + extent(b, qb) - std::abs(engine::Dot(d, n)));
  }
  return depth;
}

/// The deepest overlap between any two bodies, m (0 when nothing overlaps). Dynamic pairs are
/// found through a uniform grid, statics are tested against every dynamic body.
inline double MaxOverlap(const SceneSpec& scene, const std::vector<State>& states) {
  std::vector<std::size_t> dynamic, statics;
  double reach = 0;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (!Finite(states[i])) continue;
    const BodySpec& b = scene.bodies[i];
    (b.is_static ? statics : dynamic).push_back(i);
    if (!b.is_static) reach = std::max(reach, b.kind == Kind::kCircle ? b.radius : engine::Length(b.half));
  }
  double deepest = 0;
  for (std::size_t s : statics) {
    for (std::size_t i : dynamic) deepest = std::max(deepest, Penetration(scene.bodies[s], states[s], scene.bodies[i], states[i]));
  }
  if (dynamic.empty()) return deepest;
  const double cell = 2 * reach;
  const auto key = [&](Vec2 p) {
    return std::pair<long, long>{static_cast<long>(std::floor(p.x / cell)), static_cast<long>(std::floor(p.y / cell))};
  };
  std::vector<std::pair<std::pair<long, long>, std::size_t>> cells;
  cells.reserve(dynamic.size());
  for (std::size_t i : dynamic) cells.push_back({key(states[i].position), i});
  std::sort(cells.begin(), cells.end());
  for (std::size_t i : dynamic) {
    const auto [cx, cy] = key(states[i].position);
    for (long dx = -1; dx <= 1; ++dx) {
      for (long dy = -1; dy <= 1; ++dy) {
        const std::pair<long, long> k{cx + dx, cy + dy};
        auto it = std::lower_bound(cells.begin(), cells.end(), std::pair{k, std::size_t{0}});
        for (; it != cells.end() && it->first == k; ++it) {
          if (it->second <= i) continue;
          deepest = std::max(deepest, Penetration(scene.bodies[i], states[i], scene.bodies[it->second], states[it->second]));
        }
      }
    }
  }
  return deepest;
}

inline double KineticEnergy(const SceneSpec& scene, const std::vector<State>& states) {
  double energy = 0;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodySpec& b = scene.bodies[i];
    if (b.is_static) continue;
    energy += 0.5 * b.mass * engine::Dot(states[i].velocity, states[i].velocity);
    if (scene.rotation) energy += 0.5 * b.inertia * states[i].angular_velocity * states[i].angular_velocity;
  }
  return energy;
}

inline double MaxDrift(const SceneSpec& scene, const std::vector<State>& states) {
  double drift = 0;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    drift = std::max(drift, engine::Length(states[i].position - scene.bodies[i].position));
  }
  return drift;
}

inline int Escaped(const SceneSpec& scene, const std::vector<State>& states) {
  int escaped = 0;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].is_static) continue;
    const Vec2 p = states[i].position;
    const bool inside = p.x > scene.bounds.lower.x && p.x < scene.bounds.upper.x && p.y > scene.bounds.lower.y &&
                        p.y < scene.bounds.upper.y;
    escaped += Finite(states[i]) && inside ? 0 : 1;
  }
  return escaped;
}

/// A joint's point on each body now, from the bodies' states alone: its offset from the body's
/// centre at the start (every body starts unturned), turned with the body.
inline std::pair<Vec2, Vec2> JointAnchors(const SceneSpec& scene, const JointSpec& joint, const std::vector<State>& states) {
  const auto on = [&](std::size_t i) {
    return states[i].position + engine::Rotate(engine::MakeRot(states[i].angle), joint.anchor - scene.bodies[i].position);
  };
  return {on(joint.body_a), on(joint.body_b)};
}

/// The larger of two figures, NaN if either is: a run that blew up must not read as a good one.
inline double MaxOrNaN(double a, double b) {
  return std::isnan(a) || std::isnan(b) ? std::numeric_limits<double>::quiet_NaN() : std::max(a, b);
}

/// The widest gap between a joint's two points over every joint, m: how far the joints came apart.
inline double MaxJointGap(const SceneSpec& scene, const std::vector<State>& states) {
  double widest = 0;
  for (const JointSpec& joint : scene.joints) {
    const auto [a, b] = JointAnchors(scene, joint, states);
    widest = MaxOrNaN(widest, engine::Length(b - a));
  }
  return widest;
}

/// FNV-1a 64 over the raw bits of every position and velocity: a timed run must end where the
/// figure run ended, or it did different work.
inline std::uint64_t Hash(const std::vector<State>& states) {
  std::uint64_t hash = 14695981039346656037ull;
  for (const State& s : states) {
    for (double v : {s.position.x, s.position.y, s.velocity.x, s.velocity.y, s.angle, s.angular_velocity}) {
      std::uint64_t bits;
      std::memcpy(&bits, &v, sizeof bits);
      for (int k = 0; k < 8; ++k) hash = (hash ^ ((bits >> (8 * k)) & 0xff)) * 1099511628211ull;
    }
  }
  return hash;
}

/// A scene of the side-by-side table: its spec, how to step and measure it, and the figure whose
/// ratio to ballbox's the table prints (the first of `figures`).
struct Scene {
  SceneSpec spec;
  /// Steps the freshly built engine `steps` times and measures; some figures need samples along
  /// the way (apexes, the fastest body), so the stepping lives here.
  std::function<std::vector<Figure>(PhysicsEngine&, const SceneSpec&, int steps)> measure;
  bool sweep = false;  ///< also run ballbox's solver settings (scenes bench_solver does not have)
};

inline void StepN(PhysicsEngine& engine, int steps) {
  for (int i = 0; i < steps; ++i) engine.Step();
}

inline std::vector<Figure> RestingFigures(PhysicsEngine& engine, const SceneSpec& scene, int steps) {
  StepN(engine, steps);
  std::vector<State> s;
  engine.Read(s);
  return {{"max drift", "m", MaxDrift(scene, s)},
          {"max overlap", "m", MaxOverlap(scene, s)},
          {"kinetic energy", "J", KineticEnergy(scene, s)}};
}

inline std::vector<Figure> ContainedFigures(PhysicsEngine& engine, const SceneSpec& scene, int steps) {
  StepN(engine, steps);
  std::vector<State> s;
  engine.Read(s);
  return {{"max overlap", "m", MaxOverlap(scene, s)},
          {"escaped", "", static_cast<double>(Escaped(scene, s))},
          {"kinetic energy", "J", KineticEnergy(scene, s)}};
}

// --- Joint scenes (issue 17): chains and a grid held by revolute joints.

/// A small static anchor at `pivot` and `links` boxes of `size` (world axes) and `density` laid
/// end to end from it along `direction` (a unit axis), each joined to the one before at their
/// shared end, the first to the anchor. Returns the last link's index.
inline std::size_t AddChain(SceneSpec& s, Vec2 pivot, Vec2 direction, int links, Vec2 size, double density) {
  s.bodies.push_back(Box(pivot, {0.1, 0.1}, 1, true));
  const double length = std::abs(engine::Dot(size, direction));
  for (int i = 0; i < links; ++i) {
    s.bodies.push_back(Box(pivot + (length * (i + 0.5)) * direction, size, density));
    s.joints.push_back({s.bodies.size() - 2, s.bodies.size() - 1, pivot + (length * i) * direction});
  }
  return s.bodies.size() - 1;
}

/// The joint scenes' figures, sampled after every step: the widest joint gap over the run and at
/// the end, and, for a scene with a `weight` (body index), how far the weight sank below where it
/// started (its rigid position: the chain starts straight and unstretched) at its lowest.
inline std::vector<Figure> JointFigures(PhysicsEngine& engine, const SceneSpec& scene, int steps,
                                        std::optional<std::size_t> weight = std::nullopt) {
  std::vector<State> s;
  double widest = 0, sank = 0;
  for (int i = 0; i < steps; ++i) {
    engine.Step();
    engine.Read(s);
    widest = MaxOrNaN(widest, MaxJointGap(scene, s));
    if (weight) sank = MaxOrNaN(sank, scene.bodies[*weight].position.y - s[*weight].position.y);
  }
  std::vector<Figure> figures = {{"max joint gap", "mm", 1000 * widest},
                                 {"joint gap at end", "mm", 1000 * MaxJointGap(scene, s)}};
  if (weight) figures.push_back({"weight sank (max)", "mm", 1000 * sank});
  return figures;
}

/// The joint scenes: a chain falling from horizontal, a heavy weight on a light chain, and Box2D's
/// joint grid benchmark (its "joint_grid": 100 × 100 circles of radius 0.4 m, 1 m apart, each
/// joined to its right and lower neighbours, the seven middle bodies of the top row static, no
/// contacts), under gravity. Bodies turn.
inline std::vector<Scene> JointScenes() {
  std::vector<Scene> out;
  Scene chain;
  chain.spec.name = "chain 20 horizontal";
  chain.spec.rotation = true;
  AddChain(chain.spec, {0, 0}, {1, 0}, 20, {0.5, 0.1}, 1.0);
  chain.measure = [](PhysicsEngine& engine, const SceneSpec& scene, int steps) {
    return JointFigures(engine, scene, steps);
  };
  out.push_back(chain);

  // Ten 50 g links of 4 × 25 cm and a 50 kg box of 50 × 50 cm hanging straight from the anchor,
  // at rest: the weight's own joint carries 1000 times a link's weight.
  Scene heavy;
  heavy.spec.name = "heavy chain 1000:1";
  heavy.spec.rotation = true;
  const Vec2 link{0.04, 0.25};
  const std::size_t last = AddChain(heavy.spec, {0, 0}, {0, -1}, 10, link, 0.05 / (link.x * link.y));
  const Vec2 end = heavy.spec.bodies[last].position - Vec2{0, 0.5 * link.y};
  heavy.spec.bodies.push_back(Box(end - Vec2{0, 0.25}, {0.5, 0.5}, 50.0 / 0.25));
  heavy.spec.joints.push_back({last, heavy.spec.bodies.size() - 1, end});
  heavy.measure = [weight = heavy.spec.bodies.size() - 1](PhysicsEngine& engine, const SceneSpec& scene, int steps) {
    return JointFigures(engine, scene, steps, weight);
  };
  out.push_back(heavy);

  // Box2D's layout, body k·N + i at (k, −i); a joint between two static bodies holds nothing
  // (and ballbox refuses one), so the six along the static stretch of the top row are left out.
  constexpr int kGrid = 100;
  Scene grid;
  grid.spec.name = "joint grid 100 x 100";
  grid.spec.rotation = true;
  grid.spec.steps = 120;
  for (int k = 0; k < kGrid; ++k) {
    for (int i = 0; i < kGrid; ++i) {
      const Vec2 at{static_cast<double>(k), -static_cast<double>(i)};
      BodySpec body = Circle(at, 0.4);
      body.group = 1;
      if (i == 0 && k >= kGrid / 2 - 3 && k <= kGrid / 2 + 3) {
        body.is_static = true;
        body.mass = body.inertia = 0;
      }
      grid.spec.bodies.push_back(body);
      const std::size_t index = grid.spec.bodies.size() - 1;
      const auto join = [&](std::size_t other, Vec2 anchor) {
        if (!(grid.spec.bodies[other].is_static && body.is_static)) grid.spec.joints.push_back({other, index, anchor});
      };
      if (i > 0) join(index - 1, at + Vec2{0, 0.5});
      if (k > 0) join(index - kGrid, at - Vec2{0.5, 0});
    }
  }
  grid.measure = [](PhysicsEngine& engine, const SceneSpec& scene, int steps) {
    std::vector<Figure> figures = JointFigures(engine, scene, steps);
    std::swap(figures[0], figures[1]);  // the end state is the headline: it is the cost scene
    return figures;
  };
  out.push_back(grid);
  return out;
}

/// Every scene of the side-by-side table: the stress scenes of bench_solver (same names, same
/// parameters), confined circles, the turning versions of the box scenes, two analytic ones, and
/// the joint scenes.
inline std::vector<Scene> Scenes() {
  std::vector<Scene> out;
  const auto resting = [&](std::string name, bool rotation, std::function<void(SceneSpec&)> build) {
    Scene scene;
    scene.spec.name = std::move(name);
    scene.spec.rotation = rotation;
    build(scene.spec);
    scene.measure = RestingFigures;
    return scene;
  };
  for (bool rotation : {false, true}) {
    const std::string turning = rotation ? " (turning)" : "";
    out.push_back(resting("pyramid base 20" + turning, rotation, [](SceneSpec& s) { AddPyramid(s, 20); }));
    out.push_back(resting("pyramid base 40" + turning, rotation, [](SceneSpec& s) { AddPyramid(s, 40); }));
    if (rotation) {
      out.push_back(resting("polygon pyramid base 20 (turning)", true,
                            [](SceneSpec& s) { AddPyramid(s, 20, 0.0, true); }));
    }
    out.push_back(resting("stack of 20" + turning, rotation, [](SceneSpec& s) {
      s.bodies.push_back(Box({0, -0.5}, {20, 1}, 1, true));
      for (int i = 0; i < 20; ++i) s.bodies.push_back(Box({0, 0.5 + i}, {1, 1}));
    }));

    Scene heavy = resting("heavy on light 1000:1" + turning, rotation, [](SceneSpec& s) {
      s.bodies.push_back(Box({0, -0.5}, {20, 1}, 1, true));
      for (int i = 0; i < 3; ++i) s.bodies.push_back(Box({0, 0.5 + i}, {1, 1}));
      s.bodies.push_back(Box({0, 3.5}, {4, 1}, 1e3 / 4));
    });
    heavy.measure = [](PhysicsEngine& engine, const SceneSpec& scene, int steps) {
      StepN(engine, steps);
      std::vector<State> s;
      engine.Read(s);
      return std::vector<Figure>{{"heavy box sank", "m", scene.bodies.back().position.y - s.back().position.y},
                                 {"max overlap", "m", MaxOverlap(scene, s)},
                                 {"kinetic energy", "J", KineticEnergy(scene, s)}};
    };
    out.push_back(heavy);

    Scene overlap = resting("overlap recovery (base 4, 25%)" + turning, rotation,
                            [](SceneSpec& s) { AddPyramid(s, 4, 0.25); });
    overlap.spec.steps = 60;
    overlap.measure = [](PhysicsEngine& engine, const SceneSpec& scene, int steps) {
      double fastest = 0;
      std::vector<State> s;
      for (int i = 0; i < steps; ++i) {
        engine.Step();
        engine.Read(s);
        for (const State& b : s) fastest = std::max(fastest, engine::Length(b.velocity));
      }
      return std::vector<Figure>{{"overlap left", "m", MaxOverlap(scene, s)},
                                 {"fastest body", "m/s", fastest},
                                 {"kinetic energy", "J", KineticEnergy(scene, s)}};
    };
    out.push_back(overlap);

    Scene pour;
    pour.spec.name = "pour 4000 circles r 0.25" + turning;
    pour.spec.rotation = rotation;
    AddContainer(pour.spec, 40, 40);
    AddPour(pour.spec, 4000, 0.25, 40, false);
    pour.measure = ContainedFigures;
    out.push_back(pour);
  }

  // Packed without gravity: 625 circles on a grid 4 cm tighter than their size inside walls
  // with room for exactly a square grid of them (78.5% of the floor covered), scattered at up
  // to 1 m/s. With no gravity the kinetic energy can only fall: its peak over the start shows
  // energy the solver made.
  Scene confined;
  confined.spec.name = "confined 625 circles";
  confined.spec.gravity = {0, 0};
  AddContainer(confined.spec, 25, 25, -12.5);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> speed(-1.0, 1.0);
  for (int i = 0; i < 625; ++i) {
    const Vec2 at{0.96 * (i % 25 - 12), 0.96 * (i / 25 - 12)};
    const Vec2 velocity{speed(rng), speed(rng)};
    confined.spec.bodies.push_back(Circle(at, 0.5, velocity));
  }
  confined.measure = [](PhysicsEngine& engine, const SceneSpec& scene, int steps) {
    std::vector<State> s;
    engine.Read(s);
    const double start = KineticEnergy(scene, s);
    double peak = start;
    for (int i = 0; i < steps; ++i) {
      engine.Step();
      engine.Read(s);
      peak = std::max(peak, KineticEnergy(scene, s));
    }
    return std::vector<Figure>{{"peak / start kinetic energy", "", peak / start},
                               {"max overlap", "m", MaxOverlap(scene, s)},
                               {"kinetic energy", "J", KineticEnergy(scene, s)},
                               {"escaped", "", static_cast<double>(Escaped(scene, s))}};
  };
  confined.sweep = true;
  out.push_back(confined);

  // bench_solver's bouncing ball: apexes above the contact height sampled at the end of every
  // step, against e^(2n)·h0 (restitution 0.8 for ball and floor: every engine's mix gives 0.8).
  Scene ball;
  ball.spec.name = "bouncing ball e 0.8 from 10 m";
  ball.spec.gravity = {0, -9.81};
  ball.spec.restitution = kBallRestitution;
  ball.spec.bodies.push_back(Box({0, -0.5}, {4, 1}, 1, true));
  ball.spec.bodies.push_back(Circle({0, kBallDrop + kBallRadius}, kBallRadius));
  ball.measure = [](PhysicsEngine& engine, const SceneSpec&, int steps) {
    bench::BounceApexes apexes;
    std::vector<State> s;
    for (int i = 0; i < steps; ++i) {
      engine.Step();
      engine.Read(s);
      apexes.Observe(s[1].position.y, s[1].velocity.y);
    }
    return std::vector<Figure>{{"max apex error", "", apexes.WorstError()},
                               {"bounces", "", static_cast<double>(apexes.Bounces())}};
  };
  out.push_back(ball);

  Scene cradle;
  cradle.spec.name = "Newton's cradle, 5 + striker";
  cradle.spec.gravity = {0, 0};
  cradle.spec.steps = 120;
  cradle.spec.restitution = 1.0;
  cradle.spec.friction = 0.0;
  cradle.spec.bodies.push_back(Circle({-3, 0}, 0.5, {kCradleSpeed, 0}));
  for (int i = 0; i < 5; ++i) cradle.spec.bodies.push_back(Circle({static_cast<double>(i), 0}, 0.5));
  cradle.measure = [](PhysicsEngine& engine, const SceneSpec&, int steps) {
    StepN(engine, steps);
    std::vector<State> s;
    engine.Read(s);
    double others = 0;
    for (std::size_t i = 0; i + 1 < s.size(); ++i) others = std::max(others, engine::Length(s[i].velocity));
    // The figure is |ratio − 1|, so smaller is better like every other headline figure.
    return std::vector<Figure>{{"last ball speed error", "", std::abs(engine::Length(s.back().velocity) / kCradleSpeed - 1)},
                               {"others' max speed", "m/s", others}};
  };
  out.push_back(cradle);

  // accuracy.md S1 at one step per frame: free flight, where only the integrator and the step count.
  Scene projectile;
  projectile.spec.name = "projectile (S1), 2 s";
  projectile.spec.gravity = {0, -9.81};
  projectile.spec.steps = 120;
  projectile.spec.bodies.push_back(Circle({0, 0}, 0.5, {10, 10}));
  projectile.measure = [](PhysicsEngine& engine, const SceneSpec& scene, int steps) {
    StepN(engine, steps);
    std::vector<State> s;
    engine.Read(s);
    const double t = steps * scene.dt;
    const Vec2 exact{10 * t, 10 * t - 0.5 * 9.81 * t * t};
    return std::vector<Figure>{{"position error", "m", engine::Length(s[0].position - exact)}};
  };
  out.push_back(projectile);
  for (Scene& scene : JointScenes()) out.push_back(std::move(scene));
  return out;
}

/// Builds the scene, steps it `untimed` times (structures built, caches warm: Box2D's benchmark
/// leaves its first step out too), then times `timed` steps. Returns ms per timed step and the
/// end state's hash.
inline std::pair<double, std::uint64_t> TimeSteps(PhysicsEngine& engine, const SceneSpec& scene, int untimed, int timed) {
  engine.Build(scene);
  StepN(engine, untimed);
  const auto start = std::chrono::steady_clock::now();
  StepN(engine, timed);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::vector<State> s;
  engine.Read(s);
  return {1000.0 * seconds / std::max(1, timed), Hash(s)};
}

}  // namespace peers
