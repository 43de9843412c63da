// The order the substep solver visits contacts in, and its groups of contacts that share no
// moving body (what threads may solve side by side). Internal to the engine.
#pragma once

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <span>
#include <vector>

#include "engine/body.h"
#include "engine/contact.h"

namespace engine::detail {

/// The colour a contact takes when both its bodies have every lower one: it may share a body.
inline constexpr std::uint32_t kSharedColour = 63;

/// Gives each contact a colour, the lowest that no other contact of either of its moving bodies
/// already has (greedily, in contact order; static bodies take no colour, as they take no
/// impulse), and returns in `slot` each contact's place when the contacts are sorted by colour,
/// ties in contact order, and in `group_ends` where each colour's run ends.
///
/// Why: Gauss-Seidel visits contacts one after another, and each reads the velocities the last
/// one wrote. In contact (body-pair) order consecutive contacts mostly share their first body,
/// so every contact waits for the one before it to finish; within a colour no two contacts
/// share a body, and the processor solves several at once. The graph colouring Box2D v3 uses
/// for its wide solver (Catto, "Solver2D", 2024); here it buys instruction-level parallelism.
/// `body_marks` is scratch, one entry per body.
void ColourContacts(std::span<const Contact> contacts, std::span<const BodyInfo> infos,
                    std::vector<std::uint64_t>* body_marks, std::vector<std::uint32_t>* slot,
                    std::vector<std::uint32_t>* group_ends);

/// The order the substep solver visits contacts in: contact i's constraint sits at `slot[i]`,
/// and the constraints in [group_ends[g − 1], group_ends[g]) share no moving body.
struct ContactOrder {
  std::vector<std::uint32_t> slot;
  std::vector<std::uint32_t> group_ends;
  /// Groups from this one on may share a moving body (the colouring ran out of colours): they
  /// are solved on one thread.
  std::uint32_t parallel_groups = 0;
  std::vector<std::uint64_t> body_marks;  ///< scratch

  /// By colour: the fastest order on one thread, where the solve does not depend on order.
  void ByColour(std::span<const Contact> contacts, std::span<const BodyInfo> infos) {
    ColourContacts(contacts, infos, &body_marks, &slot, &group_ends);
    parallel_groups = std::min<std::uint32_t>(static_cast<std::uint32_t>(group_ends.size()), kSharedColour);
  }
  /// Contact order, one group on one thread: where a scene is built bottom-up, turning stacks
  /// converge better in it. (Regrouping it into levels of contacts that share no body keeps
  /// its bits, but a 4000-circle pour has 393 levels of about 24: too small to share out.)
  void AsFound(std::size_t contact_count) {
    slot.resize(contact_count);
    std::iota(slot.begin(), slot.end(), 0u);
    group_ends.assign(1, static_cast<std::uint32_t>(contact_count));
    parallel_groups = 0;
  }
};

}  // namespace engine::detail
