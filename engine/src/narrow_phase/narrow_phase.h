// The narrow-phase stage of a step: a contact manifold for every candidate pair that touches or
// comes within its speculative margin, warm-started with last step's impulses. Internal.
#pragma once

#include <span>
#include <vector>

#include "body_pair.h"
#include "engine/body.h"
#include "engine/contact.h"

namespace engine::detail {

/// The manifold between two bodies (normal from a to b); false when they are farther apart than
/// `margin`. A box that has turned takes the oriented tests, an unturned one the exact
/// axis-aligned ones, so a scene where nothing turns computes exactly what the axis-aligned game
/// does.
bool CollideBodies(const BodyInfo& info_a, const BodyState& a, const BodyInfo& info_b, const BodyState& b,
                   double margin, Manifold* manifold);

class NarrowPhase {
 public:
  /// This step's contacts for `pairs` (sorted by (a, b)), `margins` per body.
  void Update(std::span<const BodyPair> pairs, std::span<const BodyState> states,
              std::span<const BodyInfo> infos, std::span<const double> margins);

  std::vector<Contact>& Contacts() { return contacts_; }
  const std::vector<Contact>& Contacts() const { return contacts_; }

 private:
  /// Last step's impulses on the points of `contact` that match by feature id, if the pair was
  /// in contact then with about the same normal. `previous` walks forward through last step's
  /// list, which is in the same pair order.
  void WarmStart(Contact* contact, std::size_t* previous) const;

  std::vector<Contact> contacts_;
  std::vector<Contact> previous_contacts_;
};

}  // namespace engine::detail
