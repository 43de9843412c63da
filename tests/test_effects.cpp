// Effect particles (World::CreateEmitter): births counted against the rate and the cap, flight
// against the closed forms of gravity and drag, the spreads' ranges and means, determinism,
// bounces and rest on bodies that never feel them, emitters riding bodies, deaths and order, and
// the effect system's save and load.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "bodies.h"
#include "engine/world.h"
#include "particles/effects.h"
#include "snapshot/byte_stream.h"
#include "world_builders.h"

using engine::EffectParticle;
using engine::EmitterDef;
using engine::Vec2;
using engine::World;
using engine::WorldDef;

namespace {

// An emitter whose particles all leave at one speed in one direction and never die or collide,
// so that each one's flight has a closed form.
EmitterDef Steady(Vec2 position, double direction, double speed, double rate) {
  EmitterDef e;
  e.position = position;
  e.direction = direction;
  e.spread = 0.0;
  e.speed = speed;
  e.speed_spread = 0.0;
  e.rate = rate;
  e.lifetime = 1000.0;
  e.lifetime_spread = 0.0;
  e.drag = 0.0;
  e.collide = false;
  return e;
}

// One particle at a time, dropped from rest.
EmitterDef Dropper(Vec2 position, double size, double restitution) {
  EmitterDef e = Steady(position, 0.0, 0.0, 60.0);
  e.max_particles = 1;
  e.size_start = e.size_end = size;
  e.restitution = restitution;
  e.collide = true;
  return e;
}

std::vector<EffectParticle> Copy(const World& world) {
  return {world.Effects().begin(), world.Effects().end()};
}

bool SameBits(const EffectParticle& a, const EffectParticle& b) {
  return a.position == b.position && a.velocity == b.velocity && a.age == b.age && a.lifetime == b.lifetime &&
         a.emitter == b.emitter;
}

// A few dynamic boxes and circles dropped in a pile on a floor, for the one-way tests.
void AddPile(World* world) {
  world->CreateBody(testing::Floor(60.0));
  for (int i = 0; i < 6; ++i) {
    const double x = -1.5 + 0.6 * i;
    world->CreateBody(testing::Box({x, 0.5 + 0.7 * i}, {0.5, 0.5}));
    world->CreateBody(testing::Circle({x + 0.2, 3.0 + 0.5 * i}, 0.2));
  }
}

}  // namespace

TEST_CASE("effects: births after N steps are floor(rate·N·dt), and the cap holds", "[effects]") {
  SECTION("1.5 a step: every step's count exactly") {
    WorldDef def = testing::NoGravity();
    def.dt = 1.0 / 64.0;
    World world(def);
    world.CreateEmitter(Steady({0, 0}, 0.0, 1.0, 96.0));
    for (int n = 1; n <= 64; ++n) {
      world.Step();
      REQUIRE(world.Effects().size() == static_cast<std::size_t>(96 * n / 64));
    }
  }
  SECTION("5/3 a step, whose fractions round: every step's count exactly") {
    World world(testing::NoGravity());  // dt 1/60
    world.CreateEmitter(Steady({0, 0}, 0.0, 1.0, 100.0));
    for (int n = 1; n <= 600; ++n) {
      world.Step();
      REQUIRE(world.Effects().size() == static_cast<std::size_t>(100 * n / 60));
    }
  }
  SECTION("no more alive than max_particles; births resume as they die") {
    World world(testing::NoGravity());
    EmitterDef e = Steady({0, 0}, 0.0, 1.0, 600.0);  // 10 a step
    e.max_particles = 25;
    e.lifetime = 0.1;  // 6 steps
    world.CreateEmitter(e);
    // 10, 20, then 25 held for ten lifetimes: each dies within 6 steps, so births resumed as
    // each death made room.
    for (int n = 1; n <= 60; ++n) {
      world.Step();
      REQUIRE(world.Effects().size() == (n == 1 ? 10u : n == 2 ? 20u : 25u));
    }
  }
  SECTION("a rate of 0 stops it") {
    World world(testing::NoGravity());
    const engine::EmitterId id = world.CreateEmitter(Steady({0, 0}, 0.0, 1.0, 90.0));
    testing::StepTimes(world, 10);
    CHECK(world.Effects().size() == 15);
    world.SetEmitterRate(id, 0.0);
    testing::StepTimes(world, 10);
    CHECK(world.Effects().size() == 15);
  }
}

