// The narrow-phase stage of a step: a contact manifold for every candidate pair that touches or
// comes within its speculative margin, warm-started with last step's impulses. Internal.
#pragma once

#include <span>
#include <vector>

#include "body_geometry.h"
#include "body_pair.h"
#include "engine/body.h"
#include "engine/contact.h"
#include "engine/ids.h"
#include "parallel/per_thread.h"
#include "parallel/worker_pool.h"

namespace engine::detail {

/// Whether two bodies' shapes overlap or touch (what a sensor reports); the geometry of a body
/// made of parts, null for a lone circle or box.
bool ShapesOverlap(const BodyInfo& ia, const BodyState& a, const BodyGeometry* ga, const BodyInfo& ib,
                   const BodyState& b, const BodyGeometry* gb);

/// The order of contacts: by body pair, then by the pieces of bodies made of parts.
inline bool ContactBefore(const Contact& x, const Contact& y) {
  if (x.a != y.a) return x.a < y.a;
  if (x.b != y.b) return x.b < y.b;
  if (x.piece_a != y.piece_a) return x.piece_a < y.piece_a;
  return x.piece_b < y.piece_b;
}

/// The body slots' geometries (Bodies::geometries).
using Geometries = std::span<const std::shared_ptr<const BodyGeometry>>;

class NarrowPhase {
 public:
  /// This step's contacts for `pairs` (sorted by (a, b)), `margins` per body; `box_turns` per
  /// body, MakeRot of its angle for every box of one shape (others not read:
  /// CandidatePairs::BoxTurns). `parts`: some body is made of parts (else the loop is the one
  /// circles and boxes always had). The pairs are shared among `pool`'s threads; the contacts
  /// come out the same in any case.
  void Update(std::span<const BodyPair> pairs, std::span<const BodyState> states,
              std::span<const BodyInfo> infos, Geometries geometries, std::span<const double> margins,
              std::span<const Rot> box_turns, bool parts, WorkerPool& pool);

  /// Forgets the body's contacts (destroyed or disabled), so none warm-starts a body that takes
  /// its slot.
  void RemoveBody(BodyIndex index) {
    std::erase_if(contacts_, [&](const Contact& c) { return c.a == index || c.b == index; });
    std::erase_if(contact_pairs_, [&](const BodyPair& p) { return p.a == index || p.b == index; });
  }

  std::vector<Contact>& Contacts() { return contacts_; }
  const std::vector<Contact>& Contacts() const { return contacts_; }
  /// The bodies of each of this step's contacts, in order, written beside them by Update. Searches
  /// that want only who touches whom read an eighteenth of the memory, little of it from another
  /// core where the threads shared the pairs.
  std::span<const BodyPair> ContactPairs() const { return contact_pairs_; }

 private:
  /// Fewer pairs than this are collided on one thread (the hand-off would cost more).
  static constexpr std::size_t kMinSharedPairs = 4096;

  /// Where Collide puts contacts and their bodies: two lists written from `count` on, over the
  /// elements they hold and then at their ends. The first thread writes over the lists
  /// themselves (the contacts of two steps ago, the pairs of the last: every element is written
  /// again or cut off after), so that its part, about half the contacts, is not copied into place.
  struct Lists {
    std::vector<Contact>* contacts;
    std::vector<BodyPair>* pairs;
    std::size_t count = 0;  ///< how many have been put
  };

  /// Puts the contacts of `pairs` and their bodies into `out`, carrying impulses from last step's
  /// contacts from `previous` on.
  template <bool kParts>
  void Collide(std::span<const BodyPair> pairs, std::span<const BodyState> states,
               std::span<const BodyInfo> infos, Geometries geometries, std::span<const double> margins,
               std::span<const Rot> box_turns, std::size_t previous, Lists* out) const;

  std::vector<Contact> contacts_;
  std::vector<Contact> previous_contacts_;
  std::vector<BodyPair> contact_pairs_;
  /// Each thread's part but the first's, when shared, and its contacts' bodies.
  std::vector<PerThread<std::vector<Contact>>> thread_contacts_;
  std::vector<PerThread<std::vector<BodyPair>>> thread_pairs_;
};

}  // namespace engine::detail
