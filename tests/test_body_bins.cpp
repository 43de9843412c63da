// The body bins the effect particles find bodies with (engine/src/particles/body_bins.h): every
// body whose bounds meet a query box, and no other, against a brute-force look at all of them,
// for bodies of every size (a long ground, a far-off body, sensors and disabled ones left out).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "bodies.h"
#include "candidate_pairs.h"
#include "particles/body_bins.h"
#include "particles/split_mix.h"

using engine::AABB;
using engine::BodyIndex;
using engine::Vec2;
using engine::detail::Bodies;
using engine::detail::BodyBins;
using engine::detail::UniformAround;

namespace {

void AddBody(Bodies* bodies, engine::ShapeType type, Vec2 position, Vec2 half, double angle, bool sensor = false,
             bool enabled = true) {
  const auto index = static_cast<BodyIndex>(bodies->states.size());
  engine::BodyInfo info;
  info.shape.type = type;
  info.shape.radius = half.x;
  info.shape.half_extents = half;
  info.is_sensor = sensor;
  bodies->states.push_back({position, {}, angle, 0.0});
  bodies->infos.push_back(info);
  bodies->geometries.emplace_back();
  bodies->generations.push_back(0);
  bodies->alive.push_back(1);
  bodies->enabled.push_back(enabled ? 1 : 0);
  bodies->live_ids.push_back({index, 0});
}

bool Meets(const AABB& a, const AABB& b) { return engine::Overlaps(a, b); }

}  // namespace

TEST_CASE("body bins: the bodies a box meets, no more and no fewer, each once", "[effects]") {
  std::uint64_t random = 42;
  Bodies bodies;
  AddBody(&bodies, engine::ShapeType::kBox, {0, -0.5}, {500.0, 0.5}, 0.0);  // a long ground: set aside
  for (int i = 0; i < 200; ++i) {
    const Vec2 at{UniformAround(0.0, 30.0, &random), UniformAround(10.0, 10.0, &random)};
    const double size = UniformAround(0.5, 0.45, &random);
    if (i % 2 == 0) {
      AddBody(&bodies, engine::ShapeType::kCircle, at, {size, size}, 0.0);
    } else {
      AddBody(&bodies, engine::ShapeType::kBox, at, {size, 0.5 * size}, UniformAround(0.0, 3.0, &random));
    }
  }
  AddBody(&bodies, engine::ShapeType::kCircle, {1.0e6, 1.0e6}, {1.0, 1.0}, 0.0);  // far off
  AddBody(&bodies, engine::ShapeType::kBox, {0, 5}, {2, 2}, 0.0, /*sensor=*/true);
  AddBody(&bodies, engine::ShapeType::kBox, {0, 8}, {2, 2}, 0.0, /*sensor=*/false, /*enabled=*/false);
  for (const double margin : {0.0, 0.3, 2.0}) {
    BodyBins bins;
    bins.Build(bodies, margin);
    std::size_t found_any = 0;
    for (int q = 0; q < 4000; ++q) {
      // A point, and a box within the margin of it, sometimes near the far body or past the edges.
      Vec2 anchor{UniformAround(0.0, 40.0, &random), UniformAround(10.0, 15.0, &random)};
      if (q % 100 == 0) anchor = {1.0e6 + UniformAround(0.0, 2.0, &random), 1.0e6};
      const Vec2 a{anchor.x + UniformAround(0.0, margin, &random), anchor.y + UniformAround(0.0, margin, &random)};
      const AABB box{{std::min(anchor.x, a.x), std::min(anchor.y, a.y)}, {std::max(anchor.x, a.x), std::max(anchor.y, a.y)}};
      std::vector<BodyIndex> got, want;
      bins.ForEachOverlapping(anchor, box, [&](BodyIndex b) { got.push_back(b); });
      for (const engine::BodyId id : bodies.live_ids) {
        const BodyIndex b = id.index;
        if (bodies.enabled[b] && !bodies.infos[b].is_sensor && Meets(engine::detail::BoundsOf(bodies, b), box)) {
          want.push_back(b);
        }
      }
      std::vector<BodyIndex> sorted = got;
      std::sort(sorted.begin(), sorted.end());
      REQUIRE(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end());  // each once
      REQUIRE(sorted == want);
      found_any += !got.empty();
    }
    CHECK(found_any > 400);  // the queries did meet bodies
  }
}

TEST_CASE("body bins: no bodies, or only sensors, find nothing", "[effects]") {
  Bodies bodies;
  BodyBins bins;
  bins.Build(bodies, 1.0);
  CHECK(bins.Empty());
  AddBody(&bodies, engine::ShapeType::kCircle, {0, 0}, {1, 1}, 0.0, /*sensor=*/true);
  bins.Build(bodies, 1.0);
  CHECK(bins.Empty());
  int visits = 0;
  bins.ForEachOverlapping({0, 0}, {{-1, -1}, {1, 1}}, [&](BodyIndex) { ++visits; });
  CHECK(visits == 0);
}
