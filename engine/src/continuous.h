// The continuous pass for bodies made of parts: a fast one that the step carried through
// something is put back where it first touched it. Internal to the engine.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "bodies.h"
#include "body_pair.h"
#include "engine/world_def.h"

namespace engine::detail {

/// After the solver: every awake dynamic body made of parts that moved (or turned) more than
/// half its thinnest width in the step is swept from where it started to where it ended against
/// the static and kinematic bodies of its candidate pairs (a bullet also against dynamic ones),
/// piece by piece, by conservative advancement on the GJK distance (geometry/time_of_impact.h).
/// The first touch within the step puts it back there, its velocity kept; the next step's
/// speculative contact then stops it, as Box2D v3's continuous pass does (Catto, "Continuous
/// Collision", GDC 2013). Speculative contacts alone miss a fast-turning thin body: the normal
/// they take at the step's start is not the one it meets. `start_angles` holds each body's
/// angle when the step began (start_positions its centre).
/// Bodies a joint holds (`joined[i]` 1; empty: none) are left out: moving one back alone would
/// tear it off its joint (a ragdoll's shin came 3 m off its knee); their joints and speculative
/// contacts hold them.
void SolveContinuous(Bodies& bodies, std::span<const double> start_angles, std::span<const BodyPair> pairs,
                     std::span<const std::uint8_t> awake, std::span<const std::uint8_t> joined,
                     const WorldDef& def);

}  // namespace engine::detail
