// Preconditions of the public API, checked in every build. Internal to the engine.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace engine::detail {

/// A violated precondition stops the program with its reason instead of quietly corrupting the
/// simulation (or reading another body's memory). The edges (scene loader, scripts) validate
/// user input first, so a user never meets this; an embedder's bug does.
inline void Require(bool condition, const char* what) {
  if (condition) return;
  std::fprintf(stderr, "engine precondition failed: %s\n", what);
  std::abort();
}

inline bool IsPositiveFinite(double v) { return std::isfinite(v) && v > 0.0; }
inline bool IsNonNegativeFinite(double v) { return std::isfinite(v) && v >= 0.0; }

}  // namespace engine::detail
