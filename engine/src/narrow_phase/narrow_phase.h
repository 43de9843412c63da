// The narrow-phase stage of a step: a contact manifold for every candidate pair that touches or
// comes within its speculative margin, warm-started with last step's impulses. Internal.
#pragma once

#include <span>
#include <vector>

#include "body_pair.h"
#include "engine/body.h"
#include "engine/contact.h"

namespace engine::detail {

class NarrowPhase {
 public:
  /// This step's contacts for `pairs` (sorted by (a, b)), `margins` per body.
  void Update(std::span<const BodyPair> pairs, std::span<const BodyState> states,
              std::span<const BodyInfo> infos, std::span<const double> margins);

  std::vector<Contact>& Contacts() { return contacts_; }
  const std::vector<Contact>& Contacts() const { return contacts_; }

 private:
  std::vector<Contact> contacts_;
  std::vector<Contact> previous_contacts_;
};

}  // namespace engine::detail
