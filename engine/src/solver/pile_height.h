// How tall a pile stands, in body sizes: what decides whether a pile that nothing turns in takes
// a second velocity pass (SubstepSolver::PassesForPile). Measured in runs of the contacts, so
// threads can each take runs (beside filling the constraints) and the sum is the same bits as on
// one thread. Internal to the engine.
#pragma once

#include <cstddef>
#include <limits>
#include <span>

#include "engine/body.h"
#include "engine/contact.h"

namespace engine::detail {

/// The contacts a PileExtent is measured over at a time: the runs' sums are added in run order.
inline constexpr std::size_t kPileRun = 512;

/// What PileHeightInBodies sums over the contacts between two moving bodies: the lowest and
/// highest centre along `up`, and the distances between the centres of each pair.
struct PileExtent {
  double low = std::numeric_limits<double>::infinity();
  double high = -std::numeric_limits<double>::infinity();
  double spacing = 0.0;  ///< the sum of the pairs' centre distances
  std::size_t pairs = 0;

  /// Adds a later run's extent.
  void Merge(const PileExtent& later);
  /// The span of the centres over the mean distance between two that touch (0 without a pair).
  double HeightInBodies() const;
};

/// The extent of one run of contacts (at most kPileRun, the runs starting at multiples of it).
PileExtent MeasurePile(std::span<const Contact> run, std::span<const BodyInfo> infos,
                       std::span<const BodyState> states, Vec2 up);

/// How tall the bodies in contact stand along `up`, in body sizes: the span of their centres
/// over the mean distance between the centres of two moving bodies that touch (0 without such
/// a pair). A measure of how many bodies a pile's bottom carries. The runs of kPileRun contacts
/// measured in turn and merged in order.
double PileHeightInBodies(std::span<const Contact> contacts, std::span<const BodyInfo> infos,
                          std::span<const BodyState> states, Vec2 up);

}  // namespace engine::detail
