// Position-based fluid: Archimedes' principle through the two-way coupling, a dam break that
// settles incompressible and stays in its tank, the hash and snapshot it joins, and the kernel
// worked out for pairs lanes at a time giving the scalar kernel's bits (as do the pair sums and
// the search for pairs within the kernel), and the grid's search against all pairs.
#include <algorithm>
#include <bit>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "engine/world.h"
#include "particles/fluid_pairs.h"
#include "particles/near_pairs.h"
#include "particles/particle_grid.h"
#include "particles/sph_kernels.h"
#include "world_builders.h"

namespace {

using engine::BodyDef;
using engine::FluidDef;
using engine::Vec2;
using engine::World;
using engine::WorldDef;

// A tank with its floor at y = 0 and walls at x = ±half_width.
void Tank(World& world, double half_width) {
  world.CreateBody(testing::Static(testing::Box({0.0, -0.5}, {2.0 * half_width + 2.0, 1.0})));
  world.CreateBody(testing::Static(testing::Box({-half_width - 0.5, 2.0}, {1.0, 4.0})));
  world.CreateBody(testing::Static(testing::Box({half_width + 0.5, 2.0}, {1.0, 4.0})));
}

// A uniform number in [0, 1) from a 64-bit LCG's state.
double Uniform(std::uint64_t& state) {
  state = state * 6364136223846793005ull + 1442695040888963407ull;
  return static_cast<double>(state >> 11) * 0x1.0p-53;
}

std::uint64_t Bits(double v) { return std::bit_cast<std::uint64_t>(v); }

}  // namespace

TEST_CASE("a crate of density 500 floats in water half submerged (Archimedes)", "[fluid]") {
  World world(WorldDef{});
  Tank(world, 1.2);
  FluidDef water;
  water.region = {{-1.2, 0.0}, {1.2, 0.6}};
  water.spacing = 0.05;
  water.density = 1000.0;
  world.AddFluid(water);
  BodyDef crate = testing::Box({0.0, 0.9}, {0.5, 0.5});
  crate.density = 500.0;
  const engine::BodyId id = world.CreateBody(crate);
  // The water's level far from the crate: the top particles' centres plus a radius.
  const auto level = [&] {
    std::vector<double> top(48, -1.0);
    for (const Vec2 p : world.FluidPositions()) {
      if (std::abs(p.x) < 0.6) continue;
      const int column = std::clamp(static_cast<int>((p.x + 1.2) / 0.05), 0, 47);
      top[column] = std::max(top[column], p.y);
    }
    double sum = 0.0;
    int count = 0;
    for (const double y : top) {
      if (y > 0.0) sum += y, ++count;
    }
    return sum / count + 0.025;
  };
  double depth = 0.0;
  int samples = 0;
  for (int s = 0; s < 1200; ++s) {
    world.Step();
    if (s < 600) continue;  // settled after 10 s; the last 10 s averaged
    depth += level() - (world.State(id).position.y - 0.25);
    ++samples;
  }
  const double submerged = depth / samples / 0.5;
  INFO("submerged fraction " << submerged);
  REQUIRE(submerged == Approx(0.5).epsilon(0.05));
}

TEST_CASE("a dam break settles incompressible and no particle leaves its tank", "[fluid]") {
  World world(WorldDef{});
  Tank(world, 1.5);
  FluidDef water;
  water.region = {{-1.5, 0.0}, {-0.5, 1.0}};
  water.spacing = 0.05;
  water.viscosity = 0.1;  // so the waves die down within the test's 20 s
  world.AddFluid(water);
  for (int s = 0; s < 1200; ++s) {
    world.Step();
    for (const Vec2 p : world.FluidPositions()) {
      REQUIRE(std::abs(p.x) < 1.5);
      REQUIRE(p.y > 0.0);
    }
  }
  // The compression the density constraints fight, over every particle (a free surface's
  // particles, short of neighbours, read low and are left alone).
  double compression = 0.0;
  const auto density = world.FluidDensities();
  for (const double rho : density) compression += std::max(0.0, rho / 1000.0 - 1.0);
  compression /= static_cast<double>(density.size());
  INFO("mean compression " << compression);
  REQUIRE(compression < 0.01);
  // And it has spread over the tank: 1 m² of water over 3 m settles 1/3 m deep, its centre of
  // mass half that high (the waves still running move it a little).
  double height = 0.0;
  for (const Vec2 p : world.FluidPositions()) height += p.y;
  height /= static_cast<double>(density.size());
  INFO("mean height " << height);
  REQUIRE(height == Approx(1.0 / 6.0).epsilon(0.1));
}

