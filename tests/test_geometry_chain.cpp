// Chain segments: no ghost collisions on straight runs (a box, capsule and circle sliding over
// joins get the face normal at every position), convex and concave joins, either side, free ends.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "geometry/chain.h"
#include "geometry/manifold.h"

using engine::Manifold;
using engine::Rot;
using engine::Vec2;
using namespace engine::geometry;

namespace {

const Transform kIdentity{};

// Every manifold the chain's segments give for a shape, by a collide function over one segment.
template <typename Collide>
std::vector<Manifold> CollideAll(const std::vector<ChainSegment>& chain, Collide collide) {
  std::vector<Manifold> found;
  for (const ChainSegment& s : chain) {
    Manifold m;
    if (collide(s, &m)) found.push_back(m);
  }
  return found;
}

double Deepest(const std::vector<Manifold>& manifolds) {
  double d = -INFINITY;
  for (const Manifold& m : manifolds) {
    for (int i = 0; i < m.point_count; ++i) d = std::max(d, m.points[i].depth);
  }
  return d;
}

// Slides a shape along x over a flat chain with joins at x = −1, 0 and 1, sunk 0.001 into it:
// every manifold at every position must have the face normal and the true depth.
template <typename Collide>
void CheckSlidesSmoothly(const std::vector<ChainSegment>& chain, Vec2 expected_normal, Collide collide_at) {
  int manifolds = 0;
  for (int step = -200; step <= 200; ++step) {
    const double x = step * 0.01 + 0.00037;  // off the grid, so joins fall between corners too
    const std::vector<Manifold> found = CollideAll(chain, [&](const ChainSegment& s, Manifold* m) { return collide_at(s, x, m); });
    REQUIRE(!found.empty());
    for (const Manifold& m : found) {
      INFO("x = " << x << ", normal (" << m.normal.x << ", " << m.normal.y << ")");
      CHECK(std::abs(m.normal.x - expected_normal.x) < 1e-12);
      CHECK(std::abs(m.normal.y - expected_normal.y) < 1e-12);
    }
    CHECK(Deepest(found) == Approx(0.001).epsilon(1e-6));
    manifolds += static_cast<int>(found.size());
  }
  CHECK(manifolds > 401);  // the shapes straddle joins at many positions
}

const std::vector<Vec2> kFlat = {{-3, 0}, {-1, 0}, {0, 0}, {1, 0}, {3, 0}};

}  // namespace

TEST_CASE("chain: a box sliding across joins between collinear segments gets the face normal", "[geometry]") {
  const std::vector<ChainSegment> chain = MakeChain(kFlat, false);
  const Polygon box = MakeBox(0.5, 0.5);
  for (const double angle : {0.0, 0.01, -0.01}) {
    // Turned, the box's lowest corner stands 0.001 below the line.
    const double lowest = 0.5 * (std::cos(angle) + std::sin(std::abs(angle)));
    CheckSlidesSmoothly(chain, {0, 1}, [&](const ChainSegment& s, double x, Manifold* m) {
      return CollideChainPolygon(s, kIdentity, box, {{x, lowest - 0.001}, engine::MakeRot(angle)}, m, 0.01);
    });
  }
}

TEST_CASE("chain: without ghost vertices the same box catches on the join", "[geometry]") {
  // The right segment alone as a two-vertex polygon, the box's right side 0.0005 past the join
  // and 0.001 deep: the box's side separates less than its bottom, so the normal is horizontal.
  const Polygon segment = MakePolygon(std::vector<Vec2>{{0, 0}, {1, 0}});
  Manifold m;
  REQUIRE(CollidePolygons(segment, kIdentity, MakeBox(0.5, 0.5), {{-0.4995, 0.499}, Rot{}}, &m));
  CHECK(std::abs(m.normal.x) == Approx(1.0));
  // With the ghost vertices the right segment gives the face normal, or nothing.
  const std::vector<ChainSegment> chain = MakeChain(kFlat, false);
  for (const Manifold& found : CollideAll(chain, [&](const ChainSegment& s, Manifold* out) {
         return CollideChainPolygon(s, kIdentity, MakeBox(0.5, 0.5), {{-0.4995, 0.499}, Rot{}}, out);
       })) {
    CHECK(found.normal.y == Approx(1.0));
  }
}

TEST_CASE("chain: a capsule and a circle sliding across joins get the face normal", "[geometry]") {
  const std::vector<ChainSegment> chain = MakeChain(kFlat, false);
  const Capsule capsule{{-0.4, 0}, {0.4, 0}, 0.2};
  CheckSlidesSmoothly(chain, {0, 1}, [&](const ChainSegment& s, double x, Manifold* m) {
    return CollideChainCapsule(s, kIdentity, capsule, {{x, 0.199}, Rot{}}, m, 0.01);
  });
  CheckSlidesSmoothly(chain, {0, 1}, [&](const ChainSegment& s, double x, Manifold* m) {
    return CollideChainCircle(s, kIdentity, {x, 0.299}, 0.3, m, 0.01);
  });
}

