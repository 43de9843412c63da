// Chain segments from a polyline: the ghost vertices are the neighbouring points, wrapping
// around for a loop and standing on the end point itself at an open end.
#include "geometry/chain.h"

namespace engine::geometry {

ChainCheck CheckChain(std::span<const Vec2> points, bool loop) {
  const int n = static_cast<int>(points.size());
  if (n < (loop ? 3 : 2)) return {ChainProblem::kTooFewPoints};
  for (int i = 0; i < n; ++i) {
    if (!IsFinite(points[i])) return {ChainProblem::kNotFinite, i};
  }
  const int segments = loop ? n : n - 1;
  for (int i = 0; i < segments; ++i) {
    if (points[i] == points[(i + 1) % n]) return {ChainProblem::kZeroLength, i};
  }
  return {};
}

std::vector<ChainSegment> MakeChain(std::span<const Vec2> points, bool loop) {
  const int n = static_cast<int>(points.size());
  const int segments = loop ? n : n - 1;
  std::vector<ChainSegment> chain;
  chain.reserve(segments);
  for (int i = 0; i < segments; ++i) {
    const int next = (i + 1) % n;
    const bool free_start = !loop && i == 0;
    const bool free_end = !loop && i == segments - 1;
    chain.push_back({free_start ? points[i] : points[(i + n - 1) % n], points[i], points[next],
                     free_end ? points[next] : points[(next + 1) % n]});
  }
  return chain;
}

}  // namespace engine::geometry