TEST_CASE("a light crate thrown by a dam break against the wall gains no energy", "[fluid]") {
  // The wave squeezes a crate of 80 kg against the far wall, dozens of particles pressing it
  // at once: before mass splitting their pushes overshot and it reached 1e10 m/s in 15 steps.
  WorldDef def;
  def.rotation = true;  // turning is where it ran away
  World world(def);
  Tank(world, 3.7);
  FluidDef water;
  water.spacing = 0.08;
  water.viscosity = 0.02;
  water.region = {{-3.7, 0.0}, {-2.7, 2.0}};
  world.AddFluid(water);
  water.region = {{-2.7, 0.0}, {1.3, 0.32}};
  world.AddFluid(water);
  water.region = {{1.3, 0.0}, {1.7, 0.08}};
  world.AddFluid(water);
  water.region = {{1.7, 0.0}, {3.7, 0.32}};
  world.AddFluid(water);
  BodyDef crate = testing::Box({1.5, 0.32}, {0.4, 0.4});
  crate.density = 500.0;
  crate.friction = 0.4;
  const engine::BodyId id = world.CreateBody(crate);
  const double g = -world.Def().gravity.y;
  const auto energy = [&] {
    double e = 0.0;
    const auto x = world.FluidPositions();
    const auto v = world.FluidVelocities();
    const auto m = world.FluidMasses();
    for (std::size_t i = 0; i < x.size(); ++i) e += m[i] * (0.5 * engine::LengthSquared(v[i]) + g * x[i].y);
    const engine::BodyState& s = world.State(id);
    const engine::BodyInfo& info = world.Info(id);
    return e + (0.5 * engine::LengthSquared(s.velocity) + g * s.position.y) / info.inv_mass +
           0.5 * s.angular_velocity * s.angular_velocity / info.inv_inertia;
  };
  // The seeded lattice is not quite at rest against the walls and the crate: its first
  // projections give it energy once, over the first 0.2 s. From there on it can only lose it.
  for (int s = 0; s < 12; ++s) world.Step();
  const double settled = energy();
  // Ritter's dam-break front runs at 2·sqrt(g·H); nothing the wave throws goes faster.
  const double front_speed = 2.0 * std::sqrt(g * 2.0);
  double fastest = 0.0;
  for (int s = 12; s < 900; ++s) {
    world.Step();
    fastest = std::max(fastest, engine::Length(world.State(id).velocity));
    INFO("step " << s);
    REQUIRE(energy() <= settled);
  }
  INFO("the crate's top speed " << fastest);
  REQUIRE(fastest < front_speed);
}

TEST_CASE("a fluid world's snapshot restores to the same hash", "[fluid]") {
  const auto make = [] {
    auto world = std::make_unique<World>(WorldDef{});
    Tank(*world, 0.5);
    FluidDef water;
    water.region = {{-0.5, 0.0}, {0.0, 0.4}};
    water.spacing = 0.05;
    world->AddFluid(water);
    return world;
  };
  auto world = make();
  for (int s = 0; s < 20; ++s) world->Step();
  const auto bytes = world->TakeSnapshot();
  for (int s = 0; s < 20; ++s) world->Step();
  World restored(WorldDef{});
  REQUIRE(static_cast<bool>(restored.RestoreSnapshot(bytes)));
  for (int s = 0; s < 20; ++s) restored.Step();
  REQUIRE(restored.StateHash() == world->StateHash());
}