TEST_CASE("effects: free flight follows x0 + v0·t + ½·g·(1 − buoyancy)·t², births spread evenly", "[effects]") {
  World world(WorldDef{});  // g = (0, −9.8), dt = 1/60
  const Vec2 x0{1.0, 2.0};
  const double rate = 45.0, speed = 3.0, direction = 0.7;
  EmitterDef e = Steady(x0, direction, speed, rate);
  e.buoyancy = 0.25;
  world.CreateEmitter(e);
  const int steps = 90;
  testing::StepTimes(world, steps);
  const double dt = world.Def().dt;
  const Vec2 g = 0.75 * world.Def().gravity;
  const Vec2 v0{speed * std::cos(direction), speed * std::sin(direction)};
  const auto particles = world.Effects();
  REQUIRE(particles.size() == static_cast<std::size_t>(rate * steps * dt));
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const EffectParticle& p = particles[k];
    // The k-th (from 1) is born at k / rate, however the steps cut the time.
    const double t = steps * dt - static_cast<double>(k + 1) / rate;
    REQUIRE(p.age == Approx(t).margin(1e-12));
    const Vec2 exact = x0 + t * v0 + (0.5 * t * t) * g;
    // Semi-implicit Euler moves each step with the step's end velocity: after a first part step
    // τ and n whole steps it is ahead of the parabola by ½·g·(τ² + n·dt²), never more than
    // ½·|g|·t·dt.
    const double n = std::ceil(t / dt - 1e-9) - 1.0, tau = t - n * dt;
    const Vec2 lead = (0.5 * (tau * tau + n * dt * dt)) * g;
    CHECK(p.position.x == Approx(exact.x + lead.x).margin(1e-10));
    CHECK(p.position.y == Approx(exact.y + lead.y).margin(1e-10));
    CHECK(std::abs(p.position.y - exact.y) <= 0.5 * engine::Length(g) * t * dt + 1e-12);
    // The velocity has no such error: gravity is constant.
    CHECK(p.velocity.x == Approx(v0.x + t * g.x).margin(1e-12));
    CHECK(p.velocity.y == Approx(v0.y + t * g.y).margin(1e-12));
  }
}

TEST_CASE("effects: drag decays the velocity as exp(−drag·t), at any step", "[effects]") {
  for (const double dt : {1.0 / 60.0, 0.1}) {
    WorldDef def = testing::NoGravity();
    def.dt = dt;
    World world(def);
    EmitterDef e = Steady({0, 0}, 0.3, 5.0, 25.0);
    e.drag = 50.0;  // ×e^-5 a step of 0.1 s, where explicit Euler would flip and grow ×4
    world.CreateEmitter(e);
    testing::StepTimes(world, static_cast<int>(std::lround(0.5 / dt)));
    REQUIRE(world.Effects().size() >= 12);
    for (const EffectParticle& p : world.Effects()) {
      INFO("dt " << dt << ", age " << p.age);
      CHECK(engine::Length(p.velocity) == Approx(5.0 * std::exp(-50.0 * p.age)).epsilon(1e-12));
      CHECK(std::atan2(p.velocity.y, p.velocity.x) == Approx(0.3).epsilon(1e-12));
    }
  }
}

