// Concave polygons split into convex pieces: ear clipping (Meisters, "Polygons have ears",
// 1975; Eberly, "Triangulation by Ear Clipping") then Hertel–Mehlhorn merging (Hertel and
// Mehlhorn, "Fast triangulation of simple polygons", 1983): every diagonal whose removal keeps
// both sides convex is removed, which leaves at most 2r + 1 pieces for r reflex vertices and so
// at most four times the fewest possible.
#pragma once

#include <vector>

#include "geometry/outline.h"

namespace engine::geometry {

/// Convex pieces (counter-clockwise, no collinear points) covering a simple outline exactly,
/// in a deterministic order; a convex outline comes back as one piece. Each piece has at most as
/// many points as the outline. Precondition: `outline` is NormaliseOutline's output for a valid
/// outline. Empty only if rounding hides every ear (a near-degenerate sliver).
std::vector<Outline> DecomposeConvex(const Outline& outline);

}  // namespace engine::geometry