TEST_CASE("the fluid kernel's terms for pairs, worked out lanes at a time, are the scalar kernel's bits", "[fluid]") {
  // KernelTermsOfPairs (four lanes with AVX where the processor has it, else two) against
  // SphKernels::W and Gradient called one pair at a time, and PBF's artificial pressure
  // written out: bit for bit, for batches of every length up to 9 (every tail of the lanes),
  // offsets all round the kernel, two particles at the same spot and one just inside the edge.
  const engine::detail::SphKernels k(0.125);
  const double inv_clumping_w = 1.0 / k.W(std::pow(0.2 * k.h, 2)), clumping_scale = -0.37;
  std::vector<Vec2> offsets{{0.0, 0.0}, {0.0, std::nextafter(k.h, 0.0)}, {-std::nextafter(k.h, 0.0), 0.0}};
  std::uint64_t state = 12345;
  const auto uniform = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(state >> 11) * 0x1.0p-53;
  };
  while (offsets.size() < 40) {
    const Vec2 d{(2.0 * uniform() - 1.0) * k.h, (2.0 * uniform() - 1.0) * k.h};
    if (engine::LengthSquared(d) < k.h2) offsets.push_back(d);
  }
  const auto bits = [](double v) { return std::bit_cast<std::uint64_t>(v); };
  for (const bool with_gradients : {true, false}) {
    for (std::size_t count = 0; count <= 9; ++count) {
      for (std::size_t start = 0; start + count <= offsets.size(); start += 7) {
        std::vector<double> dx(count + 4, 0.0), dy(count + 4, 0.0), r2(count + 4, k.h2);
        for (std::size_t q = 0; q < count; ++q) {
          dx[q] = offsets[start + q].x, dy[q] = offsets[start + q].y;
          r2[q] = engine::LengthSquared(offsets[start + q]);
        }
        std::vector<engine::detail::PairTerms> terms(count, {-1.0, {-1.0, -1.0}, -1.0});
        engine::detail::KernelTermsOfPairs(k, inv_clumping_w, clumping_scale, with_gradients,
                                           {dx.data(), dy.data(), r2.data(), static_cast<std::uint32_t>(count)},
                                           terms.data());
        for (std::size_t q = 0; q < count; ++q) {
          const Vec2 d = offsets[start + q];
          const double r = std::sqrt(engine::LengthSquared(d));
          const engine::detail::PairTerms& t = terms[q];
          REQUIRE(bits(t.weight) == bits(k.W(engine::LengthSquared(d), r)));
          if (!with_gradients) continue;
          const Vec2 gradient = k.Gradient(d, r);
          REQUIRE(bits(t.gradient.x) == bits(gradient.x));
          REQUIRE(bits(t.gradient.y) == bits(gradient.y));
          const double ratio = t.weight * inv_clumping_w;
          REQUIRE(bits(t.clumping) == bits(clumping_scale * ((ratio * ratio) * (ratio * ratio))));
        }
      }
    }
  }
}

TEST_CASE("a light fluid poured under a heavy one rises above it", "[fluid]") {
  // Two blocks of different rest densities (so the particles' masses differ and the density
  // pass looks each neighbour's mass up): oil of 600 kg/m² under water of 1000 in a 1 m tank.
  // Buoyancy (Archimedes, as for the crate above) must carry the oil up through the water.
  World world(WorldDef{});
  Tank(world, 0.5);
  FluidDef oil;
  oil.region = {{-0.5, 0.0}, {0.5, 0.3}};
  oil.spacing = 0.05;
  oil.density = 600.0;
  oil.viscosity = 0.1;
  const std::size_t oil_count = world.AddFluid(oil);
  FluidDef water = oil;
  water.region = {{-0.5, 0.3}, {0.5, 0.6}};
  water.density = 1000.0;
  world.AddFluid(water);
  const auto mean_heights = [&] {
    double oil_y = 0.0, water_y = 0.0;
    const auto positions = world.FluidPositions();
    for (std::size_t k = 0; k < positions.size(); ++k) (k < oil_count ? oil_y : water_y) += positions[k].y;
    return std::pair{oil_y / static_cast<double>(oil_count),
                     water_y / static_cast<double>(positions.size() - oil_count)};
  };
  const auto [oil_before, water_before] = mean_heights();
  REQUIRE(oil_before < water_before);
  for (int s = 0; s < 600; ++s) world.Step();
  const auto [oil_after, water_after] = mean_heights();
  INFO("mean heights after 10 s: oil " << oil_after << " m, water " << water_after << " m");
  REQUIRE(oil_after > water_after);
}

