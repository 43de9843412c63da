// The bodies made of particles: soft bodies (docs/soft-bodies.md), fluid (docs/fluids.md) and
// effect particles from emitters (smoke, fire, sparks). Soft bodies and fluid are two-way
// coupled with the rigid bodies; effect particles only feel them.
#pragma once

#include <cstdint>
#include <optional>

#include "engine/ids.h"
#include "engine/math.h"
#include "engine/shape.h"
#include "engine/world_def.h"

namespace engine {

/// A soft body: a circle becomes a ring of particles round its rim held out by a pressure (the
/// area it keeps), a box a square lattice of particles held by edges, diagonals and cell areas.
/// Solved by XPBD (Macklin, Müller and Chentanez 2016, "XPBD: position-based simulation of
/// compliant constrained dynamics"): each constraint's compliance is the inverse of a physical
/// stiffness, so how far a soft body gives does not depend on the step or the iterations.
struct SoftBodyDef {
  Shape shape;                ///< kCircle or kBox
  Vec2 position;              ///< m: the centre
  double angle = 0.0;         ///< rad
  Vec2 velocity;              ///< m/s, every particle's
  double density = 1.0;       ///< kg/m²: the mass, density × area, is shared evenly by the particles
  /// m: between neighbouring particles (a box's sides are divided into whole cells no longer
  /// than this; a circle's rim into whole arcs); each particle is a disc of half this diameter.
  double spacing = 0.1;
  /// m/N: how far an edge one spacing long stretches per newton pulling it (XPBD's α; longer
  /// edges, in proportion). 0: the edges keep their length.
  double stretch_compliance = 1e-4;
  /// m/N: the same for a box's diagonals, which resist shear.
  double shear_compliance = 1e-4;
  /// m/N: the inverse of a 2D bulk modulus. Under a pressure P (N/m) a box cell's area, or a
  /// circle's whole area, shrinks by the fraction P × this (XPBD's α of the relative area
  /// change is this over the rest area). 0: the area is kept exactly.
  double area_compliance = 0.0;
  /// A circle's ring keeps `pressure` × its rest area (1: its own size; more: blown up).
  double pressure = 1.0;
  /// 1/s: each constraint's relative velocity along it decays at this rate (XPBD damping).
  double damping = 0.0;
  double friction = 0.3;      ///< against rigid bodies and other particles
  /// The particles that lie inside this body when the soft body is made are fastened to it
  /// (a beam clamped in a wall, a blob held by a rigid handle); they then move with it.
  std::optional<BodyId> attach_to;
};

/// A block of fluid: particles on a square lattice filling `region`, solved by position-based
/// fluids (Macklin and Müller 2013): a density constraint per particle with an artificial
/// pressure against clumping, XSPH viscosity and optional vorticity confinement. Every block in
/// a world shares the first one's spacing (the kernel's size); each keeps its own density.
struct FluidDef {
  AABB region;              ///< m: the lattice fills it, half a spacing in from its sides
  double spacing = 0.05;    ///< m between particles; the kernel reaches 2 spacings
  double density = 1000.0;  ///< kg/m²: the rest density; a particle's mass follows from it
  Vec2 velocity;            ///< m/s, every particle's
  double viscosity = 0.01;  ///< XSPH: the share of the neighbours' mean velocity taken each step
  double vorticity = 0.0;   ///< vorticity confinement strength (0: off)
  double friction = 0.0;    ///< against rigid bodies
};

/// A colour with straight (not premultiplied) alpha, 0..1; the engine carries it for the drawer.
struct Rgba {
  float r = 1.0f, g = 1.0f, b = 1.0f, a = 1.0f;
  friend constexpr bool operator==(Rgba, Rgba) = default;
};

/// How a drawer lays effect particles over what is behind them.
enum class EffectBlend : std::uint8_t {
  kAdditive,  ///< light adds up: fire, sparks
  kAlpha,     ///< covers what is behind by its alpha: smoke
};

/// An emitter of effect particles: light particles that feel gravity, drag and buoyancy and
/// bounce off the rigid bodies, which never feel them. Seeded: the same def makes the same
/// particles, step for step.
struct EmitterDef {
  Vec2 position;                   ///< m; in the body's frame when `body` is set
  /// The emitter rides on this body: its particles also leave with the velocity of the body's
  /// point, and stop coming if the body is destroyed.
  std::optional<BodyId> body;
  /// rad: the mean direction particles leave in; in the body's frame when `body` is set (it
  /// turns with the body, as a nozzle does).
  double direction = 1.5707963267948966;
  double spread = 0.3;             ///< rad: directions are uniform within ± this of it
  double speed = 2.0;              ///< m/s: the mean speed particles leave at
  double speed_spread = 0.5;       ///< m/s: speeds are uniform within ± this of it
  double rate = 100.0;             ///< particles per second
  double lifetime = 1.5;           ///< s: the mean
  double lifetime_spread = 0.3;    ///< s: lifetimes are uniform within ± this of it
  double size_start = 0.1;         ///< m: a particle's diameter when born
  double size_end = 0.3;           ///< m: and when it dies (linear in between)
  Rgba color_start;                ///< when born
  Rgba color_end{1.0f, 1.0f, 1.0f, 0.0f};  ///< when it dies
  EffectBlend blend = EffectBlend::kAdditive;
  double drag = 0.5;               ///< 1/s: velocity decays at this rate
  /// How much gravity is cancelled: 0 falls like a stone, 1 floats, 2 rises at g.
  double buoyancy = 0.0;
  /// Of the bounce off a rigid body (the body's own is not read); impacts slower than
  /// WorldDef::restitution_threshold do not bounce.
  double restitution = 0.3;
  double friction = 0.3;           ///< mixed with the body's as bodies mix theirs: √(a·b)
  bool collide = true;             ///< false: passes through everything
  std::uint64_t seed = 1;
  /// Alive at once. Births beyond wait for room, but no more than one carries over a step.
  std::uint32_t max_particles = 10000;
};

/// One effect particle.
struct EffectParticle {
  Vec2 position;
  Vec2 velocity;
  double age = 0.0;       ///< s since it was born
  double lifetime = 0.0;  ///< s it lives
  EmitterId emitter;
};

}  // namespace engine
