// The order the substep solver visits contacts in, and its groups of contacts that share no
// moving body (what threads may solve side by side). Internal to the engine.
#pragma once

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <span>
#include <vector>

#include "body_pair.h"
#include "engine/body.h"
#include "engine/contact.h"

namespace engine::detail {
class WorkerPool;
}

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
/// `contacts` are the contacts' bodies (NarrowPhase::ContactPairs); `body_marks` is scratch, one
/// entry per body.
void ColourContacts(std::span<const BodyPair> contacts, std::span<const BodyInfo> infos,
                    std::vector<std::uint64_t>* body_marks, std::vector<std::uint32_t>* slot,
                    std::vector<std::uint32_t>* group_ends);

/// The groups of the strip order, in the order they are solved: the strips; the contacts across
/// the even edges between strips (edge e joins strips e and e + 1), then the odd ones (within
/// either set no two edges share a strip); then the rest, joining strips further apart.
struct StripGroups {
  explicit StripGroups(int strip_count)
      : strips(static_cast<std::uint32_t>(strip_count)),
        even_edges(strips / 2),
        odd_edges((strips - 1) / 2),
        far(strips + even_edges + odd_edges) {}
  /// The group of the contacts across edge e.
  std::uint32_t Edge(std::uint32_t e) const { return strips + (e % 2 == 0 ? e / 2 : even_edges + e / 2); }

  std::uint32_t strips, even_edges, odd_edges;
  std::uint32_t far;  ///< the last group
};

/// Contact order within strips: the moving bodies' span along `across` is cut into `strips`
/// strips holding about as many contacts each, by where each body's centre is (`states`); a
/// contact whose moving bodies lie in one strip goes to that strip's group, one across an edge
/// to the edge's, the rest to the last (StripGroups), each in contact order; `group_ends` gets
/// each group's end.
///
/// Why: a turning stack converges in contact order where it was built bottom-up, and a colour
/// order loses that (ContactOrder::AsFound); but contact order is one chain of dependent
/// contacts. Strips of it share no moving body, so threads can each take whole strips, and the
/// order inside each stays contact order. Domain decomposition for Gauss-Seidel; with strips
/// upright (across gravity), a pile's columns stay whole.
/// `pool`: threads to share the contacts and bodies among (the same order whatever the threads).
void StripContacts(std::span<const Contact> contacts, std::span<const BodyInfo> infos,
                   std::span<const BodyState> states, Vec2 across, int strips,
                   std::vector<std::uint64_t>* body_marks, std::vector<std::uint32_t>* slot,
                   std::vector<std::uint32_t>* group_ends, WorkerPool* pool = nullptr);

/// The order the substep solver visits contacts in: contact i's constraint sits at `slot[i]`.
/// Either the groups [group_ends[g − 1], group_ends[g]) below `parallel_groups` share no moving
/// body (any constraint of one may go to any thread), or the first `strips` groups are strips
/// (each goes whole to one thread; no two share a moving body), and so are the edges after them
/// (StripGroups).
struct ContactOrder {
  std::vector<std::uint32_t> slot;
  std::vector<std::uint32_t> group_ends;
  /// Groups from this one on may share a moving body (the colouring ran out of colours): they
  /// are solved on one thread.
  std::uint32_t parallel_groups = 0;
  /// The strip order's strips (0 in colour or contact order).
  std::uint32_t strips = 0;
  std::vector<std::uint64_t> body_marks;  ///< scratch

  /// By colour, from the contacts' bodies (NarrowPhase::ContactPairs): the fastest order on one
  /// thread, where the solve does not depend on order.
  void ByColour(std::span<const BodyPair> contacts, std::span<const BodyInfo> infos) {
    ColourContacts(contacts, infos, &body_marks, &slot, &group_ends);
    parallel_groups = std::min<std::uint32_t>(static_cast<std::uint32_t>(group_ends.size()), kSharedColour);
    strips = 0;
  }
  /// Contact order within strips (StripContacts), upright when gravity gives an up.
  void InStrips(std::span<const Contact> contacts, std::span<const BodyInfo> infos,
                std::span<const BodyState> states, Vec2 gravity, WorkerPool* pool = nullptr) {
    const Vec2 across = gravity == Vec2{} ? Vec2{1.0, 0.0} : LeftPerp(gravity);
    StripContacts(contacts, infos, states, across, kStrips, &body_marks, &slot, &group_ends, pool);
    parallel_groups = 0;
    strips = kStrips;
  }
  /// Contact order, one group on one thread: where a scene is built bottom-up, turning stacks
  /// converge better in it. (Regrouping it into levels of contacts that share no body keeps
  /// its bits, but a 4000-circle pour has 393 levels of about 24: too small to share out.)
  void AsFound(std::size_t contact_count) {
    slot.resize(contact_count);
    std::iota(slot.begin(), slot.end(), 0u);
    group_ends.assign(1, static_cast<std::uint32_t>(contact_count));
    parallel_groups = 0;
    strips = 0;
  }
  /// How many strips InStrips cuts: fixed, so the order (and the bits) never depend on the
  /// threads; enough for 8 threads, few enough that most contacts lie inside one.
  static constexpr int kStrips = 8;
};

}  // namespace engine::detail
