// Whether a step's contact graph is the last step's: then what was found from the graph alone
// (the colour order, the shock levels) is still right. Internal to the engine.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "body_pair.h"
#include "engine/body.h"

namespace engine::detail {

/// The contact graph as the colour order and the shock levels read it: the contacts' bodies in
/// contact order, and which bodies are fixed (infinite mass). Both are functions of it and of
/// nothing else, so a step whose graph is the one remembered (a pile at rest: a pyramid of base
/// 40 keeps its pairs from step to step) may keep the last ones instead of finding them again.
class ContactGraphMemo {
 public:
  /// Whether `pairs` and the bodies' fixedness are what the last call saw, with nothing
  /// forgotten since; remembers them either way.
  ///
  /// The fixedness is looked at only once the pairs are the same as the last call's: a pass
  /// over every body's info, it took 8.6 kcyc a step of the 4 000-circle pour on the calling
  /// thread alone, where the pairs change every step. So after the pairs change, the call
  /// that first sees them again answers false too (it sees the fixedness then), and the graph
  /// is kept from the one after.
  bool Same(std::span<const BodyPair> pairs, std::span<const BodyInfo> infos) {
    if (!valid_ || !std::equal(pairs.begin(), pairs.end(), pairs_.begin(), pairs_.end())) {
      pairs_.assign(pairs.begin(), pairs.end());
      valid_ = true;
      fixed_seen_ = false;
      return false;
    }
    fixed_now_.resize(infos.size());
    for (std::size_t i = 0; i < infos.size(); ++i) fixed_now_[i] = HasInfiniteMass(infos[i]) ? 1 : 0;
    const bool same = fixed_seen_ && fixed_now_ == fixed_;
    if (!same) {
      fixed_.swap(fixed_now_);
      fixed_seen_ = true;
    }
    return same;
  }
  /// After what was found from the graph was found again from another (or not at all): the next
  /// call answers false.
  void Forget() { valid_ = false; }

 private:
  std::vector<BodyPair> pairs_;
  std::vector<std::uint8_t> fixed_, fixed_now_;
  bool valid_ = false;       ///< pairs_ are the last call's
  bool fixed_seen_ = false;  ///< and fixed_ the fixedness of the last call, which had them too
};

}  // namespace engine::detail