TEST_CASE("effects: lifetimes, directions and speeds lie within their spreads, their means near the means",
          "[effects]") {
  World world(testing::NoGravity());
  EmitterDef e;
  e.rate = 6000.0;  // 100 a step
  e.lifetime = 5.0;
  e.lifetime_spread = 1.0;
  e.direction = 1.0;
  e.spread = 0.5;
  e.speed = 4.0;
  e.speed_spread = 1.0;
  e.drag = 0.0;
  e.collide = false;
  world.CreateEmitter(e);
  testing::StepTimes(world, 20);
  const auto particles = world.Effects();
  REQUIRE(particles.size() == 2000);
  double lifetime_sum = 0.0, direction_sum = 0.0, speed_sum = 0.0;
  for (const EffectParticle& p : particles) {
    const double direction = std::atan2(p.velocity.y, p.velocity.x), speed = engine::Length(p.velocity);
    REQUIRE(p.lifetime >= 4.0);
    REQUIRE(p.lifetime <= 6.0);
    REQUIRE(std::abs(direction - 1.0) <= 0.5 + 1e-12);
    REQUIRE(std::abs(speed - 4.0) <= 1.0 + 1e-12);
    lifetime_sum += p.lifetime;
    direction_sum += direction;
    speed_sum += speed;
  }
  // Uniform on ±s has a standard deviation s/√3: the mean of 2000 is within 4 of its own.
  const double n = static_cast<double>(particles.size());
  const double sigma_of_mean = 1.0 / std::sqrt(3.0 * n);
  CHECK(std::abs(lifetime_sum / n - 5.0) < 4.0 * 1.0 * sigma_of_mean);
  CHECK(std::abs(direction_sum / n - 1.0) < 4.0 * 0.5 * sigma_of_mean);
  CHECK(std::abs(speed_sum / n - 4.0) < 4.0 * 1.0 * sigma_of_mean);
  // And they do spread: the extremes reach most of the way out.
  const auto [shortest, longest] = std::minmax_element(
      particles.begin(), particles.end(), [](const auto& a, const auto& b) { return a.lifetime < b.lifetime; });
  CHECK(shortest->lifetime < 4.05);
  CHECK(longest->lifetime > 5.95);
}

TEST_CASE("effects: the same seed makes the same particles; another seed, another stream", "[effects]") {
  const auto run = [](std::uint64_t seed) {
    World world(WorldDef{});
    AddPile(&world);
    EmitterDef sparks;
    sparks.position = {0.0, 5.0};
    sparks.direction = -1.2;
    sparks.spread = 1.0;
    sparks.rate = 500.0;
    sparks.seed = seed;
    world.CreateEmitter(sparks);
    EmitterDef smoke = sparks;
    smoke.position = {1.0, 1.5};
    smoke.buoyancy = 1.5;
    smoke.seed = seed + 100;
    world.CreateEmitter(smoke);
    testing::StepTimes(world, 200);
    return std::pair{world.StateHash(), Copy(world)};
  };
  const auto [hash_a, particles_a] = run(7);
  const auto [hash_b, particles_b] = run(7);
  const auto [hash_c, particles_c] = run(8);
  CHECK(hash_a == hash_b);
  REQUIRE(particles_a.size() == particles_b.size());
  CHECK(std::equal(particles_a.begin(), particles_a.end(), particles_b.begin(), SameBits));
  CHECK(hash_a != hash_c);
  const std::size_t n = std::min(particles_a.size(), particles_c.size());
  REQUIRE(n > 100);
  std::size_t same = 0;
  for (std::size_t i = 0; i < n; ++i) same += particles_a[i].lifetime == particles_c[i].lifetime;
  CHECK(same == 0);
}

TEST_CASE("effects: a particle dropped on a static box comes to rest on top, never below", "[effects]") {
  for (const bool turned : {false, true}) {
    WorldDef def;
    def.rotation = turned;
    World world(def);
    world.CreateBody(testing::Floor(4.0));  // top at y = 0
    world.CreateEmitter(Dropper({0.3, 1.0}, 0.1, 0.3));
    for (int n = 0; n < 300; ++n) {
      world.Step();
      REQUIRE(world.Effects().size() == 1);
      INFO("step " << n);
      REQUIRE(world.Effects()[0].position.y >= 0.05 - 1e-12);
    }
    const EffectParticle& p = world.Effects()[0];
    CHECK(p.position.y == Approx(0.05).margin(1e-12));
    CHECK(p.position.x == 0.3);
    CHECK(p.velocity.x == 0.0);
    CHECK(std::abs(p.velocity.y) < 1e-12);
  }
}

