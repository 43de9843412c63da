// Outline validation (every problem a user can make) and normalisation (winding, collinear
// points), and chain construction with its ghost vertices.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "geometry/chain.h"
#include "geometry/outline.h"

using engine::Vec2;
using namespace engine::geometry;

namespace {

OutlineProblem ProblemOf(const std::vector<Vec2>& points) { return CheckOutline(points).problem; }

}  // namespace

TEST_CASE("outline: a triangle either way round is valid and convex", "[geometry]") {
  const std::vector<Vec2> ccw = {{0, 0}, {2, 0}, {0, 1}};
  const std::vector<Vec2> cw = {{0, 0}, {0, 1}, {2, 0}};
  const OutlineCheck a = CheckOutline(ccw), b = CheckOutline(cw);
  CHECK(a.problem == OutlineProblem::kNone);
  CHECK(b.problem == OutlineProblem::kNone);
  CHECK_FALSE(a.clockwise);
  CHECK(b.clockwise);
  CHECK(a.convex);
  CHECK(b.convex);
  CHECK(TwiceSignedArea(ccw) == 2.0);
  CHECK(TwiceSignedArea(cw) == -2.0);
  // Normalising the clockwise one reverses it: same points, counter-clockwise.
  const Outline n = NormaliseOutline(cw);
  REQUIRE(n.count == 3);
  CHECK(TwiceSignedArea(n.View()) == 2.0);
}

TEST_CASE("outline: point counts and non-finite numbers", "[geometry]") {
  CHECK(ProblemOf({{0, 0}, {1, 0}}) == OutlineProblem::kTooFewPoints);
  std::vector<Vec2> many;
  for (int i = 0; i < 65; ++i) {
    const double a = 2.0 * 3.14159265358979 * i / 65;
    many.push_back({std::cos(a), std::sin(a)});
  }
  CHECK(ProblemOf(many) == OutlineProblem::kTooManyPoints);
  many.pop_back();
  CHECK(ProblemOf(many) == OutlineProblem::kNone);
  const OutlineCheck nan = CheckOutline(std::vector<Vec2>{{0, 0}, {1, 0}, {0, NAN}});
  CHECK(nan.problem == OutlineProblem::kNotFinite);
  CHECK(nan.first == 2);
}

TEST_CASE("outline: duplicate points, adjacent or not, are named", "[geometry]") {
  const OutlineCheck adjacent = CheckOutline(std::vector<Vec2>{{0, 0}, {1, 0}, {1, 0}, {0, 1}});
  CHECK(adjacent.problem == OutlineProblem::kDuplicatePoint);
  CHECK(adjacent.first == 1);
  CHECK(adjacent.second == 2);
  // A figure eight through one point twice.
  const OutlineCheck apart =
      CheckOutline(std::vector<Vec2>{{0, 0}, {1, 1}, {2, 0}, {2, 2}, {1, 1}, {0, 2}});
  CHECK(apart.problem == OutlineProblem::kDuplicatePoint);
  CHECK(apart.first == 1);
  CHECK(apart.second == 4);
}

TEST_CASE("outline: points all on one line have no area", "[geometry]") {
  CHECK(ProblemOf({{0, 0}, {1, 1}, {3, 3}}) == OutlineProblem::kAllCollinear);
  CHECK(ProblemOf({{0, 0}, {2, 2}, {1, 1}, {-1, -1}}) == OutlineProblem::kAllCollinear);
  // Off the line by a millionth of the size is an outline (a sliver), not collinear.
  CHECK(ProblemOf({{0, 0}, {1, 1e-6}, {3, 3}}) == OutlineProblem::kNone);
}

TEST_CASE("outline: crossings, touchings and spikes are self-crossing", "[geometry]") {
  // A bow tie: edge 0 ((0,0)-(2,2)) crosses edge 2 ((2,0)-(0,2)).
  const OutlineCheck bow = CheckOutline(std::vector<Vec2>{{0, 0}, {2, 2}, {2, 0}, {0, 2}});
  CHECK(bow.problem == OutlineProblem::kSelfCrossing);
  CHECK(bow.first == 0);
  CHECK(bow.second == 2);
  // A vertex touching another edge's interior.
  CHECK(ProblemOf({{0, 0}, {4, 0}, {4, 4}, {2, 0}, {0, 4}}) == OutlineProblem::kSelfCrossing);
  // A spike: the outline runs out along a line and straight back.
  CHECK(ProblemOf({{0, 0}, {4, 0}, {4, 2}, {6, 2}, {4, 2.0000001}, {0, 2}}) == OutlineProblem::kNone);
  CHECK(ProblemOf({{0, 0}, {4, 0}, {4, 2}, {6, 2}, {5, 2}, {0, 2}}) == OutlineProblem::kSelfCrossing);
}

