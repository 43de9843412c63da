// Mass, centre of mass and inertia of bodies made of parts, against hand-computed values.
#include <catch2/catch.hpp>

#include <cmath>

#include "engine/world.h"
#include "shape_builders.h"

using namespace testing;

TEST_CASE("a right triangle's mass, centroid and inertia", "[shapes]") {
  // Legs 3 (x) and 6 (y), density 2: area 9, mass 18, centroid (1, 2). About the centroid,
  // I = m·(a² + b²)/18 for a right triangle with legs a, b: 18·45/18 = 45.
  engine::World world{TurningWorld()};
  engine::BodyDef def = PartsBody({PolygonPart({{0, 0}, {3, 0}, {0, 6}})}, {10, 20});
  def.density = 2.0;
  const engine::BodyId id = world.CreateBody(def);
  const engine::BodyInfo& info = world.Info(id);
  CHECK(info.shape.type == engine::ShapeType::kPolygon);
  CHECK(info.mass == Approx(18.0).epsilon(1e-12));
  CHECK(world.LocalCenter(id).x == Approx(1.0).epsilon(1e-12));
  CHECK(world.LocalCenter(id).y == Approx(2.0).epsilon(1e-12));
  CHECK(info.inertia == Approx(45.0).epsilon(1e-12));
  // The state holds the centre of mass; the origin is where the scene put the frame.
  CHECK(world.State(id).position.x == Approx(11.0).epsilon(1e-12));
  // Reported exactly as given while the body stays where it was put (not recomputed from the
  // centre of mass, which rounds).
  CHECK(world.Origin(id).x == 10.0);
  CHECK(world.Origin(id).y == 20.0);
  world.SetPosition(id, {0.1, 0.3});
  CHECK(world.Origin(id).x == 0.1);
  CHECK(world.Origin(id).y == 0.3);
  CHECK(world.State(id).position.x == Approx(1.1).epsilon(1e-12));
}

TEST_CASE("an L of two boxes adds up by the parallel axis theorem", "[shapes]") {
  // A 2 × 1 bar along the bottom (centre (1, 0.5)) and a 1 × 2 post standing on its left end
  // (centre (0.5, 2)); density 1: masses 2 and 2, centre (0.75, 1.25).
  // Each: I = m(w² + h²)/12 = 2·5/12 = 5/6, plus m·d² with d² = 0.25² + 0.75² = 0.625 each.
  engine::World world{TurningWorld()};
  const engine::BodyId id =
      world.CreateBody(PartsBody({BoxPart({2, 1}, {1, 0.5}), BoxPart({1, 2}, {0.5, 2})}, {0, 0}));
  const engine::BodyInfo& info = world.Info(id);
  CHECK(info.shape.type == engine::ShapeType::kCompound);
  CHECK(info.mass == Approx(4.0).epsilon(1e-12));
  CHECK(world.LocalCenter(id).x == Approx(0.75).epsilon(1e-12));
  CHECK(world.LocalCenter(id).y == Approx(1.25).epsilon(1e-12));
  CHECK(info.inertia == Approx(2.0 * (5.0 / 6.0 + 2.0 * 0.625)).epsilon(1e-12));
  CHECK(world.Pieces(id).size() == 2);
}

TEST_CASE("a capsule's mass and inertia: a rectangle and two half discs", "[shapes]") {
  // length L = 2, radius r = 0.5, density 1. Rectangle 2 × 1: m_r = 2, I_r = m_r(L² + 4r²)/12.
  // Two half discs = one disc: m_d = π/4, about its own centre ½·m_d·r², each half's centroid
  // 4r/(3π) from the flat side, so by the parallel axis theorem each half about the capsule's
  // centre adds (m_d/2)·((L/2 + 4r/(3π))² − (4r/(3π))²).
  constexpr double kPi = 3.14159265358979323846;
  const double L = 2.0, r = 0.5;
  const double m_r = L * 2 * r, i_r = m_r * (L * L + 4 * r * r) / 12.0;
  const double m_d = kPi * r * r, c = 4 * r / (3 * kPi);
  const double i_d = 0.5 * m_d * r * r + m_d * ((L / 2 + c) * (L / 2 + c) - c * c);
  engine::World world{TurningWorld()};
  const engine::BodyId id = world.CreateBody(PartsBody({CapsulePart(L, r)}, {0, 0}));
  CHECK(world.Info(id).mass == Approx(m_r + m_d).epsilon(1e-12));
  CHECK(world.Info(id).inertia == Approx(i_r + i_d).epsilon(1e-12));
  CHECK(world.LocalCenter(id).x == Approx(0.0).margin(1e-15));
}

TEST_CASE("a concave polygon is split into convex pieces that cover its area", "[shapes]") {
  // A U: the 3 × 3 square less the 1 × 2 notch from the top middle: area 7.
  engine::World world{TurningWorld()};
  const engine::BodyId id = world.CreateBody(
      PartsBody({PolygonPart({{0, 0}, {3, 0}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}})}, {0, 0}));
  CHECK(world.Pieces(id).size() >= 3);
  CHECK(world.Info(id).mass == Approx(7.0).epsilon(1e-12));
  // Symmetric about x = 1.5; the centre of mass: (2·(1·3·1.5) + 3·1·0.5... by parts: bottom bar
  // 3 × 1 at y 0.5 (area 3), two posts 1 × 2 at y 2 (area 4): y = (3·0.5 + 4·2)/7 = 9.5/7.
  CHECK(world.LocalCenter(id).x == Approx(1.5).epsilon(1e-12));
  CHECK(world.LocalCenter(id).y == Approx(9.5 / 7.0).epsilon(1e-12));
}

TEST_CASE("CheckShapePart names what is wrong", "[shapes]") {
  const auto crossing = engine::CheckShapePart(PolygonPart({{0, 0}, {1, 1}, {1, 0}, {0, 1}}), false);
  REQUIRE(crossing);
  CHECK(crossing->key == "vertices");
  const auto collinear = engine::CheckShapePart(PolygonPart({{0, 0}, {1, 1}, {2, 2}}), false);
  REQUIRE(collinear);
  CHECK(collinear->key == "vertices");
  const auto moving_segments = engine::CheckShapePart(SegmentsPart({{0, 0}, {1, 0}}), false);
  REQUIRE(moving_segments);
  CHECK(moving_segments->key == "shape");
  CHECK_FALSE(engine::CheckShapePart(SegmentsPart({{0, 0}, {1, 0}}), true));
  CHECK(engine::CheckShapePart(CapsulePart(0.0, 1.0), false)->key == "length");
  // A corner 4e-60 m above another edge (fuzz_snapshot found it): the outline does not cross
  // itself, but splitting it leaves a piece of no area, which nothing could collide.
  const auto hair = engine::CheckShapePart(
      PolygonPart({{0, 0}, {2, 0}, {2, 1}, {1.6, 1}, {1.6, 0.3}, {0.4, 3.9281720437910931e-60}, {0.39999999999855052, 1}, {0, 1}}),
      false);
  REQUIRE(hair);
  CHECK(hair->key == "vertices");
}
