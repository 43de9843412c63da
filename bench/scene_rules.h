// What bench_solver's stress scenes (stress_scenes.h, solver_scenes.h) and the engine-neutral
// peer scenes (peers/scenes.h) share, so the two programs build and measure the same thing: the
// pour's jittered grid and the bouncing ball with its apex figure.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "engine/math.h"

namespace bench {

/// Places `count` bodies of `size` (radius or half extent) on a grid of pitch 2.3 `size` filling a
/// container of inner `width` from its floor at y = 0, row by row, each moved by up to a tenth of
/// `size` and given up to 1 m/s on each axis: `place(position, velocity)` per body, in order.
template <class Place>
void JitteredGrid(int count, double size, double width, std::uint64_t seed, Place place) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.1 * size, 0.1 * size);
  std::uniform_real_distribution<double> speed(-1.0, 1.0);
  const double pitch = 2.3 * size;
  const int per_row = static_cast<int>((width - pitch) / pitch);
  for (int i = 0; i < count; ++i) {
    // Braced lists evaluate left to right: the draws come in the same order on every compiler.
    const engine::Vec2 position{-0.5 * width + pitch * (1 + i % per_row) + jitter(rng),
                                pitch * (1 + i / per_row) + jitter(rng)};
    const engine::Vec2 velocity{speed(rng), speed(rng)};
    place(position, velocity);
  }
}

// The bouncing ball: dropped from kBallDrop above the floor with restitution kBallRestitution for
// ball and floor, judged on its first kBallBounces apexes. The cradle's striker comes at kCradleSpeed.
constexpr double kBallDrop = 10.0, kBallRestitution = 0.8, kBallRadius = 0.5, kCradleSpeed = 3.0;
constexpr int kBallBounces = 5;

/// The ball's apexes above the contact height, from its state at the end of every step (as the
/// solver test samples them), against e^(2n)·kBallDrop.
class BounceApexes {
 public:
  void Observe(double y, double vy) {
    if (previous_vy_ <= 0 && vy > 0) flying_up_ = true, highest_ = 0;
    highest_ = std::max(highest_, y - kBallRadius);
    if (flying_up_ && vy <= 0) {
      apexes_.push_back(highest_);
      flying_up_ = false;
    }
    previous_vy_ = vy;
  }

  /// The apexes seen, up to kBallBounces.
  int Bounces() const { return static_cast<int>(std::min<std::size_t>(apexes_.size(), kBallBounces)); }

  /// The largest error of an apex relative to its closed form; NaN before the first apex.
  double WorstError() const {
    double worst = apexes_.empty() ? std::numeric_limits<double>::quiet_NaN() : 0.0;
    for (std::size_t n = 0; n < apexes_.size() && n < kBallBounces; ++n) {
      const double expected = std::pow(kBallRestitution, 2.0 * (n + 1)) * kBallDrop;
      worst = std::max(worst, std::abs(apexes_[n] - expected) / expected);
    }
    return worst;
  }

 private:
  std::vector<double> apexes_;
  double previous_vy_ = 0, highest_ = 0;
  bool flying_up_ = false;
};

}  // namespace bench