TEST_CASE("the pairs within a distance, lanes at a time, are the plain loop's", "[fluid]") {
  // PairsWithin (eight at a time with AVX-512, four with AVX2, where the processor has them,
  // and one at a time) against a loop over the pairs: the same pairs kept in the same order,
  // for lists of every length up to 41 (every tail), with pairs at exactly the distance (not
  // kept) and at one point.
  std::uint64_t state = 99;
  std::vector<Vec2> x(40);
  for (Vec2& p : x) p = {Uniform(state), Uniform(state)};
  x[1] = x[0] + Vec2{0.25, 0.0};
  x[2] = x[0];
  std::vector<engine::detail::ParticlePair> pairs{{0, 1}, {0, 2}};
  while (pairs.size() < 41) {
    pairs.push_back({static_cast<std::uint32_t>(Uniform(state) * 40), static_cast<std::uint32_t>(Uniform(state) * 40)});
  }
  const double r2 = 0.0625;
  for (std::size_t count = 0; count <= pairs.size(); ++count) {
    const std::span<const engine::detail::ParticlePair> some(pairs.data(), count);
    std::vector<engine::detail::ParticlePair> want;
    for (const auto& p : some) {
      if (engine::LengthSquared(x[p.first] - x[p.second]) < r2) want.push_back(p);
    }
    for (const int lanes : {0, 4, 1}) {
      std::vector<engine::detail::ParticlePair> got(count);
      std::vector<double> dx(count), dy(count), d2(count);
      got.resize(engine::detail::PairsWithin(x.data(), some, r2, got.data(), {dx.data(), dy.data(), d2.data()}, lanes));
      INFO("lanes " << lanes);
      REQUIRE(got == want);
      for (std::size_t q = 0; q < got.size(); ++q) {
        const Vec2 d = x[got[q].first] - x[got[q].second];
        REQUIRE(Bits(dx[q]) == Bits(d.x));
        REQUIRE(Bits(dy[q]) == Bits(d.y));
        REQUIRE(Bits(d2[q]) == Bits(engine::LengthSquared(d)));
      }
    }
  }
}

