// The order the substep solver visits contacts in: by colour, so that neighbouring constraints
// seldom share a body. Internal to the engine.
#pragma once

#include <cstdint>
#include <numeric>
#include <span>
#include <vector>

#include "engine/body.h"
#include "engine/contact.h"

namespace engine::detail {

/// Gives each contact a colour, the lowest that no other contact of either of its moving bodies
/// already has (greedily, in contact order; static bodies take no colour, as they take no
/// impulse), and returns in `slot` each contact's place when the contacts are sorted by colour,
/// ties in contact order.
///
/// Why: Gauss-Seidel visits contacts one after another, and each reads the velocities the last
/// one wrote. In contact (body-pair) order consecutive contacts mostly share their first body,
/// so every contact waits for the one before it to finish; within a colour no two contacts
/// share a body, and the processor solves several at once. The graph colouring Box2D v3 uses
/// for its wide solver (Catto, "Solver2D", 2024); here it buys instruction-level parallelism.
/// `body_colours` is scratch, one entry per body.
void ColourContacts(std::span<const Contact> contacts, std::span<const BodyInfo> infos,
                    std::vector<std::uint64_t>* body_colours, std::vector<std::uint32_t>* slot);

/// The order the substep solver visits contacts in: contact i's constraint sits at `slot[i]`.
struct ContactOrder {
  std::vector<std::uint32_t> slot;
  std::vector<std::uint64_t> body_colours;  ///< ColourContacts' scratch

  void ByColour(std::span<const Contact> contacts, std::span<const BodyInfo> infos) {
    ColourContacts(contacts, infos, &body_colours, &slot);
  }
  /// Contact order: where a scene is built bottom-up, turning stacks converge better in it.
  void AsFound(std::size_t contact_count) {
    slot.resize(contact_count);
    std::iota(slot.begin(), slot.end(), 0u);
  }
};

}  // namespace engine::detail
