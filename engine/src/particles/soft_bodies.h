// Soft bodies: their particles' layout (a box's lattice, a circle's ring), their constraints,
// and the XPBD passes over them (Macklin, Müller and Chentanez 2016). Internal.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "engine/ids.h"
#include "engine/particles.h"

namespace engine::detail {

/// Keeps the distance between two particles: an edge (stretch) or a diagonal (shear).
struct SoftEdge {
  std::uint32_t a = 0, b = 0;  ///< the soft body's own particle numbers
  double rest = 0.0;           ///< m
  double compliance = 0.0;     ///< m/N, XPBD's α
};

/// Keeps a polygon's area (a box cell, or a circle's whole ring) at `target`.
struct SoftArea {
  std::uint32_t first = 0;  ///< into SoftBody::area_vertices, anticlockwise
  std::uint32_t count = 0;
  double rest = 0.0;        ///< m²: the area the soft body was made with
  double target = 0.0;      ///< m²: the area kept (pressure × rest)
  double compliance = 0.0;  ///< XPBD's α of the relative change (area − target) / rest, 1/J
};

/// A particle fastened to a rigid body: it stays at `local` in the body's centre-of-mass frame.
struct SoftAttachment {
  std::uint32_t particle = 0;
  BodyIndex body = kNoBody;
  Vec2 local;
};

/// A soft body as made: its particles' rest layout and its constraints.
struct SoftBody {
  SoftBodyDef def;
  std::uint32_t first = 0;  ///< its particles' first index in ParticleSystem's arrays
  std::uint32_t count = 0;
  double particle_mass = 0.0;
  double radius = 0.0;
  std::vector<Vec2> rest_positions;  ///< where the particles were made, world
  std::vector<SoftEdge> edges;       ///< by colour: edges of one colour share no particle
  std::vector<SoftArea> areas;       ///< by colour, as the edges
  std::vector<std::uint32_t> area_vertices;
  std::vector<SoftAttachment> attachments;
  std::vector<std::uint32_t> outline;  ///< the rim, anticlockwise
};

/// Whether `def` meets World::CreateSoftBody's preconditions (the attached body aside): a
/// snapshot's definitions are checked with it before anything is built from them.
bool IsValidSoftBodyDef(const SoftBodyDef& def);

/// The layout and constraints of a soft body made from `def` (valid: World::CreateSoftBody's
/// preconditions), without attachments.
SoftBody MakeSoftBody(const SoftBodyDef& def);

/// One XPBD pass over the soft body's edges and areas: x are all particles' positions (the
/// body's from `body.first`), w their inverse masses, `lambda` its constraints' multipliers
/// this substep (edges then areas), h the substep.
void SolveSoftBody(const SoftBody& body, double h, std::span<Vec2> x, std::span<const double> w,
                   std::span<double> lambda, std::vector<Vec2>& scratch);

/// Damps each edge's stretching speed by the body's damping rate over a substep h, and a
/// ring's velocities relative to its rigid motion too (it has no bending constraint).
void DampSoftBody(const SoftBody& body, double h, std::span<const Vec2> x, std::span<Vec2> v,
                  std::span<const double> w);

/// J: the energy stored in the soft body's stretched edges and squeezed areas (Σ C²/2α over its
/// compliant constraints; an exact constraint stores none).
double SoftBodyElasticEnergy(const SoftBody& body, std::span<const Vec2> x);

}  // namespace engine::detail