TEST_CASE("a fluid of one kind's pair sums, four pairs at a time, are one pair at a time's bits", "[fluid]") {
  // AddDensityOfPairs (at the widest lanes, and at four), AddMovesOfPairs and AddPullsOfPairs
  // at the widest lanes against one pair at a time, on the same pairs (by lower particle, each
  // with runs of pairs and a tail, some adding into the spill sums), from the same sums: bit
  // for bit.
  const engine::detail::SphKernels k(0.125);
  std::uint64_t state = 7;
  std::vector<Vec2> x(60);
  for (Vec2& p : x) p = {0.3 * Uniform(state), 0.3 * Uniform(state)};
  x[5] = x[4];  // two particles at the same spot: no gradient
  for (const std::uint32_t count : {3u, 4u, 9u, 37u, 160u}) {
    std::vector<engine::detail::ParticlePair> pairs;
    for (std::uint32_t i = 0; i < x.size() && pairs.size() < count; ++i) {
      for (std::uint32_t j = i + 1; j < x.size() && pairs.size() < count; ++j) {
        if (engine::LengthSquared(x[i] - x[j]) < k.h2) pairs.push_back({i, j});
      }
    }
    const engine::detail::UniformPairs fluid{k, 0.9, 1.0 / 0.9, 1.0 / 1000.0, 3.1, -0.004, 40};
    std::vector<engine::detail::DensitySums> sums(x.size()), spill(x.size());
    for (std::size_t f = 0; f < x.size(); ++f) {
      sums[f] = {Uniform(state), {Uniform(state), Uniform(state)}, Uniform(state)};
      spill[f] = {Uniform(state), {Uniform(state), Uniform(state)}, Uniform(state)};
    }
    auto sums_1 = sums, spill_1 = spill, sums_4 = sums, spill_4 = spill;
    std::vector<double> terms(3 * pairs.size()), terms_4(3 * pairs.size()), unused(3 * pairs.size());
    std::vector<double> dx(pairs.size()), dy(pairs.size()), d2(pairs.size());
    for (std::size_t q = 0; q < pairs.size(); ++q) {
      const Vec2 d = x[pairs[q].first] - x[pairs[q].second];
      dx[q] = d.x, dy[q] = d.y, d2[q] = engine::LengthSquared(d);
    }
    const engine::detail::PairOffsets offsets{dx.data(), dy.data(), d2.data()};
    engine::detail::AddDensityOfPairs(fluid, x.data(), pairs, offsets, sums.data(), spill.data(), terms.data());
    engine::detail::AddDensityOfPairs(fluid, x.data(), pairs, offsets, sums_1.data(), spill_1.data(), unused.data(), 1);
    // Four lanes too, where the widest are eight (AVX-512): both wide loops against one.
    engine::detail::AddDensityOfPairs(fluid, x.data(), pairs, offsets, sums_4.data(), spill_4.data(), terms_4.data(), 4);
    for (std::size_t f = 0; f < x.size(); ++f) {
      for (const auto* both : {&sums, &spill, &sums_4, &spill_4}) {
        const bool own = both == &sums || both == &sums_4;
        const auto& one = own ? sums_1[f] : spill_1[f];
        const auto& wide = (*both)[f];
        REQUIRE(Bits(wide.density) == Bits(one.density));
        REQUIRE(Bits(wide.gradient.x) == Bits(one.gradient.x));
        REQUIRE(Bits(wide.gradient.y) == Bits(one.gradient.y));
        REQUIRE(Bits(wide.denominator) == Bits(one.denominator));
      }
    }
    // The move pass's terms are where the move pass looks for them either way.
    for (std::size_t q = 0; q < pairs.size() / 4 * 4 * 3; ++q) REQUIRE(Bits(terms[q]) == Bits(terms_4[q]));
    std::vector<double> lambda(x.size());
    for (std::size_t f = 0; f < x.size(); ++f) lambda[f] = -Uniform(state);
    std::vector<Vec2> moves(x.size()), moves_spill(x.size());
    for (std::size_t f = 0; f < x.size(); ++f) moves[f] = {Uniform(state), 0.0}, moves_spill[f] = {0.0, Uniform(state)};
    auto moves_1 = moves, moves_spill_1 = moves_spill;
    engine::detail::AddMovesOfPairs(fluid, x.data(), pairs, lambda.data(), terms.data(), moves.data(),
                                    moves_spill.data());
    engine::detail::AddMovesOfPairs(fluid, x.data(), pairs, lambda.data(), unused.data(), moves_1.data(),
                                    moves_spill_1.data(), 1);
    for (std::size_t f = 0; f < x.size(); ++f) {
      REQUIRE(Bits(moves[f].x) == Bits(moves_1[f].x));
      REQUIRE(Bits(moves[f].y) == Bits(moves_1[f].y));
      REQUIRE(Bits(moves_spill[f].x) == Bits(moves_spill_1[f].x));
      REQUIRE(Bits(moves_spill[f].y) == Bits(moves_spill_1[f].y));
    }
    // XSPH's pulls, from random velocities and m/ρ.
    std::vector<Vec2> v(x.size());
    std::vector<double> mass_over_density(x.size());
    for (std::size_t f = 0; f < x.size(); ++f) {
      v[f] = {Uniform(state) - 0.5, Uniform(state) - 0.5};
      mass_over_density[f] = 0.001 * (1.0 + Uniform(state));
    }
    auto pulls = moves, pulls_spill = moves_spill;
    auto pulls_1 = moves, pulls_spill_1 = moves_spill;
    engine::detail::AddPullsOfPairs(fluid, x.data(), v.data(), mass_over_density.data(), pairs, offsets, pulls.data(),
                                    pulls_spill.data());
    engine::detail::AddPullsOfPairs(fluid, x.data(), v.data(), mass_over_density.data(), pairs, offsets,
                                    pulls_1.data(), pulls_spill_1.data(), 1);
    for (std::size_t f = 0; f < x.size(); ++f) {
      REQUIRE(Bits(pulls[f].x) == Bits(pulls_1[f].x));
      REQUIRE(Bits(pulls[f].y) == Bits(pulls_1[f].y));
      REQUIRE(Bits(pulls_spill[f].x) == Bits(pulls_spill_1[f].x));
      REQUIRE(Bits(pulls_spill[f].y) == Bits(pulls_spill_1[f].y));
    }
  }
}