TEST_CASE("effects: a bouncing particle comes back at restitution × its impact speed", "[effects]") {
  for (const double restitution : {0.2, 0.5, 0.9}) {
    World world(WorldDef{});
    world.CreateBody(testing::Floor(4.0));
    const double height = 2.0, radius = 0.05;
    world.CreateEmitter(Dropper({0.0, height + radius}, 2.0 * radius, restitution));
    double before = 0.0, after = 0.0;
    for (int n = 0; n < 200 && after <= 0.0; ++n) {
      before = world.Effects().empty() ? 0.0 : world.Effects()[0].velocity.y;
      world.Step();
      after = world.Effects()[0].velocity.y;
    }
    REQUIRE(after > 0.0);
    // It struck in the step after `before`, gaining g·dt on the way in.
    const double impact = -before + 9.8 * world.Def().dt;
    INFO("restitution " << restitution);
    CHECK(after == Approx(restitution * impact).epsilon(1e-12));
    // And the impact was the free fall's from that height, to within a step's gain.
    CHECK(std::abs(impact - std::sqrt(2.0 * 9.8 * height)) <= 9.8 * world.Def().dt);
  }
}

TEST_CASE("effects: friction slows sliding by at most friction × the normal impulse", "[effects]") {
  WorldDef def = testing::NoGravity();
  World world(def);
  world.CreateBody(testing::WithMaterial(testing::Floor(40.0), 0.0, 0.5));
  EmitterDef e = Dropper({0.0, 0.3}, 0.1, 0.0);
  e.direction = -std::atan2(1.0, 4.0);  // 4 m/s along, 1 m/s down
  e.speed = std::hypot(4.0, 1.0);
  e.friction = 0.5;  // mixed with the floor's: √(0.5·0.5)
  world.CreateEmitter(e);
  double before = 0.0;
  for (int n = 0; n < 60; ++n) {
    const double vx = world.Effects().empty() ? 4.0 : world.Effects()[0].velocity.x;
    const double vy = world.Effects().empty() ? -1.0 : world.Effects()[0].velocity.y;
    world.Step();
    const EffectParticle& p = world.Effects()[0];
    if (vy < 0.0 && p.velocity.y == 0.0) {  // this step it struck the floor, without bounce (1 m/s)
      before = vx;
      CHECK(p.velocity.x == Approx(vx - 0.5 * 1.0).epsilon(1e-12));
      CHECK(p.position.y == Approx(0.05).margin(1e-12));
    }
  }
  CHECK(before == Approx(4.0).epsilon(1e-12));
  // Resting, nothing presses it on: it slides on at 3.5 m/s.
  CHECK(world.Effects()[0].velocity.x == Approx(3.5).epsilon(1e-12));
}

TEST_CASE("effects: a fast spark does not pass through a thin plank", "[effects]") {
  World world(testing::NoGravity());
  world.CreateBody(testing::Static(testing::Box({0, 0}, {2.0, 0.02})));
  EmitterDef e = Dropper({0.0, 0.6}, 0.02, 0.0);
  e.direction = -std::numbers::pi / 2;
  e.speed = 40.0;  // 0.67 m a step, 33 planks' thickness
  e.max_particles = 100;
  e.rate = 600.0;
  world.CreateEmitter(e);
  for (int n = 0; n < 30; ++n) {
    world.Step();
    for (const EffectParticle& p : world.Effects()) REQUIRE(p.position.y >= 0.01 + 0.01 - 1e-12);
  }
}

TEST_CASE("effects: particles pass through sensors, disabled bodies, and everything when collide is off",
          "[effects]") {
  for (int variant = 0; variant < 3; ++variant) {
    World world(WorldDef{});
    engine::BodyDef floor = testing::Floor(4.0);
    if (variant == 0) floor = testing::Sensor(floor);
    if (variant == 1) floor.enabled = false;
    world.CreateBody(floor);
    EmitterDef e = Dropper({0.0, 0.5}, 0.1, 0.3);
    e.collide = variant != 2;
    world.CreateEmitter(e);
    testing::StepTimes(world, 60);
    INFO("variant " << variant);
    CHECK(world.Effects()[0].position.y < -1.0);
  }
}

