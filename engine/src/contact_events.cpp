// Contact events: touching pairs after each step, merged against the last step's.
#include "contact_events.h"

#include <algorithm>
#include <chrono>
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

// Past every pair: where the last run stops.
constexpr BodyPair kEndOfPairs{kNoBody, kNoBody};

BodyPair PairOf(const Contact& c) { return {c.a, c.b}; }

ContactBeginEvent BeginOf(const Contact& c, double approach, const Bodies& bodies) {
  Vec2 point;
  for (int i = 0; i < c.manifold.point_count; ++i) point += c.manifold.points[i].point;
  point = point / static_cast<double>(c.manifold.point_count);
  return {bodies.IdOf(c.a), bodies.IdOf(c.b), point, c.manifold.normal, approach};
}

}  // namespace

void ContactEvents::RecordStartVelocities(std::span<const BodyState> states, WorkerPool& pool) {
  start_velocities_.resize(states.size());
  start_angular_velocities_.resize(states.size());
  // Each thread its share of the bodies, whose states its core wrote last (on thread 0 alone,
  // half came from the other core: 27 kcyc a step of the 4 000-circle pour on two threads).
  ForEachIndex(&pool, states.size(), kMinSharedBodies, [&](std::uint32_t i) {
    start_velocities_[i] = states[i].velocity;
    start_angular_velocities_[i] = states[i].angular_velocity;
  });
}

