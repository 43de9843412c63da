// Every scenario of bench_work_precision, under every integrator and step size it sweeps, builds
// and steps briefly to finite figures that start on its closed form. No timing here.
#include <catch2/catch.hpp>

#include <cmath>

#include "bench/work_precision_scenarios.h"
#include "engine/world.h"

namespace wp = work_precision;

TEST_CASE("every work-precision scenario steps 20 times to finite figures at every h", "[bench]") {
  for (const wp::Scenario& s : wp::Scenarios()) {
    for (const wp::Method& m : wp::Methods()) {
      for (int rate : wp::StepRates()) {
        INFO(s.id << " " << s.title << ", " << m.name << ", h = 1/" << rate);
        const wp::Figures f = wp::Measure(s, m.integrator, rate, 20);
        REQUIRE(f.steps == 20);
        CHECK(f.finite);
        CHECK(std::isfinite(f.position_error));
        // Twenty steps of the shortest h stay on the closed form, so the formulas match the setup
        // (a wrong sign or start would show at once).
        if (rate == 3840) CHECK(f.position_error < 1e-3 * s.scale);
        if (s.conservative) {
          CHECK(std::isfinite(f.energy_error));
          CHECK(std::isfinite(f.energy_slope));
        }
      }
    }
  }
}

TEST_CASE("the work-precision sweep covers 1/30 to 1/3840 s and the closed forms start at the setup", "[bench]") {
  const std::vector<int> rates = wp::StepRates();
  CHECK(rates.front() == 30);
  CHECK(rates.back() == 3840);
  for (const wp::Scenario& s : wp::Scenarios()) {
    INFO(s.id);
    const engine::World world = s.build(engine::Integrator::kSemiImplicitEuler, 1.0 / 60);
    CHECK(engine::Length(s.observed(world) - s.exact(0.0)) < 1e-12);
  }
  // S7's bounces: apex e^(2n)·h0 after every impact faster than the threshold.
  const double first = std::sqrt(2 * wp::kBounceHeight / wp::kG), up = wp::kBounceRestitution * wp::kG * first;
  CHECK(wp::BounceHeight(first + up / wp::kG) == Approx(0.64).epsilon(1e-12));
}