TEST_CASE("effects: the bodies never feel the particles", "[effects]") {
  for (const bool turned : {false, true}) {
    WorldDef def;
    def.rotation = turned;
    World plain(def), showered(def);
    AddPile(&plain);
    AddPile(&showered);
    EmitterDef sparks;
    sparks.position = {0.0, 6.0};
    sparks.direction = -std::numbers::pi / 2;
    sparks.spread = 0.8;
    sparks.speed = 6.0;
    sparks.rate = 3000.0;
    sparks.size_start = sparks.size_end = 0.05;
    sparks.restitution = 0.6;
    showered.CreateEmitter(sparks);
    for (int n = 0; n < 240; ++n) {
      plain.Step();
      showered.Step();
    }
    REQUIRE(showered.Effects().size() > 1000);
    for (const engine::BodyId id : plain.BodyIds()) {
      const engine::BodyState& a = plain.State(id);
      const engine::BodyState& b = showered.State(id);
      REQUIRE(a.position == b.position);
      REQUIRE(a.velocity == b.velocity);
      REQUIRE(a.angle == b.angle);
      REQUIRE(a.angular_velocity == b.angular_velocity);
    }
    // The sparks did strike: none went through the floor (one squeezed under a box may be a
    // little in it for a step), and many lie on something.
    std::size_t resting = 0;
    for (const EffectParticle& p : showered.Effects()) {
      REQUIRE(p.position.y > -0.025);
      resting += engine::Length(p.velocity) < 0.2;
    }
    CHECK(resting > 100);
  }
}

TEST_CASE("effects: an emitter riding a moving body emits from the body's point", "[effects]") {
  SECTION("a moving, turned body: the closed form of each particle") {
    World world(testing::NoGravity());
    engine::BodyDef cart = testing::Kinematic(testing::Box({0, 0}, {1, 1}), {3.0, 1.0});
    cart.angle = std::numbers::pi / 2;
    const engine::BodyId body = world.CreateBody(cart);
    EmitterDef e = Steady({0.8, 0.0}, 0.0, 2.0, 50.0);  // from its local +x side, outwards
    e.body = body;
    world.CreateEmitter(e);
    const int steps = 45;
    testing::StepTimes(world, steps);
    const double dt = world.Def().dt, now = steps * dt;
    const Vec2 cart_velocity{3.0, 1.0}, out{0.0, 1.0};  // local +x is world +y
    const Vec2 point0 = Vec2{0.0, 0.8};
    const auto particles = world.Effects();
    REQUIRE(particles.size() == static_cast<std::size_t>(50 * steps / 60));
    for (std::size_t k = 0; k < particles.size(); ++k) {
      const double born = static_cast<double>(k + 1) / 50.0;
      const Vec2 want = point0 + born * cart_velocity + (now - born) * (cart_velocity + 2.0 * out);
      CHECK(particles[k].position.x == Approx(want.x).margin(1e-9));
      CHECK(particles[k].position.y == Approx(want.y).margin(1e-9));
      CHECK(particles[k].velocity.x == Approx(3.0).margin(1e-12));
      CHECK(particles[k].velocity.y == Approx(3.0).margin(1e-12));
    }
  }
  SECTION("a spinning body: born at its rim point, leaving at the rim's speed") {
    WorldDef def = testing::NoGravity();
    def.rotation = true;
    World world(def);
    engine::BodyDef wheel = testing::Kinematic(testing::Circle({1.0, 1.0}, 0.5));
    wheel.angular_velocity = 3.0;
    const engine::BodyId body = world.CreateBody(wheel);
    EmitterDef e = Steady({1.0, 0.0}, 0.0, 0.0, 60.0);
    e.body = body;
    world.CreateEmitter(e);
    testing::StepTimes(world, 20);
    const double angle = world.State(body).angle;
    const Vec2 rim = Vec2{1.0, 1.0} + Vec2{std::cos(angle), std::sin(angle)};
    const EffectParticle& newest = world.Effects().back();
    CHECK(engine::Length(newest.position - rim) < 1e-9);  // one a step, born at the step's end
    CHECK(engine::Length(newest.velocity) == Approx(3.0).epsilon(1e-12));
  }
  SECTION("a body made of parts: the emitter's point is in the body's frame, not from its centre of mass") {
    WorldDef def = testing::NoGravity();
    def.rotation = true;
    World world(def);
    engine::BodyDef lever;
    lever.is_static = true;
    lever.position = {2.0, -1.0};
    lever.angle = 0.5;
    engine::ShapePart weight;
    weight.type = engine::ShapeType::kCircle;
    weight.radius = 0.3;
    weight.offset = {1.5, 0.0};
    lever.parts = {weight};
    const engine::BodyId body = world.CreateBody(lever);
    EmitterDef e = Steady({0.0, 0.5}, 0.0, 0.0, 60.0);
    e.body = body;
    world.CreateEmitter(e);
    world.Step();
    const Vec2 want = Vec2{2.0, -1.0} + Vec2{-0.5 * std::sin(0.5), 0.5 * std::cos(0.5)};
    CHECK(world.Effects()[0].position.x == Approx(want.x).margin(1e-12));
    CHECK(world.Effects()[0].position.y == Approx(want.y).margin(1e-12));
  }
  SECTION("its body destroyed, it stops") {
    World world(testing::NoGravity());
    const engine::BodyId body = world.CreateBody(testing::Circle({0, 0}, 0.5));
    EmitterDef e = Steady({1.0, 0.0}, 0.0, 1.0, 60.0);
    e.body = body;
    world.CreateEmitter(e);
    testing::StepTimes(world, 5);
    world.DestroyBody(body);
    world.CreateBody(testing::Circle({5, 5}, 0.5));  // takes the slot
    testing::StepTimes(world, 5);
    CHECK(world.Effects().size() == 5);
  }
}