void ContactEvents::Update(std::span<const Contact> contacts, const Bodies& bodies,
                           std::span<const std::uint8_t> awake, const WorldDef& def, WorkerPool& pool,
                           StepEvents* events) {
  previous_.swap(touching_);
  events->contact_end.insert(events->contact_end.end(), removed_.begin(), removed_.end());
  removed_.clear();
  const int threads = pool.Threads();
  if (threads == 1 || contacts.size() < kMinSharedContacts) {
    touching_.clear();
    Merge(contacts, 0, contacts.size(), previous_, kEndOfPairs, bodies, awake, def, &touching_, events);
    return;
  }
  // Shared: each thread takes its own run of the contacts, the part the solver's store wrote on
  // it (StoreImpulses, ForEachIndex), so that it reads contacts its core wrote last. (Runs dealt to
  // whichever thread was free, three a thread, read half of them from the other core: the events
  // of the settled 4 000-circle pour took 158-170 kcyc a step on two threads, against 134-136.)
  // A run's contacts are tested and merged against the last step's pairs below the next run's
  // first, into lists of the run's own; the runs' lists then go one after another. A run never
  // splits a pair's contacts (bodies made of parts have several), so every pair is seen whole,
  // and the lists come out as one thread's, wherever the runs are cut. They are cut where they
  // took alike last step (BalancedCuts): the second run of a pour is the one still settling, and
  // took 1.3 times the first's time on as many contacts (bench_threads' window: 116 kcyc a step
  // against 87, the first thread waiting out the difference).
  const auto runs = static_cast<std::uint32_t>(threads);
  const auto cut = [&](std::uint32_t r) {
    std::size_t i = cuts_.Cut(r, runs, contacts.size());
    while (i > 0 && i < contacts.size() && PairOf(contacts[i]) == PairOf(contacts[i - 1])) ++i;
    return i;
  };
  const auto first_pair = [&](std::size_t i) { return i < contacts.size() ? PairOf(contacts[i]) : kEndOfPairs; };
  const auto previous_below = [&](BodyPair pair) {
    return static_cast<std::size_t>(std::lower_bound(previous_.begin(), previous_.end(), pair) - previous_.begin());
  };
  runs_.resize(runs);
  const auto merge_run = [&](std::uint32_t r) {
    const std::size_t begin = cut(r), end = cut(r + 1);
    const BodyPair stop = first_pair(end);
    const std::size_t old_begin = r == 0 ? 0 : previous_below(first_pair(begin));
    const std::size_t old_end = previous_below(stop);
    MergeRun& run = runs_[r].value;
    const auto start = std::chrono::steady_clock::now();
    run.touching.clear();
    run.events.Clear();
    Merge(contacts, begin, end, std::span<const BodyPair>(previous_).subspan(old_begin, old_end - old_begin), stop,
          bodies, awake, def, &run.touching, &run.events);
    run.begin = begin;
    run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  pool.RunOnAll([&](int thread) { merge_run(static_cast<std::uint32_t>(thread)); });
  run_cuts_.resize(runs + 1);
  run_seconds_.resize(runs);
  for (std::uint32_t r = 0; r < runs; ++r) {
    run_cuts_[r] = runs_[r].value.begin;
    run_seconds_[r] = runs_[r].value.seconds;
  }
  run_cuts_[runs] = contacts.size();
  cuts_.Learn(run_cuts_, run_seconds_);
  // Each thread copies its run's pairs into place: joined on the first thread, the second run's
  // pairs crossed the cores on it, alone, and the next step's second run read them back across
  // (the settled 4 000-circle pour on two threads: Update 124-129 -> 111-115 kcyc a step). The
  // list keeps its last length, so only its growth is zeroed first.
  run_offsets_.assign(runs + 1, 0);
  for (std::uint32_t r = 0; r < runs; ++r) run_offsets_[r + 1] = run_offsets_[r] + runs_[r].value.touching.size();
  touching_.resize(run_offsets_[runs]);
  pool.RunOnAll([&](int thread) {
    const auto r = static_cast<std::size_t>(thread);
    std::ranges::copy(runs_[r].value.touching, touching_.begin() + static_cast<std::ptrdiff_t>(run_offsets_[r]));
  });
  for (const PerThread<MergeRun>& part : runs_) {
    const MergeRun& run = part.value;
    events->contact_end.insert(events->contact_end.end(), run.events.contact_end.begin(), run.events.contact_end.end());
    events->contact_begin.insert(events->contact_begin.end(), run.events.contact_begin.begin(),
                                 run.events.contact_begin.end());
    events->hits.insert(events->hits.end(), run.events.hits.begin(), run.events.hits.end());
  }
}

double ContactEvents::StartApproach(const Contact& c, const Bodies& bodies) const {
  auto start = [&](BodyIndex i) {
    return BodyState{bodies.start_positions[i], start_velocities_[i], 0.0, start_angular_velocities_[i]};
  };
  return ApproachSpeed(c, start(c.a), start(c.b));
}

void ContactEvents::Merge(std::span<const Contact> contacts, std::size_t begin, std::size_t end,
                          std::span<const BodyPair> previous, BodyPair stop, const Bodies& bodies,
                          std::span<const std::uint8_t> awake, const WorldDef& def,
                          std::vector<BodyPair>* touching, StepEvents* events) const {
  std::size_t j = 0;  // walks the last step's touching pairs, in the same order
  // A pair gone from the contacts ended, unless neither body moved: sleeping bodies keep
  // touching without a contact.
  auto end_before = [&](BodyPair pair) {
    for (; j < previous.size() && previous[j] < pair; ++j) {
      const BodyPair old = previous[j];
      if (!awake[old.a] && !awake[old.b]) {
        touching->push_back(old);
      } else {
        events->contact_end.push_back({bodies.IdOf(old.a), bodies.IdOf(old.b)});
      }
    }
  };
  const bool parts = bodies.with_parts > 0;
  for (std::size_t i = begin; i < end; ++i) {
    const Contact& c = contacts[i];
    if (!Touching(c, [&] { return StartApproach(c, bodies); }, bodies.states, def)) continue;
    const BodyPair pair = PairOf(c);
    // Bodies made of parts can touch at several pieces: one pair, one begin.
    if (parts && !touching->empty() && touching->back() == pair) continue;
    end_before(pair);
    touching->push_back(pair);
    if (j < previous.size() && previous[j] == pair) {
      ++j;
      continue;
    }
    const ContactBeginEvent begin_event = BeginOf(c, StartApproach(c, bodies), bodies);
    events->contact_begin.push_back(begin_event);
    if (begin_event.approach_speed >= def.hit_speed) events->hits.push_back(begin_event);
  }
  end_before(stop);
}

void ContactEvents::RemoveBody(BodyIndex index, const Bodies& bodies) {
  std::erase_if(touching_, [&](BodyPair p) {
    if (p.a != index && p.b != index) return false;
    removed_.push_back({bodies.IdOf(p.a), bodies.IdOf(p.b)});
    return true;
  });
}

}  // namespace engine::detail
