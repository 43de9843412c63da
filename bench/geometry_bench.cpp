// The geometry layer's per-call cost (issue 16): manifolds, GJK, time of impact and ray casts on
// fixed random placements, in nanoseconds per call of thread CPU time (median of 9 repeats), with
// the oriented-box collider beside the polygon one on the same boxes.
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "bench/bench_common.h"
#include "geometry/chain.h"
#include "geometry/gjk.h"
#include "geometry/manifold.h"
#include "geometry/ray_cast.h"
#include "geometry/time_of_impact.h"
#include "narrow_phase/collide.h"

using engine::Manifold;
using engine::Rot;
using engine::Vec2;
using namespace engine::geometry;

namespace {

constexpr int kPlacements = 1024;

class Random {
 public:
  double Uniform(double lo, double hi) { return lo + (hi - lo) * (static_cast<double>(engine_() >> 11) * 0x1.0p-53); }
  Vec2 InBox(double half) { return {Uniform(-half, half), Uniform(-half, half)}; }
  Rot AnyRotation() {
    const Vec2 v{Uniform(-1, 1), Uniform(-1, 1) + 1e-3};
    const double length = engine::Length(v);
    return {v.x / length, v.y / length};
  }

 private:
  std::mt19937_64 engine_{16};
};

Polygon RegularPolygon(int n, double radius) {
  std::vector<Vec2> points;
  for (int i = 0; i < n; ++i) {
    const double a = 6.283185307179586 * i / n;
    points.push_back({radius * std::cos(a), radius * std::sin(a)});
  }
  return MakePolygon(points);
}

// Nanoseconds per call of `call(i)` over the placements, the median of 9 repeats.
template <typename Call>
double NanosecondsPerCall(Call call) {
  std::vector<double> repeats;
  volatile int sink = 0;
  for (int repeat = 0; repeat < 9; ++repeat) {
    const double start = bench::ThreadSeconds();
    for (int round = 0; round < 20; ++round) {
      for (int i = 0; i < kPlacements; ++i) sink = sink + call(i);
    }
    repeats.push_back((bench::ThreadSeconds() - start) * 1e9 / (20.0 * kPlacements));
  }
  return bench::Median(repeats);
}

void Row(const char* what, double ns) { std::printf("| %-44s | %8s |\n", what, bench::Number(ns, "%.0f").c_str()); }

}  // namespace

int main() {
  const std::string load = bench::LoadAverage();
  Random rng;
  std::vector<Transform> near_a, near_b;
  std::vector<engine::OrientedBox> boxes_a, boxes_b;
  for (int i = 0; i < kPlacements; ++i) {
    near_a.push_back({rng.InBox(0.3), rng.AnyRotation()});
    near_b.push_back({rng.InBox(1.6), rng.AnyRotation()});
    boxes_a.push_back({near_a[i].position, {0.5, 0.5}, near_a[i].rotation});
    boxes_b.push_back({near_b[i].position, {0.5, 0.5}, near_b[i].rotation});
  }
  const Polygon box = MakeBox(0.5, 0.5), octagon = RegularPolygon(8, 0.6), many = RegularPolygon(64, 0.6);
  const Capsule capsule{{-0.4, 0}, {0.4, 0}, 0.2};
  const std::vector<ChainSegment> chain = MakeChain(std::vector<Vec2>{{-3, 0}, {0, 0}, {3, 0}}, false);
  const double margin = 0.02;
  Manifold m;

  bench::PrintMachine(load);
  std::printf("\n| call (over %d random placements) | ns/call |\n|---|---:|\n", kPlacements);
  Row("CollideOrientedBoxes (existing)", NanosecondsPerCall([&](int i) { return engine::CollideOrientedBoxes(boxes_a[i], boxes_b[i], &m, margin) ? 1 : 0; }));
  Row("CollidePolygons, the same boxes", NanosecondsPerCall([&](int i) { return CollidePolygons(box, near_a[i], box, near_b[i], &m, margin) ? 1 : 0; }));
  Row("CollidePolygons, octagons", NanosecondsPerCall([&](int i) { return CollidePolygons(octagon, near_a[i], octagon, near_b[i], &m, margin) ? 1 : 0; }));
  Row("CollidePolygons, 64-gons", NanosecondsPerCall([&](int i) { return CollidePolygons(many, near_a[i], many, near_b[i], &m, margin) ? 1 : 0; }));
  Row("CollideCapsules", NanosecondsPerCall([&](int i) { return CollideCapsules(capsule, near_a[i], capsule, near_b[i], &m, margin) ? 1 : 0; }));
  Row("CollideCirclePolygon, octagon", NanosecondsPerCall([&](int i) { return CollideCirclePolygon(near_a[i].position, 0.4, octagon, near_b[i], &m, margin) ? 1 : 0; }));
  Row("CollideChainPolygon, box over a join", NanosecondsPerCall([&](int i) {
        const Transform xf{{near_b[i].position.x, 0.45 + 0.1 * near_a[i].position.y}, near_a[i].rotation};
        return CollideChainPolygon(chain[i & 1], {}, box, xf, &m, margin) ? 1 : 0;
      }));
  const ShapeProxy proxy8 = MakeProxy(octagon), proxy64 = MakeProxy(many);
  Row("ShapeDistance (GJK), octagons", NanosecondsPerCall([&](int i) { return ShapeDistance(proxy8, near_a[i], proxy8, near_b[i]).iterations; }));
  Row("ShapeDistance (GJK), 64-gons", NanosecondsPerCall([&](int i) { return ShapeDistance(proxy64, near_a[i], proxy64, near_b[i]).iterations; }));
  const ShapeProxy wall = MakeProxy(MakeOffsetBox(0.05, 2.0, {10.55, 0.0}, Rot{}));
  const ShapeProxy box_proxy = MakeProxy(box);
  Row("TimeOfImpact, spinning box against a wall", NanosecondsPerCall([&](int i) {
        const Sweep sweep{{0, 0}, {9.0, near_a[i].position.y}, {10.0, 0}, Rot{}, near_b[i].rotation};
        return TimeOfImpact(box_proxy, sweep, wall, {{0, 0}, {0, 0}, {0, 0}, Rot{}, Rot{}}).iterations;
      }));
  Row("RayCastPolygon, octagon", NanosecondsPerCall([&](int i) {
        return RayCastPolygon(octagon, near_a[i], {near_b[i].position * 2.0, -2.0 * near_b[i].position}).hit ? 1 : 0;
      }));
  return 0;
}