TEST_CASE("the grid's search finds every pair within reach, fluid pairs sorted, on any threads and lanes", "[fluid]") {
  // Particles of a soft body (numbered first, left in their order) and of a fluid (renumbered in
  // the grid's order), some at exactly the reach apart (kept) and two at one point: the lists
  // and the fluid's pairs against every pair tried, four candidates at a time and one at a
  // time, on one to three threads.
  using Pair = std::pair<std::uint32_t, std::uint32_t>;
  std::uint64_t state = 5;
  const double reach = 0.15;
  const std::uint32_t first = 60, n = 700;
  std::vector<Vec2> x(n);
  for (Vec2& p : x) p = {2.0 * Uniform(state) - 1.0, Uniform(state)};
  x[first + 1] = x[first] + Vec2{reach, 0.0};
  x[first + 2] = x[first] + Vec2{0.0, reach};
  x[first + 3] = x[first];
  x[4] = x[first + 5] + Vec2{0.0, -reach};
  engine::detail::ParticleGrid grid;
  grid.Build(x, reach);
  std::vector<std::uint32_t> old_of_new, rows;
  grid.RenumberFrom(first, &old_of_new, &rows);
  const std::vector<Vec2> before = x;
  for (std::uint32_t k = 0; k < n - first; ++k) x[first + k] = before[first + old_of_new[k]];
  std::vector<std::vector<std::uint32_t>> want_lists(n);
  std::vector<Pair> want_pairs;
  for (std::uint32_t i = 0; i < n; ++i) {
    for (std::uint32_t j = i + 1; j < n; ++j) {
      if (engine::LengthSquared(x[j] - x[i]) > reach * reach) continue;
      want_lists[i].push_back(j);
      want_lists[j].push_back(i);
      if (i >= first) want_pairs.push_back({i - first, j - first});
    }
  }
  REQUIRE(want_pairs.size() > 1000);
  std::vector<Pair> reference;
  std::vector<std::uint32_t> reference_lists;
  for (const int threads : {1, 2, 3}) {
    for (const int lanes : {0, 1}) {
      engine::detail::WorkerPool pool(threads);
      std::vector<std::uint32_t> offsets, neighbours;
      const auto found = grid.FindNeighbours(x, reach, pool, &offsets, &neighbours, first, n, lanes);
      const std::vector<Pair> pairs(found.begin(), found.end());
      INFO("threads " << threads << ", lanes " << lanes);
      REQUIRE(pairs == want_pairs);
      for (std::uint32_t i = 0; i < n; ++i) {
        std::vector<std::uint32_t> list(neighbours.begin() + offsets[i], neighbours.begin() + offsets[i + 1]);
        std::sort(list.begin(), list.end());
        std::vector<std::uint32_t> want = want_lists[i];
        std::sort(want.begin(), want.end());
        REQUIRE(list == want);
      }
      // The same lists in the same order every way.
      if (reference.empty()) reference = pairs, reference_lists = neighbours;
      REQUIRE(neighbours == reference_lists);
    }
  }
}

TEST_CASE("a fluid of one kind's multipliers and moves, lanes at a time, are one particle at a time's bits", "[fluid]") {
  // InitialSums, MultipliersOf and MoveParticles at the widest lanes (eight and four particles
  // with AVX-512) against one at a time, over ranges with tails: particles squeezed and not and
  // one exactly at the rest density, from random sums.
  const engine::detail::SphKernels k(0.125);
  const engine::detail::UniformPairs fluid{k, 0.9, 1.0 / 0.9, 1.0 / 1000.0, 3.1, -0.004, 0};
  std::uint64_t state = 11;
  const std::uint32_t n = 45;
  std::vector<engine::detail::DensitySums> sums(n);
  std::vector<double> wall_denominator(n), lambda_wide(n), lambda_one(n), density_wide(n), density_one(n);
  std::vector<Vec2> moves(n), slope(n), x(n);
  for (std::uint32_t f = 0; f < n; ++f) {
    sums[f] = {900.0 + 200.0 * Uniform(state), {Uniform(state) - 0.5, Uniform(state) - 0.5}, Uniform(state)};
    wall_denominator[f] = f % 3 == 0 ? 0.0 : Uniform(state);
    moves[f] = {Uniform(state) - 0.5, Uniform(state) - 0.5};
    slope[f] = f % 2 == 0 ? Vec2{} : Vec2{Uniform(state), Uniform(state)};
    x[f] = {Uniform(state), Uniform(state)};
  }
  sums[3].density = 1000.0;
  // The sums' starting values, from the walls' shares and slopes.
  {
    std::vector<double> share(n);
    for (double& a : share) a = Uniform(state) < 0.5 ? 0.0 : Uniform(state);
    std::vector<engine::detail::DensitySums> wide(n), one(n);
    for (const auto& [begin, end] : {std::pair{0u, n}, std::pair{5u, 13u}, std::pair{9u, 10u}}) {
      engine::detail::InitialSums(fluid, 0.7, 1000.0, share.data(), slope.data(), begin, end, wide.data());
      engine::detail::InitialSums(fluid, 0.7, 1000.0, share.data(), slope.data(), begin, end, one.data(), 1);
      for (std::uint32_t f = 0; f < n; ++f) {
        REQUIRE(Bits(wide[f].density) == Bits(one[f].density));
        REQUIRE(Bits(wide[f].gradient.x) == Bits(one[f].gradient.x));
        REQUIRE(Bits(wide[f].gradient.y) == Bits(one[f].gradient.y));
        REQUIRE(Bits(wide[f].denominator) == Bits(one[f].denominator));
      }
    }
  }
  for (const auto& [begin, end] : {std::pair{0u, n}, std::pair{5u, 13u}, std::pair{7u, 8u}}) {
    engine::detail::MultipliersOf(fluid, sums.data(), wall_denominator.data(), 0.01, begin, end, density_wide.data(),
                                  lambda_wide.data());
    engine::detail::MultipliersOf(fluid, sums.data(), wall_denominator.data(), 0.01, begin, end, density_one.data(),
                                  lambda_one.data(), 1);
    for (std::uint32_t f = begin; f < end; ++f) {
      REQUIRE(Bits(density_wide[f]) == Bits(density_one[f]));
      REQUIRE(Bits(lambda_wide[f]) == Bits(lambda_one[f]));
    }
    std::vector<Vec2> x_wide = x, x_one = x;
    engine::detail::MoveParticles(fluid, moves.data(), lambda_one.data(), slope.data(), 2.0, 0.5, begin, end,
                                  x_wide.data());
    engine::detail::MoveParticles(fluid, moves.data(), lambda_one.data(), slope.data(), 2.0, 0.5, begin, end,
                                  x_one.data(), 1);
    for (std::uint32_t f = 0; f < n; ++f) {
      REQUIRE(Bits(x_wide[f].x) == Bits(x_one[f].x));
      REQUIRE(Bits(x_wide[f].y) == Bits(x_one[f].y));
    }
  }
  // The one at the rest density gets λ = −0, as std::max(0.0, 0.0) negated gives.
  REQUIRE(std::signbit(lambda_one[3]));
  REQUIRE(lambda_one[3] == 0.0);
}