TEST_CASE("effects: the dead go, the rest stay oldest first", "[effects]") {
  World world(WorldDef{});
  world.CreateBody(testing::Floor(20.0));
  EmitterDef a;
  a.rate = 130.0;
  a.lifetime = 0.5;
  a.lifetime_spread = 0.3;
  a.spread = 1.0;
  EmitterDef b = a;
  b.position = {1.0, 0.5};
  b.rate = 70.0;
  b.seed = 99;
  world.CreateEmitter(a);
  world.CreateEmitter(b);
  for (int n = 0; n < 180; ++n) {
    world.Step();
    const auto particles = world.Effects();
    for (std::size_t i = 0; i < particles.size(); ++i) {
      REQUIRE(particles[i].age < particles[i].lifetime);
      if (i > 0) REQUIRE(particles[i].age <= particles[i - 1].age);
    }
  }
  // All born in the last 0.8 s live and none older: at most 200 × 0.8, at least 200 × 0.2.
  const std::size_t alive = world.Effects().size();
  CHECK(alive <= 160);
  CHECK(alive >= 40);
  CHECK(world.Effects().front().age < 0.8);
}

TEST_CASE("effects: a destroyed emitter's particles live out their lives, and its slot waits for them",
          "[effects]") {
  World world(testing::NoGravity());
  EmitterDef e = Steady({0, 0}, 0.0, 1.0, 60.0);
  e.lifetime = 0.5;  // 30 steps
  const engine::EmitterId first = world.CreateEmitter(e);
  testing::StepTimes(world, 10);
  world.DestroyEmitter(first);
  CHECK_FALSE(world.IsValid(first));
  CHECK(world.EmitterIds().empty());
  const engine::EmitterId second = world.CreateEmitter(e);
  CHECK(second.index != first.index);  // the slot still has particles
  testing::StepTimes(world, 5);
  const auto of_first = [&] {
    return std::count_if(world.Effects().begin(), world.Effects().end(),
                         [&](const EffectParticle& p) { return p.emitter == first; });
  };
  CHECK(of_first() == 10);
  testing::StepTimes(world, 30);
  CHECK(of_first() == 0);
  world.DestroyEmitter(second);
  const engine::EmitterId third = world.CreateEmitter(e);
  CHECK(third.index == first.index);  // freed once its particles died
  CHECK(third.generation == first.generation + 1);
}

