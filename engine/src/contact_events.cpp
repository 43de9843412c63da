// Contact events: touching pairs after each step, merged against the last step's.
#include "contact_events.h"

#include <algorithm>
#include <limits>

namespace engine::detail {

namespace {

// Fewer contacts than this are looked at on one thread.
constexpr std::uint32_t kMinSharedContacts = 4096;

// How fast the bodies close along the normal at the contact's points (the fastest), m/s.
double ApproachSpeed(const Contact& c, const BodyState& a, const BodyState& b) {
  double fastest = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < c.manifold.point_count; ++i) {
    const Vec2 p = c.manifold.points[i].point;
    const Vec2 va = a.velocity + Cross(a.angular_velocity, p - a.position);
    const Vec2 vb = b.velocity + Cross(b.angular_velocity, p - b.position);
    fastest = std::max(fastest, -Dot(vb - va, c.manifold.normal));
  }
  return fastest;
}

// Whether the pair touched in this step: the contact solver pushed on it, or the bodies are
// within the slop, or they bounced. A bounce (the substep solver's impact pass) leaves no
// impulse on the contact and the bodies apart: they closed at `approach` when the step began,
// near enough to meet within it, and now they part. `approach` is asked only then.
template <typename Approach>
bool Touching(const Contact& c, Approach approach, std::span<const BodyState> states, const WorldDef& def) {
  double gap = std::numeric_limits<double>::infinity();
  for (int i = 0; i < c.manifold.point_count; ++i) {
    if (c.normal_impulse[i] > 0.0 || c.manifold.points[i].depth >= -def.linear_slop) return true;
    gap = std::min(gap, -c.manifold.points[i].depth);
  }
  const double closing = approach();
  if (!(closing > 0.0)) return false;
  const double reach = closing * def.dt + 0.5 * Length(def.gravity) * def.dt * def.dt + def.linear_slop;
  return gap <= reach && ApproachSpeed(c, states[c.a], states[c.b]) < 0.0;
}

ContactBeginEvent BeginOf(const Contact& c, double approach, const Bodies& bodies) {
  Vec2 point;
  for (int i = 0; i < c.manifold.point_count; ++i) point += c.manifold.points[i].point;
  point = point / static_cast<double>(c.manifold.point_count);
  return {bodies.IdOf(c.a), bodies.IdOf(c.b), point, c.manifold.normal, approach};
}

}  // namespace

void ContactEvents::RecordStartVelocities(std::span<const BodyState> states) {
  start_velocities_.resize(states.size());
  start_angular_velocities_.resize(states.size());
  for (std::size_t i = 0; i < states.size(); ++i) {
    start_velocities_[i] = states[i].velocity;
    start_angular_velocities_[i] = states[i].angular_velocity;
  }
}

void ContactEvents::Update(std::span<const Contact> contacts, const Bodies& bodies,
                           std::span<const std::uint8_t> awake, const WorldDef& def, WorkerPool& pool,
                           StepEvents* events) {
  previous_.swap(touching_);
  touching_.clear();
  events->contact_end.insert(events->contact_end.end(), removed_.begin(), removed_.end());
  removed_.clear();
  std::size_t j = 0;  // walks the last step's touching pairs, in the same order
  // A pair gone from the contacts ended, unless neither body moved: sleeping bodies keep
  // touching without a contact.
  auto end_before = [&](BodyPair pair) {
    for (; j < previous_.size() && previous_[j] < pair; ++j) {
      const BodyPair old = previous_[j];
      if (!awake[old.a] && !awake[old.b]) {
        touching_.push_back(old);
      } else {
        events->contact_end.push_back({bodies.IdOf(old.a), bodies.IdOf(old.b)});
      }
    }
  };
  // How fast the contact closed when the step began.
  auto approach = [&](const Contact& c) {
    auto start = [&](BodyIndex i) {
      return BodyState{bodies.start_positions[i], start_velocities_[i], 0.0, start_angular_velocities_[i]};
    };
    return ApproachSpeed(c, start(c.a), start(c.b));
  };
  const bool parts = bodies.with_parts > 0;
  touches_.resize(contacts.size());
  pool.ParallelFor(static_cast<std::uint32_t>(contacts.size()), kMinSharedContacts, [&](std::uint32_t i) {
    touches_[i] = Touching(contacts[i], [&] { return approach(contacts[i]); }, bodies.states, def);
  });
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    if (!touches_[i]) continue;
    const Contact& c = contacts[i];
    const BodyPair pair{c.a, c.b};
    // Bodies made of parts can touch at several pieces: one pair, one begin.
    if (parts && !touching_.empty() && touching_.back() == pair) continue;
    end_before(pair);
    touching_.push_back(pair);
    if (j < previous_.size() && previous_[j] == pair) {
      ++j;
      continue;
    }
    const ContactBeginEvent begin = BeginOf(c, approach(c), bodies);
    events->contact_begin.push_back(begin);
    if (begin.approach_speed >= def.hit_speed) events->hits.push_back(begin);
  }
  end_before({kNoBody, kNoBody});
}

void ContactEvents::RemoveBody(BodyIndex index, const Bodies& bodies) {
  std::erase_if(touching_, [&](BodyPair p) {
    if (p.a != index && p.b != index) return false;
    removed_.push_back({bodies.IdOf(p.a), bodies.IdOf(p.b)});
    return true;
  });
}

}  // namespace engine::detail
