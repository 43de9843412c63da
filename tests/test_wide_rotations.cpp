// The bodies' rotations in lanes (WidePasses::rotations, solver/wide_cos_sin.inl) against
// ComputeCosSin one angle at a time: the same bits in every build of the lanes this processor
// runs, for every kind of angle.
#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "engine/body.h"
#include "engine/portable_math.h"
#include "solver/wide_passes.h"

namespace {

using engine::BodyIndex;
using engine::BodyState;
using engine::Rot;

// Angles of every kind CosSinOf tells apart: no turn (±0), subnormal and tiny, near each
// quadrant's edges (k·π/4 and its neighbours, where the rounding of k decides), ordinary
// random turns, large ones up to and past the exact reduction's limit, and NaN and infinities.
std::vector<double> Angles() {
  std::vector<double> angles = {0.0, -0.0, 5e-324, -5e-324, 1e-300, -1e-300, 1e-9, -1e-9};
  for (int k = -40; k <= 40; ++k) {
    const double edge = k * (std::numbers::pi / 4);
    angles.push_back(edge);
    angles.push_back(std::nextafter(edge, 1e300));
    angles.push_back(std::nextafter(edge, -1e300));
  }
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> turn(-10.0, 10.0), large(-6.4e9, 6.4e9);
  for (int i = 0; i < 4000; ++i) angles.push_back(turn(random));
  for (int i = 0; i < 400; ++i) angles.push_back(large(random));
  angles.push_back(0x1.8p32);                    // the exact reduction's last angle
  angles.push_back(std::nextafter(0x1.8p32, 1e300));  // and the first past it
  angles.push_back(-1e12);
  angles.push_back(std::numeric_limits<double>::quiet_NaN());
  angles.push_back(std::numeric_limits<double>::infinity());
  angles.push_back(-std::numeric_limits<double>::infinity());
  return angles;
}

bool SameBits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

}  // namespace

TEST_CASE("wide rotations: every width gives ComputeCosSin's bits for every listed body") {
  const std::vector<double> angles = Angles();
  // One body more, never listed: the rotations leave its entry alone.
  std::vector<BodyState> states(angles.size() + 1);
  for (std::size_t i = 0; i < angles.size(); ++i) states[i].angle = angles[i];
  // Every angle's body, backwards (the lanes gather), an odd count (a remainder after the last
  // group of lanes); the special angles land among ordinary ones in their groups.
  std::vector<BodyIndex> bodies;
  for (std::size_t i = angles.size(); i-- > 0;) bodies.push_back(static_cast<BodyIndex>(i));
  if (bodies.size() % 2 == 0) bodies.erase(bodies.begin() + 3);
  for (const engine::detail::WidePasses* build : engine::detail::RunnableWidePasses()) {
    const engine::detail::WidePasses& passes = *build;
    INFO(passes.lanes << " lanes");
    const Rot unwritten{-7.0, -7.0};
    std::vector<Rot> rotations(states.size(), unwritten);
    passes.rotations(&states[0].angle, sizeof(BodyState) / sizeof(double), bodies.data(), bodies.size(),
                     rotations.data());
    std::vector<bool> listed(states.size(), false);
    for (const BodyIndex body : bodies) listed[body] = true;
    int wrong = 0;
    for (std::size_t i = 0; i < states.size(); ++i) {
      const Rot expected = listed[i] ? [&] {
        const engine::CosSin q = engine::ComputeCosSin(angles[i]);
        return Rot{q.c, q.s};
      }()
                                     : unwritten;
      if (!SameBits(rotations[i].c, expected.c) || !SameBits(rotations[i].s, expected.s)) {
        if (++wrong <= 5) {
          UNSCOPED_INFO("angle " << angles[i] << ": (" << rotations[i].c << ", " << rotations[i].s << ") against ("
                                 << expected.c << ", " << expected.s << ")");
        }
      }
    }
    CHECK(wrong == 0);
  }
}