TEST_CASE("chain: either side of the polyline collides", "[geometry]") {
  const std::vector<ChainSegment> chain = MakeChain(kFlat, false);
  const Polygon box = MakeBox(0.5, 0.5);
  CheckSlidesSmoothly(chain, {0, -1}, [&](const ChainSegment& s, double x, Manifold* m) {
    return CollideChainPolygon(s, kIdentity, box, {{x, -0.499}, Rot{}}, m, 0.01);
  });
  // The chain placed in the world: turned a quarter turn, the floor becomes a wall at x = 5.
  const Transform wall{{5, 0}, Rot{0.0, 1.0}};
  Manifold m;
  REQUIRE(CollideChainCircle(chain[2], wall, {5.29, 0.5}, 0.3, &m));
  CHECK(m.normal.x == Approx(1.0));
  CHECK(m.normal.y == Approx(0.0).margin(1e-15));
  CHECK(m.points[0].depth == Approx(0.01).epsilon(1e-9));
}

TEST_CASE("chain: a box resting on a convex peak is held by the peak's vertex", "[geometry]") {
  const std::vector<ChainSegment> peak = MakeChain(std::vector<Vec2>{{-2, -1}, {0, 0}, {2, -1}}, false);
  const std::vector<Manifold> found = CollideAll(peak, [&](const ChainSegment& s, Manifold* m) {
    return CollideChainPolygon(s, kIdentity, MakeBox(0.5, 0.5), {{0.1, 0.499}, Rot{}}, m);
  });
  REQUIRE(!found.empty());
  for (const Manifold& m : found) {
    CHECK(m.normal.x == Approx(0.0).margin(1e-12));
    CHECK(m.normal.y == Approx(1.0));
    REQUIRE(m.point_count == 1);
    CHECK(m.points[0].point.x == Approx(0.0).margin(1e-12));
    CHECK(m.points[0].point.y == Approx(-0.0005).margin(1e-12));
    CHECK(m.points[0].depth == Approx(0.001).epsilon(1e-9));
  }
  // A circle on the peak, the same way.
  const std::vector<Manifold> round = CollideAll(peak, [&](const ChainSegment& s, Manifold* m) {
    return CollideChainCircle(s, kIdentity, {0, 0.499}, 0.5, m);
  });
  REQUIRE(!round.empty());
  for (const Manifold& m : round) {
    CHECK(m.normal.y == Approx(1.0));
    CHECK(m.points[0].depth == Approx(0.001).epsilon(1e-9));
  }
}

TEST_CASE("chain: past a convex join the neighbour's face owns the contact", "[geometry]") {
  // Flat, then down at 45° from the origin. A box on the flat part, 0.01 deep, whose right side
  // pokes 0.002 past the corner: the sloping segment must not push it sideways or up its slope.
  const std::vector<ChainSegment> chain = MakeChain(std::vector<Vec2>{{-2, 0}, {0, 0}, {2, -2}}, false);
  for (const double right_side : {-0.001, 0.002}) {
    const Transform at{{right_side - 0.5, 0.49}, Rot{}};
    Manifold slope, flat;
    CHECK_FALSE(CollideChainPolygon(chain[1], kIdentity, MakeBox(0.5, 0.5), at, &slope, 0.01));
    REQUIRE(CollideChainPolygon(chain[0], kIdentity, MakeBox(0.5, 0.5), at, &flat, 0.01));
    CHECK(flat.normal.y == Approx(1.0));
  }
}

TEST_CASE("chain: a circle in a valley touches both faces", "[geometry]") {
  const std::vector<ChainSegment> valley = MakeChain(std::vector<Vec2>{{-2, 1}, {0, 0}, {2, 1}}, false);
  // Radius 0.5 at (0, h): h / √1.25 = 0.5 from each line y = ∓x/2.
  const double h = 0.5 * std::sqrt(1.25);
  const std::vector<Manifold> found = CollideAll(valley, [&](const ChainSegment& s, Manifold* m) {
    return CollideChainCircle(s, kIdentity, {0, h - 0.001}, 0.5, m);
  });
  REQUIRE(found.size() == 2);
  CHECK(found[0].normal.x == Approx(1.0 / std::sqrt(5.0)));
  CHECK(found[0].normal.y == Approx(2.0 / std::sqrt(5.0)));
  CHECK(found[1].normal.x == Approx(-1.0 / std::sqrt(5.0)));
  CHECK(found[1].normal.y == Approx(2.0 / std::sqrt(5.0)));
  CHECK(found[0].points[0].depth == Approx(0.001 * 2.0 / std::sqrt(5.0)).epsilon(1e-9));
}

TEST_CASE("chain: a free end is round", "[geometry]") {
  const std::vector<ChainSegment> chain = MakeChain(std::vector<Vec2>{{-1, 0}, {1, 0}}, false);
  Manifold m;
  // Centre (1.3, 0.4): 0.5 from the end point.
  REQUIRE(CollideChainCircle(chain[0], kIdentity, {1.3, 0.4}, 0.5, &m));
  CHECK(m.normal.x == Approx(0.6));
  CHECK(m.normal.y == Approx(0.8));
  CHECK(m.points[0].depth == Approx(0.0).margin(1e-12));
  // A box's corner off the end: one point on the line from the end to the corner.
  REQUIRE(CollideChainPolygon(chain[0], kIdentity, MakeBox(0.5, 0.5), {{1.8, 0.9}, Rot{}}, &m, 0.6));
  REQUIRE(m.point_count == 1);
  CHECK(m.normal.x == Approx(0.6));
  CHECK(m.normal.y == Approx(0.8));
  CHECK(m.points[0].depth == Approx(-0.5));
}
