// Ear clipping then Hertel–Mehlhorn, on vertex indices. O(n³) at worst for n ≤ 64 points, run
// once when a scene loads; every loop runs in index order, so the pieces are deterministic.
#include "geometry/decompose.h"

#include <algorithm>
#include <cmath>

namespace engine::geometry {

namespace {

using Piece = std::vector<int>;  // indices into the outline's points, counter-clockwise

struct Diagonal {
  int u, v;
};

double Orient(Vec2 a, Vec2 b, Vec2 c) { return Cross(b - a, c - a); }

// Whether the corner prev → x → next turns left, or is straight within `tolerance` (a distance
// of x behind the chord prev → next).
bool ConvexCorner(Vec2 prev, Vec2 x, Vec2 next, double tolerance) {
  return Orient(prev, x, next) >= -tolerance * Length(next - prev);
}

bool InsideOrOnTriangle(Vec2 a, Vec2 b, Vec2 c, Vec2 p) {
  return Orient(a, b, p) >= 0.0 && Orient(b, c, p) >= 0.0 && Orient(c, a, p) >= 0.0;
}

// An ear: a strictly convex corner whose triangle holds no other remaining point, not even on
// its edges (a point on the new diagonal would make it touch the outline).
bool IsEar(const Outline& outline, const std::vector<int>& remaining, std::size_t k) {
  const std::size_t m = remaining.size();
  const int prev = remaining[(k + m - 1) % m], cur = remaining[k], next = remaining[(k + 1) % m];
  const Vec2 a = outline.points[prev], b = outline.points[cur], c = outline.points[next];
  if (Orient(a, b, c) <= 0.0) return false;
  for (const int other : remaining) {
    if (other == prev || other == cur || other == next) continue;
    if (InsideOrOnTriangle(a, b, c, outline.points[other])) return false;
  }
  return true;
}

// Cuts off the first ear in index order until a triangle remains; the new edge of each cut is a
// diagonal.
bool ClipEars(const Outline& outline, std::vector<Piece>* triangles, std::vector<Diagonal>* diagonals) {
  std::vector<int> remaining(outline.count);
  for (int i = 0; i < outline.count; ++i) remaining[i] = i;
  while (remaining.size() > 3) {
    std::size_t k = 0;
    while (k < remaining.size() && !IsEar(outline, remaining, k)) ++k;
    if (k == remaining.size()) return false;
    const std::size_t m = remaining.size();
    const int prev = remaining[(k + m - 1) % m], next = remaining[(k + 1) % m];
    triangles->push_back({prev, remaining[k], next});
    diagonals->push_back({prev, next});
    remaining.erase(remaining.begin() + static_cast<std::ptrdiff_t>(k));
  }
  triangles->push_back(remaining);
  return true;
}

// The piece holding the directed edge a → b (each diagonal is one directed edge in each of the
// two pieces it separates), and where in it the edge starts.
std::size_t FindEdge(const std::vector<Piece>& pieces, int a, int b, std::size_t* start) {
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    const Piece& piece = pieces[p];
    for (std::size_t k = 0; k < piece.size(); ++k) {
      if (piece[k] == a && piece[(k + 1) % piece.size()] == b) {
        *start = k;
        return p;
      }
    }
  }
  return pieces.size();
}

// The piece turned so that it starts at index `first`.
Piece StartingAt(const Piece& piece, std::size_t first) {
  Piece turned(piece.begin() + static_cast<std::ptrdiff_t>(first), piece.end());
  turned.insert(turned.end(), piece.begin(), piece.begin() + static_cast<std::ptrdiff_t>(first));
  return turned;
}

// Removes the diagonal u → v if the union of its two pieces is convex at u and at v (the only
// corners that change).
void TryRemoveDiagonal(const Outline& outline, Diagonal d, double tolerance, std::vector<Piece>* pieces) {
  std::size_t start_p = 0, start_q = 0;
  const std::size_t p = FindEdge(*pieces, d.u, d.v, &start_p);
  const std::size_t q = FindEdge(*pieces, d.v, d.u, &start_q);
  if (p == pieces->size() || q == pieces->size()) return;
  // p from v round to u, then q's points strictly between u and v.
  const Piece from_v = StartingAt((*pieces)[p], (start_p + 1) % (*pieces)[p].size());
  const Piece from_u = StartingAt((*pieces)[q], (start_q + 1) % (*pieces)[q].size());
  Piece merged = from_v;
  merged.insert(merged.end(), from_u.begin() + 1, from_u.end() - 1);
  const auto at = [&](std::size_t k) { return outline.points[merged[k % merged.size()]]; };
  const std::size_t u_index = from_v.size() - 1;
  if (!ConvexCorner(at(u_index - 1), at(u_index), at(u_index + 1), tolerance)) return;
  if (!ConvexCorner(at(merged.size() - 1), at(0), at(1), tolerance)) return;
  (*pieces)[p] = merged;
  pieces->erase(pieces->begin() + static_cast<std::ptrdiff_t>(q));
}

// A piece's points, without the corners a merge left straight.
Outline ToOutline(const Outline& outline, const Piece& piece, double tolerance) {
  Outline out;
  const std::size_t m = piece.size();
  for (std::size_t k = 0; k < m; ++k) {
    const Vec2 prev = outline.points[piece[(k + m - 1) % m]];
    const Vec2 x = outline.points[piece[k]], next = outline.points[piece[(k + 1) % m]];
    if (std::abs(Orient(prev, x, next)) <= tolerance * Length(next - prev)) continue;
    out.points[out.count++] = x;
  }
  return out;
}

}  // namespace

std::vector<Outline> DecomposeConvex(const Outline& outline) {
  std::vector<Piece> pieces;
  std::vector<Diagonal> diagonals;
  if (!ClipEars(outline, &pieces, &diagonals)) return {};
  // One pass suffices: merging only widens the corners at a diagonal's ends, so a diagonal that
  // could not go stays needed (Hertel and Mehlhorn).
  const double tolerance = kCollinearTolerance * OutlineSize(outline.View());
  for (const Diagonal& d : diagonals) TryRemoveDiagonal(outline, d, tolerance, &pieces);
  std::vector<Outline> convex;
  convex.reserve(pieces.size());
  for (const Piece& piece : pieces) convex.push_back(ToOutline(outline, piece, tolerance));
  return convex;
}

}  // namespace engine::geometry
