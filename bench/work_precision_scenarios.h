// The analytic scenarios S1-S7 of accuracy.md §2 as engine worlds with their closed forms, and
// the error figures of one run; shared by bench_work_precision and the test that runs each briefly.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "engine/world.h"

namespace work_precision {

constexpr double kPi = 3.14159265358979323846;
constexpr double kG = 9.81;  // accuracy.md's g (the engine's default is 9.8)

struct Method {
  engine::Integrator integrator;
  const char* name;
  int evaluations;  ///< force evaluations per step (forces.md)
  int order;        ///< theoretical order of accuracy
};

inline const std::vector<Method>& Methods() {
  static const std::vector<Method> methods = {
      {engine::Integrator::kSemiImplicitEuler, "semi-implicit Euler", 1, 1},
      {engine::Integrator::kExplicitEuler, "explicit Euler", 1, 1},
      {engine::Integrator::kVelocityVerlet, "velocity Verlet", 2, 2},
      {engine::Integrator::kMidpoint, "midpoint", 2, 2},
      {engine::Integrator::kRungeKutta4, "RK4", 4, 4},
  };
  return methods;
}

/// h = 1/30 s down to 1/3840 s in factors of 2 (1/60 s with 1 to 64 substeps, and 1/30 s).
inline std::vector<int> StepRates() { return {30, 60, 120, 240, 480, 960, 1920, 3840}; }

struct Scenario {
  std::string id;     ///< "S1"
  std::string title;  ///< "projectile"
  double duration = 0;  ///< s simulated
  /// m: a position error this large means the run has left the problem (a blow-up); the orbit's
  /// position error saturates at its size, so S6 judges by energy instead.
  double scale = 0;
  bool conservative = false;  ///< energy is invariant: its error is the second figure
  /// Explicit Euler and midpoint multiply the oscillator's energy by a constant > 1 every step:
  /// unstable at every h (accuracy.md S2), however slowly it shows.
  bool growth_is_instability = false;
  std::function<engine::World(engine::Integrator, double h)> build;
  /// The watched position: the body's contact height, or the orbit's relative position.
  std::function<engine::Vec2(const engine::World&)> observed;
  std::function<engine::Vec2(double t)> exact;
  std::function<double(const engine::World&)> energy;  ///< conservative scenarios only
};

/// Free motion at one world step of h: the default (substep) solver with one substep, awake, so
/// the step is exactly h and nothing else changes the motion; the integrator is the variable.
inline engine::WorldDef Def(engine::Integrator integrator, double h, engine::Vec2 gravity) {
  engine::WorldDef def;
  def.integrator = integrator;
  def.dt = h;
  def.gravity = gravity;
  def.substeps = 1;
  def.sleeping = false;
  return def;
}

inline engine::BodyDef Ball(engine::Vec2 position, engine::Vec2 velocity, double mass, double radius = 0.5) {
  engine::BodyDef def;
  def.shape.radius = radius;
  def.position = position;
  def.velocity = velocity;
  def.mass = mass;
  return def;
}

inline engine::Vec2 FirstBody(const engine::World& world) { return world.State({0}).position; }

// S2 and S3: m = 1 on a spring of rest length 0 to the origin, from x = 1 at rest.
inline engine::World SpringWorld(engine::Integrator integrator, double h, double damping) {
  engine::World world(Def(integrator, h, {0, 0}));
  engine::SpringDef spring;
  spring.body_a = world.CreateBody(Ball({1, 0}, {0, 0}, 1.0));
  spring.stiffness = 4 * kPi * kPi;
  spring.damping = damping;
  world.AddSpring(spring);
  return world;
}

/// Kepler's equation E − e·sin E = M by Newton's method: the orbit's exact position at t.
inline engine::Vec2 KeplerPosition(double t, double e) {
  const double mean = std::fmod(t, 2 * kPi);
  double anomaly = mean + e * std::sin(mean);
  for (int i = 0; i < 50; ++i) {
    const double change = (anomaly - e * std::sin(anomaly) - mean) / (1 - e * std::cos(anomaly));
    anomaly -= change;
    if (std::abs(change) < 1e-15) break;
  }
  return {std::cos(anomaly) - e, std::sqrt(1 - e * e) * std::sin(anomaly)};
}

constexpr double kBounceHeight = 1.0, kBounceRestitution = 0.8, kBounceThreshold = 1.0, kBallRadius = 0.5;

/// S7: the ball's contact height at t: parabolas between impacts, each leaving at e times the
/// impact speed; an impact slower than the engine's restitution threshold (1 m/s) stops it.
inline double BounceHeight(double t) {
  const double first = std::sqrt(2 * kBounceHeight / kG);
  if (t < first) return kBounceHeight - 0.5 * kG * t * t;
  double impact_time = first, speed = kG * first;
  while (speed >= kBounceThreshold) {
    const double up = kBounceRestitution * speed, flight = 2 * up / kG;
    if (t < impact_time + flight) {
      const double tau = t - impact_time;
      return up * tau - 0.5 * kG * tau * tau;
    }
    impact_time += flight;
    speed = up;
  }
  return 0.0;
}

inline std::vector<Scenario> Scenarios() {
  using engine::Vec2;
  using engine::World;
  std::vector<Scenario> out;

  Scenario s1{"S1", "projectile", 2.0, 10.0, false, false, {}, FirstBody, {}, {}};
  s1.build = [](engine::Integrator integrator, double h) {
    World world(Def(integrator, h, {0, -kG}));
    world.CreateBody(Ball({0, 0}, {10, 10}, 1.0));
    return world;
  };
  s1.exact = [](double t) { return Vec2{10 * t, 10 * t - 0.5 * kG * t * t}; };
  out.push_back(s1);

  // Undamped, conservative: ω = 2π, period 1 s, E = ½·k.
  Scenario s2{"S2", "undamped spring", 10.0, 1.0, true, true, {}, FirstBody, {}, {}};
  s2.build = [](engine::Integrator integrator, double h) { return SpringWorld(integrator, h, 0.0); };
  s2.exact = [](double t) { return Vec2{std::cos(2 * kPi * t), 0}; };
  s2.energy = [](const World& world) {
    const engine::BodyState& s = world.State({0});
    return 0.5 * engine::Dot(s.velocity, s.velocity) + 0.5 * 4 * kPi * kPi * engine::Dot(s.position, s.position);
  };
  out.push_back(s2);

  // ζ = 0.1 by the spring's own damping c = 2ζω.
  Scenario s3{"S3", "damped spring", 5.0, 1.0, false, false, {}, FirstBody, {}, {}};
  s3.build = [](engine::Integrator integrator, double h) { return SpringWorld(integrator, h, 0.4 * kPi); };
  s3.exact = [](double t) {
    const double omega = 2 * kPi, zeta = 0.1, omega_d = omega * std::sqrt(1 - zeta * zeta);
    return Vec2{std::exp(-zeta * omega * t) * (std::cos(omega_d * t) + (zeta * omega / omega_d) * std::sin(omega_d * t)), 0};
  };
  out.push_back(s3);

  // m = 1, F = −b·v with b = 0.5 as the body's linear damping b/m: v_t = 19.62 m/s, τ = 2 s.
  Scenario s4{"S4", "linear drag", 5.0, 10.0, false, false, {}, FirstBody, {}, {}};
  s4.build = [](engine::Integrator integrator, double h) {
    World world(Def(integrator, h, {0, -kG}));
    engine::BodyDef body = Ball({0, 0}, {0, 0}, 1.0);
    body.linear_damping = 0.5;
    world.CreateBody(body);
    return world;
  };
  s4.exact = [](double t) {
    const double terminal = kG / 0.5, tau = 2.0;
    return Vec2{0, -terminal * t + tau * terminal * (1 - std::exp(-t / tau))};
  };
  out.push_back(s4);

  // c = ½·ρ·C_d·2r = 0.05 kg/m with ρ = 1, C_d = 0.1, r = 0.5: v_t = 14.007 m/s.
  Scenario s5{"S5", "quadratic drag", 5.0, 10.0, false, false, {}, FirstBody, {}, {}};
  s5.build = [](engine::Integrator integrator, double h) {
    engine::WorldDef def = Def(integrator, h, {0, -kG});
    def.fluid_density = 1.0;
    World world(def);
    engine::BodyDef body = Ball({0, 0}, {0, 0}, 1.0, 0.5);
    body.drag_coefficient = 0.1;
    world.CreateBody(body);
    return world;
  };
  s5.exact = [](double t) {
    const double terminal = std::sqrt(kG / 0.05);
    return Vec2{0, -(terminal * terminal / kG) * std::log(std::cosh(kG * t / terminal))};
  };
  out.push_back(s5);

  // e = 0.6, GM = 1, 10 orbits of period 2π: a sun of 1 kg with G = 1 and a planet of 1e-20 kg
  // (G·(M + m) rounds to 1), watched as the relative position.
  Scenario s6{"S6", "Kepler orbit e = 0.6", 20 * kPi, 1.0, true, false, {}, {}, {}, {}};
  s6.build = [](engine::Integrator integrator, double h) {
    engine::WorldDef def = Def(integrator, h, {0, 0});
    def.gravitational_constant = 1.0;
    World world(def);
    world.CreateBody(Ball({0, 0}, {0, 0}, 1.0, 0.01));
    world.CreateBody(Ball({0.4, 0}, {0, 2}, 1e-20, 0.01));
    return world;
  };
  s6.observed = [](const World& world) { return world.State({1}).position - world.State({0}).position; };
  s6.exact = [](double t) { return KeplerPosition(t, 0.6); };
  s6.energy = [](const World& world) {
    const Vec2 r = world.State({1}).position - world.State({0}).position;
    const Vec2 v = world.State({1}).velocity - world.State({0}).velocity;
    return 0.5 * engine::Dot(v, v) - 1.0 / engine::Length(r);
  };
  out.push_back(s6);

  // h0 = 1 m of contact height, e = 0.8, on a static floor: six bounces in 3 s.
  Scenario s7{"S7", "bouncing ball e = 0.8", 3.0, 1.0, false, false, {}, {}, {}, {}};
  s7.build = [](engine::Integrator integrator, double h) {
    World world(Def(integrator, h, {0, -kG}));
    engine::BodyDef floor;
    floor.shape = {engine::ShapeType::kBox, 0, {4, 0.5}};
    floor.position = {0, -0.5};
    floor.is_static = true;
    world.CreateBody(floor);
    engine::BodyDef ball = Ball({0, kBounceHeight + kBallRadius}, {0, 0}, 1.0, kBallRadius);
    ball.restitution = kBounceRestitution;
    world.CreateBody(ball);
    return world;
  };
  s7.observed = [](const World& world) { return world.State({1}).position - Vec2{0, kBallRadius}; };
  s7.exact = [](double t) { return Vec2{0, BounceHeight(t)}; };
  out.push_back(s7);
  return out;
}

inline int StepsFor(const Scenario& scenario, int rate) {
  return static_cast<int>(std::lround(scenario.duration * rate));
}

/// One run's figures, measured at every step (never inside a timed run).
struct Figures {
  int steps = 0;
  double position_error = 0;  ///< l∞ over the steps of |observed − exact|, m
  double energy_error = std::numeric_limits<double>::quiet_NaN();  ///< max |ΔE|/|E0|
  double energy_slope = std::numeric_limits<double>::quiet_NaN();  ///< fitted d(ΔE/|E0|)/dt, 1/s
  bool finite = true;
  bool energy_grows_every_step = false;
  std::uint64_t hash = 0;  ///< the final state, to check that timed runs did the same work
  std::string unstable;    ///< empty, or why the run counts as unstable
  /// Unstable by leaving the problem (not finite, energy doubled, error beyond the scene's size),
  /// as opposed to an energy that grows slowly but every step while the error still converges.
  bool blew_up = false;
};

inline Figures Measure(const Scenario& scenario, engine::Integrator integrator, int rate, int max_steps = 0) {
  const double h = 1.0 / rate;
  engine::World world = scenario.build(integrator, h);
  Figures f;
  f.steps = StepsFor(scenario, rate);
  if (max_steps > 0) f.steps = std::min(f.steps, max_steps);
  const double e0 = scenario.conservative ? scenario.energy(world) : 0.0;
  double previous_energy = e0, st = 0, se = 0, stt = 0, ste = 0;
  if (scenario.conservative) f.energy_error = 0, f.energy_grows_every_step = true;
  for (int step = 1; step <= f.steps; ++step) {
    world.Step();
    const double t = step * h;
    const engine::Vec2 d = scenario.observed(world) - scenario.exact(t);
    const double error = engine::Length(d);
    if (!std::isfinite(error)) {
      f.finite = false;
      break;
    }
    f.position_error = std::max(f.position_error, error);
    if (scenario.conservative) {
      const double energy = scenario.energy(world), relative = (energy - e0) / std::abs(e0);
      f.energy_error = std::max(f.energy_error, std::abs(relative));
      f.energy_grows_every_step = f.energy_grows_every_step && energy > previous_energy;
      previous_energy = energy;
      st += t, se += relative, stt += t * t, ste += t * relative;
    }
  }
  if (scenario.conservative && f.finite) {
    const double n = f.steps;
    f.energy_slope = (n * ste - st * se) / (n * stt - st * st);
  }
  f.hash = world.StateHash();
  if (!f.finite) {
    f.position_error = f.energy_error = std::numeric_limits<double>::infinity();
    f.unstable = "non-finite state";
  } else if (scenario.conservative && f.energy_error >= 1.0) {
    f.unstable = "energy error above 100%";
  } else if (scenario.id != "S6" && f.position_error >= scenario.scale) {
    f.unstable = "position error above the scene's size";
  } else if (scenario.growth_is_instability && f.energy_grows_every_step) {
    f.unstable = "energy grows every step";
  }
  f.blew_up = !f.unstable.empty() && !(scenario.growth_is_instability && f.energy_grows_every_step);
  return f;
}

}  // namespace work_precision