TEST_CASE("a substep's prediction and velocities, particles lanes at a time, are one at a time's bits", "[fluid]") {
  // PredictParticles and VelocitiesOfMoves at the widest lanes against one at a time, over
  // ranges with tails, with pinned particles (no inverse mass) among them.
  std::uint64_t state = 13;
  const std::uint32_t n = 23;
  std::vector<Vec2> x(n), v(n);
  std::vector<double> inv_mass(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    x[i] = {Uniform(state), Uniform(state)};
    v[i] = {Uniform(state) - 0.5, Uniform(state) - 0.5};
    inv_mass[i] = i % 5 == 2 ? 0.0 : 1.0 + Uniform(state);
  }
  const double h = 1.0 / 480.0;
  for (const auto& [begin, end] : {std::pair{0u, n}, std::pair{3u, 10u}, std::pair{6u, 7u}}) {
    std::vector<Vec2> x_wide = x, v_wide = v, previous_wide(n), x_one = x, v_one = v, previous_one(n);
    engine::detail::PredictParticles({0.0, -9.81}, h, inv_mass.data(), begin, end, x_wide.data(), v_wide.data(),
                                     previous_wide.data());
    engine::detail::PredictParticles({0.0, -9.81}, h, inv_mass.data(), begin, end, x_one.data(), v_one.data(),
                                     previous_one.data(), 1);
    // A pinned particle stays where it was put, with its velocity.
    REQUIRE(Bits(x_wide[7].x) == Bits(x[7].x));
    REQUIRE(Bits(v_wide[7].y) == Bits(v[7].y));
    for (std::uint32_t i = 0; i < n; ++i) {
      x_wide[i] += Vec2{1e-3 * Uniform(state), 0.0};
      x_one[i] = x_wide[i];
    }
    engine::detail::VelocitiesOfMoves(h, x_wide.data(), previous_wide.data(), begin, end, v_wide.data());
    engine::detail::VelocitiesOfMoves(h, x_one.data(), previous_one.data(), begin, end, v_one.data(), 1);
    for (std::uint32_t i = 0; i < n; ++i) {
      REQUIRE(Bits(previous_wide[i].x) == Bits(previous_one[i].x));
      REQUIRE(Bits(previous_wide[i].y) == Bits(previous_one[i].y));
      REQUIRE(Bits(v_wide[i].x) == Bits(v_one[i].x));
      REQUIRE(Bits(v_wide[i].y) == Bits(v_one[i].y));
    }
  }
}
