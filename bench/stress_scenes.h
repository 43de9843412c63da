// The solver stress scenes (accuracy.md §3), shared by the benchmark and the stability tests.
#pragma once

#include <cmath>
#include <cstdint>

#include "bench/scene_rules.h"
#include "engine/world.h"

namespace stress {

inline engine::BodyDef Box(engine::Vec2 center, engine::Vec2 size, double density = 1.0) {
  engine::BodyDef def;
  def.shape.type = engine::ShapeType::kBox;
  def.shape.half_extents = 0.5 * size;
  def.position = center;
  def.density = density;
  def.friction = 0.6;
  return def;
}

inline engine::BodyDef Ground(engine::Vec2 center, engine::Vec2 size) {
  engine::BodyDef def = Box(center, size);
  def.is_static = true;
  return def;
}

/// A pyramid of 1×1 boxes on a static ground: `base` boxes at the bottom, one fewer each row.
/// `overlap` packs the rows into each other by that fraction of a box (0.25 for the
/// overlap-recovery scene).
/// `gap` leaves that much air under every row, so the pyramid first has to fall into place.
inline void AddPyramid(engine::World& world, int base, double overlap = 0.0, double gap = 0.0) {
  world.CreateBody(Ground({0, -0.5}, {2.0 * base + 20, 1}));
  const double pitch = 1.0 - overlap;
  for (int row = 0; row < base; ++row) {
    const int n = base - row;
    for (int i = 0; i < n; ++i) {
      world.CreateBody(Box({(i - 0.5 * (n - 1)) * pitch, 0.5 + row * pitch + (row + 1) * gap}, {1, 1}));
    }
  }
}

/// A vertical stack of `count` 1×1 boxes.
inline void AddStack(engine::World& world, int count) {
  world.CreateBody(Ground({0, -0.5}, {20, 1}));
  for (int i = 0; i < count; ++i) world.CreateBody(Box({0, 0.5 + i}, {1, 1}));
}

/// A column of `count` small boxes (1 kg each) under a wide box `ratio` times heavier.
inline void AddHeavyOnLight(engine::World& world, int count, double ratio) {
  world.CreateBody(Ground({0, -0.5}, {20, 1}));
  for (int i = 0; i < count; ++i) world.CreateBody(Box({0, 0.5 + i}, {1, 1}));
  const engine::Vec2 size{4, 1};
  world.CreateBody(Box({0, count + 0.5 * size.y}, size, ratio / (size.x * size.y)));
}

/// A closed box container (inner width `width`, walls `height` high) with a lid.
inline void AddContainer(engine::World& world, double width, double height) {
  const double t = 1.0;
  world.CreateBody(Ground({0, -0.5 * t}, {width + 2 * t, t}));
  world.CreateBody(Ground({-0.5 * (width + t), 0.5 * height}, {t, height}));
  world.CreateBody(Ground({0.5 * (width + t), 0.5 * height}, {t, height}));
  world.CreateBody(Ground({0, height + 0.5 * t}, {width + 2 * t, t}));
}

/// `count` circles of radius `radius` on a jittered grid filling the container from the floor.
inline void AddCirclePour(engine::World& world, int count, double radius, double width,
                          double restitution = 0.2, std::uint64_t seed = 1) {
  bench::JitteredGrid(count, radius, width, seed, [&](engine::Vec2 position, engine::Vec2 velocity) {
    engine::BodyDef def;
    def.shape.radius = radius;
    def.position = position;
    def.velocity = velocity;
    def.restitution = restitution;
    def.friction = 0.6;
    world.CreateBody(def);
  });
}

/// A pour of `count` circles 0.1 m in radius into a closed container a fifth of √count × 1.2 m
/// wide and four times as tall.
inline void AddBoxedPour(engine::World& world, int count) {
  const double width = 1.2 * std::sqrt(static_cast<double>(count)) * 0.2;
  AddContainer(world, width, 4.0 * width);
  AddCirclePour(world, count, 0.1, width - 0.4);
}

}  // namespace stress
