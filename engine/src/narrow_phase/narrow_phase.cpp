// Contacts from candidate pairs: the shape pair picks the collide function; last step's contact
// of the same pair hands its impulses on.
#include "narrow_phase/narrow_phase.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <memory>

#include "narrow_phase/collide.h"
#include "narrow_phase/collide_pieces.h"

namespace engine::detail {

namespace {

// The manifold between two bodies (normal from a to b); false when they are farther apart than
// `margin`. A box that has turned takes the oriented tests, an unturned one the exact
// axis-aligned ones, so a scene where nothing turns computes exactly what the axis-aligned game
// does. Inlined into the loop over the pairs: called, it cost 20 % of the narrow phase (a circle
// pour's pairs are mostly this test; measured with callgrind). `turn_a()` and `turn_b()` give a
// turned box's rotation, MakeRot of its angle.
template <typename TurnA, typename TurnB>
[[gnu::always_inline]] inline bool CollideBodies(const BodyInfo& ia, const BodyState& a, const BodyInfo& ib,
                                                 const BodyState& b, double margin, Manifold* m, TurnA&& turn_a,
                                                 TurnB&& turn_b) {
  const Vec2 pa = a.position, pb = b.position;
  const bool circle_a = ia.shape.type == ShapeType::kCircle;
  const bool circle_b = ib.shape.type == ShapeType::kCircle;
  auto box_a = [&] { return OrientedBox{pa, ia.shape.half_extents, turn_a()}; };
  auto box_b = [&] { return OrientedBox{pb, ib.shape.half_extents, turn_b()}; };
  if (circle_a && circle_b) return CollideCircles(pa, ia.shape.radius, pb, ib.shape.radius, m, margin);
  if (circle_a) {
    return b.angle == 0.0 ? CollideCircleBox(pa, ia.shape.radius, pb, ib.shape.half_extents, m, margin)
                          : CollideCircleOrientedBox(pa, ia.shape.radius, box_b(), m, margin);
  }
  if (circle_b) {
    // The collide functions take the circle first; flip its normal back to point from a to b.
    const bool touching =
        a.angle == 0.0 ? CollideCircleBox(pb, ib.shape.radius, pa, ia.shape.half_extents, m, margin)
                       : CollideCircleOrientedBox(pb, ib.shape.radius, box_a(), m, margin);
    m->normal = -m->normal;
    return touching;
  }
  if (a.angle == 0.0 && b.angle == 0.0) {
    return CollideBoxes(pa, ia.shape.half_extents, pb, ib.shape.half_extents, m, margin);
  }
  return CollideOrientedBoxes(box_a(), box_b(), m, margin);
}

// A lone circle's or box's contact, every member given, made where it is converted to: in a
// list's new element, by emplace_back.
struct NewContact {
  BodyPair pair;
  Manifold manifold;
  double restitution;
  double friction;
  operator Contact() const {  // NOLINT(google-explicit-constructor): for emplace_back
    return Contact{.a = pair.a,
                   .b = pair.b,
                   .piece_a = 0,
                   .piece_b = 0,
                   .strike_first_touch = false,
                   .manifold = manifold,
                   .restitution = restitution,
                   .friction = friction,
                   .normal_impulse = {0.0, 0.0},
                   .tangent_impulse = {0.0, 0.0}};
  }
};

// Last step's impulses on the points of `contact` that match by feature id, if the same pieces
// were in contact then with about the same normal. `cursor` walks forward through last step's
// list, which is in the same order. Without bodies made of parts every piece is 0, and only the
// pair is compared (the narrow phase of a circle pour is mostly this).
template <bool kParts>
[[gnu::always_inline]] inline void CarryImpulses(const std::vector<Contact>& previous, Contact* contact,
                                                 std::size_t* cursor) {
  auto before = [&](const Contact& old) {
    if constexpr (kParts) return ContactBefore(old, *contact);
    return BodyPair{old.a, old.b} < BodyPair{contact->a, contact->b};
  };
  while (*cursor < previous.size() && before(previous[*cursor])) ++*cursor;
  if (*cursor == previous.size()) return;
  const Contact& old = previous[*cursor];
  if (old.a != contact->a || old.b != contact->b) return;
  if constexpr (kParts) {
    if (old.piece_a != contact->piece_a || old.piece_b != contact->piece_b) return;
  }
  if (!(Dot(old.manifold.normal, contact->manifold.normal) > 0.99)) return;
  const Manifold& m = contact->manifold;
  for (int i = 0; i < m.point_count; ++i) {
    for (int j = 0; j < old.manifold.point_count; ++j) {
      if (old.manifold.points[j].id != m.points[i].id) continue;
      contact->normal_impulse[i] = old.normal_impulse[j];
      contact->tangent_impulse[i] = old.tangent_impulse[j];
    }
  }
}

}  // namespace

bool ShapesOverlap(const BodyInfo& ia, const BodyState& a, const BodyGeometry* ga, const BodyInfo& ib,
                   const BodyState& b, const BodyGeometry* gb) {
  if (ga || gb) return PiecesOverlap({0, ia, a, ga}, {0, ib, b, gb});
  Manifold m;
  if (!CollideBodies(ia, a, ib, b, 0.0, &m, [&] { return MakeRot(a.angle); }, [&] { return MakeRot(b.angle); })) {
    return false;
  }
  for (int i = 0; i < m.point_count; ++i) {
    if (m.points[i].depth >= 0.0) return true;
  }
  return false;
}

void NarrowPhase::Update(std::span<const BodyPair> pairs, std::span<const BodyState> states,
                         std::span<const BodyInfo> infos, Geometries geometries, std::span<const double> margins,
                         std::span<const Rot> box_turns, bool parts, WorkerPool& pool) {
  previous_contacts_.swap(contacts_);
  const auto collide = [&](std::span<const BodyPair> part, Lists* out) {
    // A part starts its walk through last step's contacts at its first pair: the walk from the
    // start would have reached no further, as every contact before it is of an earlier pair.
    const auto first = part.empty() ? previous_contacts_.end()
                                    : std::lower_bound(previous_contacts_.begin(), previous_contacts_.end(),
                                                       part.front(), [](const Contact& c, const BodyPair& p) {
                                                         return BodyPair{c.a, c.b} < p;
                                                       });
    const auto cursor = static_cast<std::size_t>(first - previous_contacts_.begin());
    if (parts) {
      // A body made of parts appends its pieces' contacts (CollidePieces): nothing to write over.
      out->contacts->resize(out->count);
      out->pairs->resize(out->count);
      Collide<true>(part, states, infos, geometries, margins, box_turns, cursor, out);
    } else {
      Collide<false>(part, states, infos, geometries, margins, box_turns, cursor, out);
    }
  };
  const int threads = pool.Threads();
  if (threads == 1 || pairs.size() < kMinSharedPairs) {
    Lists out{&contacts_, &contact_pairs_};
    collide(pairs, &out);
    contacts_.resize(out.count);
    contact_pairs_.resize(out.count);
    return;
  }
  // Each thread collides a contiguous part of the pairs, the first into the lists themselves and
  // the others into their own; those, joined after it in order, give the contacts one thread
  // would have found.
  thread_contacts_.resize(threads);
  thread_pairs_.resize(threads);
  std::vector<std::size_t> offsets(threads + 1, 0);
  pool.RunOnAll([&](int t) {
    const std::size_t begin = pairs.size() * t / threads, end = pairs.size() * (t + 1) / threads;
    Lists out{&contacts_, &contact_pairs_};
    if (t > 0) {
      out = {&thread_contacts_[t].value, &thread_pairs_[t].value};
      out.contacts->clear();
      out.pairs->clear();
    }
    collide(pairs.subspan(begin, end - begin), &out);
    offsets[t + 1] = out.count;
  });
  for (int t = 0; t < threads; ++t) offsets[t + 1] += offsets[t];
  // Only what the lists grow by is zeroed: the elements past the first thread's are copied in.
  const std::size_t total = offsets[threads];
  contacts_.resize(total);
  contact_pairs_.resize(total);
  // The copies shared evenly among the threads, each an equal run of the joined list.
  const std::size_t copied = total - offsets[1];
  pool.RunOnAll([&](int t) {
    const std::size_t from = offsets[1] + copied * t / threads, to = offsets[1] + copied * (t + 1) / threads;
    for (int part = 1; part < threads; ++part) {
      const std::size_t begin = std::max(from, offsets[part]), end = std::min(to, offsets[part + 1]);
      if (begin >= end) continue;
      const auto at = static_cast<std::ptrdiff_t>(begin - offsets[part]);
      const auto count = static_cast<std::ptrdiff_t>(end - begin);
      std::copy_n(thread_contacts_[part].value.begin() + at, count, contacts_.begin() + static_cast<std::ptrdiff_t>(begin));
      std::copy_n(thread_pairs_[part].value.begin() + at, count, contact_pairs_.begin() + static_cast<std::ptrdiff_t>(begin));
    }
  });
}

template <bool kParts>
void NarrowPhase::Collide(std::span<const BodyPair> pairs, std::span<const BodyState> states,
                          std::span<const BodyInfo> infos, Geometries geometries, std::span<const double> margins,
                          std::span<const Rot> box_turns, std::size_t previous, Lists* out) const {
  std::vector<Contact>& contacts = *out->contacts;
  std::vector<BodyPair>& contact_pairs = *out->pairs;
  // At most one contact a pair: reserving that much at once avoids growth by doubling, which
  // could hold twice what a large pile needs.
  contacts.reserve(out->count + pairs.size());
  contact_pairs.reserve(out->count + pairs.size());
  for (const BodyPair& pair : pairs) {
    const BodyInfo& ia = infos[pair.a];
    const BodyInfo& ib = infos[pair.b];
    const double margin = margins[pair.a] + margins[pair.b];
    if constexpr (kParts) {
      if (!IsSimpleShape(ia.shape.type) || !IsSimpleShape(ib.shape.type)) {
        assert(contacts.size() == out->count);  // nothing to write over (Update)
        CollidePieces({pair.a, ia, states[pair.a], geometries[pair.a].get()},
                      {pair.b, ib, states[pair.b], geometries[pair.b].get()}, margin, &contacts);
        for (; out->count < contacts.size(); ++out->count) {
          CarryImpulses<true>(previous_contacts_, &contacts[out->count], &previous);
          contact_pairs.push_back(pair);
        }
        continue;
      }
    }
    Manifold m;
    // A box's rotation as the broad phase made it for its bounds (the same numbers): made here,
    // it was made again for every pair the box is in (the turning pyramid of base 40 spent
    // 1.7 % of its step on those).
    if (!CollideBodies(ia, states[pair.a], ib, states[pair.b], margin, &m, [&] { return box_turns[pair.a]; },
                       [&] { return box_turns[pair.b]; })) {
      continue;
    }
    // Made in place (NewContact converts into the element): built aside and copied in, a
    // contact cost a clear of the whole block and loads of what had just been stored in other
    // widths; the pyramid of base 40 took 0.240 ms/step that way.
    const NewContact made{pair, m, std::max(ia.restitution, ib.restitution), std::sqrt(ia.friction * ib.friction)};
    // (The two lists may hold unlike numbers of elements to write over: the contacts are two
    // steps old, the pairs one.)
    Contact* const contact = out->count < contacts.size() ? std::construct_at(&contacts[out->count], made)
                                                          : &contacts.emplace_back(made);
    if (out->count < contact_pairs.size()) {
      contact_pairs[out->count] = pair;
    } else {
      contact_pairs.push_back(pair);
    }
    ++out->count;
    CarryImpulses<kParts>(previous_contacts_, contact, &previous);
  }
}

}  // namespace engine::detail