TEST_CASE("outline: convexity of an L and of a box with midpoints", "[geometry]") {
  const std::vector<Vec2> l = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  CHECK(CheckOutline(l).problem == OutlineProblem::kNone);
  CHECK_FALSE(CheckOutline(l).convex);
  // Midpoints of a box's sides are exactly collinear: dropped, and the box is convex.
  const std::vector<Vec2> box = {{0, 0}, {1, 0}, {2, 0}, {2, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};
  const OutlineCheck check = CheckOutline(box);
  CHECK(check.problem == OutlineProblem::kNone);
  CHECK(check.convex);
  const Outline n = NormaliseOutline(box);
  REQUIRE(n.count == 4);
  CHECK(n.points[0] == Vec2{0, 0});
  CHECK(n.points[1] == Vec2{2, 0});
  CHECK(n.points[2] == Vec2{2, 2});
  CHECK(n.points[3] == Vec2{0, 2});
}

TEST_CASE("outline: a collinear point is kept when dropping it would make the outline cross", "[geometry]") {
  // P = (1, −4e-10) lies within the collinear tolerance (1e-9 of the size ≈ 2.2e-9) of the chord
  // from (0,0) to (2,0), but a slit from the top reaches down to X = (1, −2e-10), between P and
  // the chord: without P the bottom edge would cut through the slit.
  const std::vector<Vec2> slit = {{0, 0}, {1, -4e-10}, {2, 0}, {2, 1}, {1 + 1e-7, 1}, {1, -2e-10}, {1 - 1e-7, 1}, {0, 1}};
  REQUIRE(CheckOutline(slit).problem == OutlineProblem::kNone);
  const Outline kept = NormaliseOutline(slit);
  CHECK(kept.count == 8);
  CHECK(CheckOutline(kept.View()).problem == OutlineProblem::kNone);
  // The same bottom without the slit: P goes.
  const std::vector<Vec2> plain = {{0, 0}, {1, -4e-10}, {2, 0}, {2, 1}, {0, 1}};
  CHECK(NormaliseOutline(plain).count == 4);
  // And the slit outline with P dropped by hand does cross, so keeping it mattered.
  const std::vector<Vec2> dropped = {{0, 0}, {2, 0}, {2, 1}, {1 + 1e-7, 1}, {1, -2e-10}, {1 - 1e-7, 1}, {0, 1}};
  CHECK(ProblemOf(dropped) == OutlineProblem::kSelfCrossing);
}

TEST_CASE("outline: every problem has a message", "[geometry]") {
  CHECK(std::string(Describe(OutlineProblem::kSelfCrossing)) == "crosses itself (two edges meet)");
  CHECK(std::string(Describe(OutlineProblem::kDuplicatePoint)) == "has duplicate points");
}

TEST_CASE("chain: an open polyline has free ends, a loop wraps its ghosts", "[geometry]") {
  const std::vector<Vec2> points = {{0, 0}, {1, 0}, {2, 1}, {3, 1}};
  const std::vector<ChainSegment> open = MakeChain(points, false);
  REQUIRE(open.size() == 3);
  CHECK(HasFreeStart(open[0]));
  CHECK_FALSE(HasFreeEnd(open[0]));
  CHECK(open[0].ghost2 == Vec2{2, 1});
  CHECK(open[1].ghost1 == Vec2{0, 0});
  CHECK(open[1].point1 == Vec2{1, 0});
  CHECK(open[1].point2 == Vec2{2, 1});
  CHECK(open[1].ghost2 == Vec2{3, 1});
  CHECK(HasFreeEnd(open[2]));
  const std::vector<ChainSegment> loop = MakeChain(points, true);
  REQUIRE(loop.size() == 4);
  CHECK(loop[0].ghost1 == Vec2{3, 1});
  CHECK(loop[3].point1 == Vec2{3, 1});
  CHECK(loop[3].point2 == Vec2{0, 0});
  CHECK(loop[3].ghost2 == Vec2{1, 0});
  CHECK_FALSE(HasFreeStart(loop[0]));
}

TEST_CASE("chain: checks point counts, numbers and zero-length segments", "[geometry]") {
  CHECK(CheckChain(std::vector<Vec2>{{0, 0}}, false).problem == ChainProblem::kTooFewPoints);
  CHECK(CheckChain(std::vector<Vec2>{{0, 0}, {1, 0}}, false).problem == ChainProblem::kNone);
  CHECK(CheckChain(std::vector<Vec2>{{0, 0}, {1, 0}}, true).problem == ChainProblem::kTooFewPoints);
  const ChainCheck repeated = CheckChain(std::vector<Vec2>{{0, 0}, {1, 0}, {1, 0}}, false);
  CHECK(repeated.problem == ChainProblem::kZeroLength);
  CHECK(repeated.index == 1);
  // A loop whose last point repeats the first has a zero-length closing segment.
  const ChainCheck closing = CheckChain(std::vector<Vec2>{{0, 0}, {1, 0}, {1, 1}, {0, 0}}, true);
  CHECK(closing.problem == ChainProblem::kZeroLength);
  CHECK(closing.index == 3);
  CHECK(CheckChain(std::vector<Vec2>{{0, 0}, {INFINITY, 0}}, false).problem == ChainProblem::kNotFinite);
}
