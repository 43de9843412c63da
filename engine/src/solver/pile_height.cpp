#include "solver/pile_height.h"

#include <algorithm>

namespace engine::detail {

void PileExtent::Merge(const PileExtent& later) {
  low = std::min(low, later.low);
  high = std::max(high, later.high);
  spacing += later.spacing;
  pairs += later.pairs;
}

double PileExtent::HeightInBodies() const {
  if (pairs == 0 || !(spacing > 0.0)) return 0.0;
  return (high - low) / (spacing / static_cast<double>(pairs));
}

PileExtent MeasurePile(std::span<const Contact> run, std::span<const BodyInfo> infos,
                       std::span<const BodyState> states, Vec2 up) {
  // Summed in locals: summed in the returned extent, which the compiler must suppose the inputs
  // may overlap, every contact stored the sums and loaded them back, each load waiting for the
  // store before it.
  PileExtent start;
  double low = start.low, high = start.high, spacing = start.spacing;
  std::size_t pairs = 0;
  for (const Contact& c : run) {
    if (HasInfiniteMass(infos[c.a]) || HasInfiniteMass(infos[c.b])) continue;
    const Vec2 a = states[c.a].position, b = states[c.b].position;
    spacing += Length(b - a);
    for (const double height : {Dot(a, up), Dot(b, up)}) {
      low = std::min(low, height);
      high = std::max(high, height);
    }
    ++pairs;
  }
  return {low, high, spacing, pairs};
}

double PileHeightInBodies(std::span<const Contact> contacts, std::span<const BodyInfo> infos,
                          std::span<const BodyState> states, Vec2 up) {
  PileExtent total;
  for (std::size_t begin = 0; begin < contacts.size(); begin += kPileRun) {
    total.Merge(MeasurePile(contacts.subspan(begin, std::min(kPileRun, contacts.size() - begin)), infos, states, up));
  }
  return total.HeightInBodies();
}

}  // namespace engine::detail
