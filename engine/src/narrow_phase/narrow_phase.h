// The narrow-phase stage of a step: a contact manifold for every candidate pair that touches or
// comes within its speculative margin, warm-started with last step's impulses. Internal.
#pragma once

#include <span>
#include <vector>

#include "body_pair.h"
#include "engine/body.h"
#include "engine/contact.h"
#include "engine/ids.h"

namespace engine::detail {

/// Whether two bodies' shapes overlap or touch (what a sensor reports).
bool ShapesOverlap(const BodyInfo& ia, const BodyState& a, const BodyInfo& ib, const BodyState& b);

class NarrowPhase {
 public:
  /// This step's contacts for `pairs` (sorted by (a, b)), `margins` per body.
  void Update(std::span<const BodyPair> pairs, std::span<const BodyState> states,
              std::span<const BodyInfo> infos, std::span<const double> margins);

  /// Forgets the body's contacts (destroyed or disabled), so none warm-starts a body that takes
  /// its slot.
  void RemoveBody(BodyIndex index) {
    std::erase_if(contacts_, [&](const Contact& c) { return c.a == index || c.b == index; });
  }

  std::vector<Contact>& Contacts() { return contacts_; }
  const std::vector<Contact>& Contacts() const { return contacts_; }

 private:
  std::vector<Contact> contacts_;
  std::vector<Contact> previous_contacts_;
};

}  // namespace engine::detail
