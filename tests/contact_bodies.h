// Each contact's bodies, in order: what the narrow phase writes beside its contacts
// (NarrowPhase::ContactPairs), for tests that hand made-up contacts to the solver's searches.
#pragma once

#include <span>
#include <vector>

#include "body_pair.h"
#include "engine/contact.h"

namespace testing {

inline std::vector<engine::BodyPair> BodiesOf(std::span<const engine::Contact> contacts) {
  std::vector<engine::BodyPair> pairs;
  pairs.reserve(contacts.size());
  for (const engine::Contact& c : contacts) pairs.push_back({c.a, c.b});
  return pairs;
}

}  // namespace testing