TEST_CASE("effects: the effect system saves and loads its whole state", "[effects]") {
  using engine::detail::ByteReader;
  using engine::detail::ByteWriter;
  using engine::detail::EffectSystem;
  const engine::detail::Bodies no_bodies;
  engine::detail::WorkerPool pool(1);
  WorldDef def;
  EffectSystem a;
  EmitterDef e;
  e.rate = 250.0;
  const engine::EmitterId first = a.Create(e);
  e.seed = 5;
  e.buoyancy = 1.4;
  e.body = engine::BodyId{3, 2};  // no such body: it waits
  a.Create(e);
  e.body.reset();
  e.rate = 37.0;
  a.Create(e);
  for (int n = 0; n < 30; ++n) a.Step(def, no_bodies, pool);
  a.Destroy(first.index);  // draining
  for (int n = 0; n < 3; ++n) a.Step(def, no_bodies, pool);
  std::vector<std::uint8_t> bytes;
  ByteWriter out(&bytes);
  a.Save(out);
  EffectSystem b;
  ByteReader in(bytes);
  REQUIRE(b.Load(in));
  CHECK(in.Remaining() == 0);
  for (int n = 0; n < 60; ++n) {
    a.Step(def, no_bodies, pool);
    b.Step(def, no_bodies, pool);
  }
  REQUIRE(a.Particles().size() == b.Particles().size());
  REQUIRE(!a.Particles().empty());
  CHECK(std::equal(a.Particles().begin(), a.Particles().end(), b.Particles().begin(), SameBits));
  CHECK(std::equal(a.Ids().begin(), a.Ids().end(), b.Ids().begin(), b.Ids().end()));
  CHECK(a.Create(e) == b.Create(e));  // the same free list

  SECTION("a truncated or corrupt save is refused and changes nothing") {
    const std::size_t had = b.Particles().size();
    for (const std::size_t cut : {std::size_t{0}, std::size_t{9}, bytes.size() / 2, bytes.size() - 1}) {
      ByteReader short_in(std::span<const std::uint8_t>(bytes).first(cut));
      CHECK_FALSE(b.Load(short_in));
    }
    std::vector<std::uint8_t> bad = bytes;
    bad[bad.size() - 9] = 0x7f;  // the last particle's emitter: a slot that is not there
    ByteReader bad_in(bad);
    CHECK_FALSE(b.Load(bad_in));
    CHECK(b.Particles().size() == had);
  }
}

TEST_CASE("effects: an emitter present but idle changes no bit of the world", "[effects]") {
  World without(WorldDef{}), with(WorldDef{});
  AddPile(&without);
  AddPile(&with);
  EmitterDef idle;
  idle.rate = 0.0;
  with.CreateEmitter(idle);
  testing::StepTimes(without, 120);
  testing::StepTimes(with, 120);
  CHECK(with.Effects().empty());
  CHECK(with.StateHash() == without.StateHash());
}

TEST_CASE("effects: a world snapshot carries the emitters and their particles, step for step", "[effects]") {
  WorldDef def;
  def.rotation = true;
  World world(def);
  AddPile(&world);
  EmitterDef sparks;
  sparks.position = {0.0, 5.0};
  sparks.direction = -1.0;
  sparks.rate = 400.0;
  const engine::EmitterId doomed = world.CreateEmitter(sparks);
  sparks.body = world.BodyIds()[3];
  sparks.position = {0.0, 0.4};
  sparks.seed = 9;
  world.CreateEmitter(sparks);
  testing::StepTimes(world, 60);
  world.DestroyEmitter(doomed);  // its particles still flying: the slot drains
  testing::StepTimes(world, 10);
  const std::vector<std::uint8_t> snapshot = world.TakeSnapshot();
  World restored(def);
  REQUIRE(restored.RestoreSnapshot(snapshot));
  CHECK(restored.StateHash() == world.StateHash());
  REQUIRE(restored.EmitterIds().size() == 1);
  CHECK(restored.EmitterIds()[0] == world.EmitterIds()[0]);
  CHECK(restored.GetEmitterDef(restored.EmitterIds()[0]).body == sparks.body);
  for (int n = 0; n < 90; ++n) {
    world.Step();
    restored.Step();
  }
  CHECK(restored.StateHash() == world.StateHash());
  const auto a = Copy(world), b = Copy(restored);
  REQUIRE(a.size() == b.size());
  CHECK(std::equal(a.begin(), a.end(), b.begin(), SameBits));
  // The same free list too: the next emitter gets the same id in both.
  CHECK(world.CreateEmitter(sparks) == restored.CreateEmitter(sparks));
}
