// Effect particles: the emitters' slots, births spread evenly through the step from each
// emitter's own generator, motion under gravity less buoyancy with drag as exact decay, and
// one-way bounces off the rigid bodies. Save and Load are in effects_snapshot.cpp.
#include "particles/effects.h"

#include <algorithm>
#include <cmath>

#include "engine/portable_math.h"
#include "particles/split_mix.h"

namespace engine::detail {

namespace {

/// A birth owed to within this share of a particle is due now, so that the rounding of the
/// carried fraction never puts a birth off by a whole step.
constexpr double kBirthTolerance = 1e-9;
/// m: a disc this close to a body's surface touches it.
constexpr double kTouch = 1e-9;
/// Fewer particles than this move and bounce on one thread. A worker has gone to sleep between
/// two steps' effects, and waking it costs about 0.1 ms here: 10 000 colliding particles took
/// 0.19 ms a step on one thread and 0.30 on two.
constexpr std::size_t kMinParallel = 16384;

/// Particles per block handed to a thread.
constexpr std::size_t kBlock = 256;

/// Calls body(begin, end, thread) for blocks of [0, count) on `pool`'s threads (all on the
/// caller's if `count` is small), thread t taking blocks t, t + threads, …: dealt round, since
/// the particles come oldest first and the old ones, low down among the bodies, cost the most
/// (in halves, two threads were no faster than one). Each particle's result depends on nothing
/// but itself, so it is the same with any thread count.
template <typename Body>
void ForBlocks(WorkerPool& pool, std::size_t count, Body&& body) {
  const auto threads = static_cast<std::uint32_t>(count < kMinParallel ? 1 : pool.Threads());
  pool.ParallelFor(threads, 2, [&](std::uint32_t t) {
    for (std::size_t begin = t * kBlock; begin < count; begin += threads * kBlock) {
      body(begin, std::min(count, begin + kBlock), t);
    }
  });
}

// One particle through `time` s: gravity, then drag as exact decay (stable at any step), then
// the position with the new velocity (semi-implicit Euler).
void Advance(EffectParticle* p, Vec2 gravity, double decay, double time) {
  p->velocity = decay * (p->velocity + time * gravity);
  p->position += time * p->velocity;
}

// m: the particle's diameter, from the emitter's start size to its end size over its life.
double SizeOf(const EmitterDef& e, const EffectParticle& p) {
  const double t = std::min(p.age / p.lifetime, 1.0);
  return e.size_start + (e.size_end - e.size_start) * t;
}

// Reflects the particle's velocity off a surface moving with the body: the approach speed comes
// back times the restitution (none below the world's restitution threshold, so resting is
// quiet); the sliding speed loses at most friction × the normal change, as a Coulomb impulse.
void Bounce(EffectParticle* p, const BodyPlane& plane, double radius, const BodyState& body, const EmitterDef& e,
            double threshold) {
  const Vec2 n = plane.normal;
  const Vec2 contact = p->position - radius * n;
  const Vec2 surface_velocity = body.velocity + Cross(body.angular_velocity, contact - body.position);
  const Vec2 relative = p->velocity - surface_velocity;
  const double approach = -Dot(relative, n);
  if (approach <= 0.0) return;  // already leaving: being pushed out was enough
  const double restitution = approach > threshold ? e.restitution : 0.0;
  const Vec2 sliding = relative + approach * n;
  const double slide = Length(sliding);
  const double friction = std::sqrt(plane.friction * e.friction);  // mixed as body pairs mix theirs
  const double kept = slide > 0.0 ? 1.0 - std::min(slide, friction * (1.0 + restitution) * approach) / slide : 0.0;
  p->velocity = surface_velocity + (restitution * approach) * n + kept * sliding;
}

}  // namespace

EmitterId EffectSystem::Create(const EmitterDef& def) {
  std::uint32_t slot;
  if (!free_.empty()) {
    slot = free_.back();
    free_.pop_back();
  } else {
    slot = static_cast<std::uint32_t>(defs_.size());
    defs_.emplace_back();
    generations_.push_back(0);
    alive_.push_back(0);
    random_states_.push_back(0);
    owed_births_.push_back(0.0);
    alive_counts_.push_back(0);
  }
  defs_[slot] = def;
  alive_[slot] = 1;
  random_states_[slot] = def.seed;
  owed_births_[slot] = 0.0;
  RebuildLiveIds();
  ever_used_ = true;
  return {slot, generations_[slot]};
}

void EffectSystem::Destroy(std::uint32_t slot) {
  alive_[slot] = 0;
  ++generations_[slot];
  if (alive_counts_[slot] == 0) {
    free_.push_back(slot);
  } else {
    draining_.push_back(slot);
  }
  RebuildLiveIds();
}

void EffectSystem::RebuildLiveIds() {
  live_ids_.clear();
  for (std::uint32_t s = 0; s < defs_.size(); ++s) {
    if (alive_[s]) live_ids_.push_back({s, generations_[s]});
  }
}

void EffectSystem::BodyGone(BodyIndex body) {
  for (std::uint32_t s = 0; s < defs_.size(); ++s) {
    if (alive_[s] && defs_[s].body && defs_[s].body->index == body) defs_[s].rate = 0.0;
  }
}

void EffectSystem::Step(const WorldDef& def, const Bodies& bodies, WorkerPool& pool) {
  AgeAndBury(def.dt);         // the dead go; the survivors keep their order, oldest first
  ReleaseDrained();           // a destroyed emitter's slot is free once its last particle has died
  Move(def, pool);            // those alive when the step began move a whole step
  Emit(def, bodies);          // the newborns, each moved from its moment of birth to the step's end
  Collide(def, bodies, pool); // bounces off the bodies, which never feel them
}

void EffectSystem::AgeAndBury(double dt) {
  std::size_t kept = 0;
  for (EffectParticle p : particles_) {
    p.age += dt;
    if (p.age >= p.lifetime) {
      --alive_counts_[p.emitter.index];
      continue;
    }
    particles_[kept++] = p;
  }
  particles_.resize(kept);
}

void EffectSystem::ReleaseDrained() {
  std::size_t kept = 0;
  for (const std::uint32_t slot : draining_) {
    if (alive_counts_[slot] == 0) {
      free_.push_back(slot);
    } else {
      draining_[kept++] = slot;
    }
  }
  draining_.resize(kept);
}

void EffectSystem::Move(const WorldDef& def, WorkerPool& pool) {
  motions_.resize(defs_.size());
  for (std::uint32_t s = 0; s < defs_.size(); ++s) {
    const EmitterDef& e = defs_[s];
    motions_[s] = {(1.0 - e.buoyancy) * def.gravity, Exp(-e.drag * def.dt), 0.5 * std::max(e.size_start, e.size_end)};
  }
  starts_.resize(particles_.size());
  thread_farthest_.assign(pool.Threads(), {});
  ForBlocks(pool, particles_.size(), [&](std::size_t begin, std::size_t end, std::uint32_t thread) {
    double farthest = 0.0;  // a local: the member, written through each turn, halved the loop's speed
    for (std::size_t i = begin; i < end; ++i) {
      EffectParticle& p = particles_[i];
      starts_[i] = p.position;
      const Motion& m = motions_[p.emitter.index];
      Advance(&p, m.gravity, m.decay, def.dt);
      farthest = std::max(farthest, LengthSquared(p.position - starts_[i]));
    }
    thread_farthest_[thread].value = std::max(thread_farthest_[thread].value, farthest);
  });
  farthest_ = 0.0;
  for (const Farthest& f : thread_farthest_) farthest_ = std::max(farthest_, f.value);
}

void EffectSystem::Emit(const WorldDef& def, const Bodies& bodies) {
  births_.clear();
  for (const EmitterId id : live_ids_) EmitFrom(id.index, def, bodies);
  // Oldest first across the emitters too; the stable sort keeps slot order between equal moments.
  if (live_ids_.size() > 1) {
    std::stable_sort(births_.begin(), births_.end(),
                     [](const Birth& a, const Birth& b) { return a.fraction < b.fraction; });
  }
  for (const Birth& b : births_) {
    particles_.push_back(b.particle);
    starts_.push_back(b.start);
  }
}

void EffectSystem::EmitFrom(std::uint32_t slot, const WorldDef& def, const Bodies& bodies) {
  const EmitterDef& e = defs_[slot];
  const double per_step = e.rate * def.dt;
  if (!(per_step > 0.0)) return;                      // stopped: not even a waiting birth comes
  if (e.body && !bodies.IsLive(*e.body)) return;      // its body has gone
  const double owed_before = owed_births_[slot];
  const double owed = owed_before + per_step;
  const double due = std::floor(owed + kBirthTolerance);
  const std::uint32_t alive = alive_counts_[slot];
  const double count = std::min(due, alive < e.max_particles ? static_cast<double>(e.max_particles - alive) : 0.0);
  // Where the emitter stands at the step's end, how fast that point moves and which way it faces.
  Vec2 at = e.position, point_velocity;
  double facing = 0.0;
  if (e.body) {
    const BodyIndex b = e.body->index;
    const BodyState& s = bodies.states[b];
    const Vec2 arm = Rotate(MakeRot(s.angle), bodies.FromCenter(b, e.position));
    at = s.position + arm;
    point_velocity = s.velocity + Cross(s.angular_velocity, arm);
    facing = s.angle;
  }
  const Motion& m = motions_[slot];
  std::uint64_t* random = &random_states_[slot];
  for (std::uint64_t j = 1; static_cast<double>(j) <= count; ++j) {
    // The j-th birth comes when the owed count, growing evenly through the step, reaches j; the
    // emitter's point was then where its velocity carries it back from the step's end.
    const double fraction = std::clamp((static_cast<double>(j) - owed_before) / per_step, 0.0, 1.0);
    const double left = (1.0 - fraction) * def.dt;
    const Rot heading = MakeRot(facing + UniformAround(e.direction, e.spread, random));
    const double speed = UniformAround(e.speed, e.speed_spread, random);
    Birth birth{fraction, {}, at - left * point_velocity};
    EffectParticle& p = birth.particle;
    p.position = birth.start;
    p.velocity = point_velocity + speed * Vec2{heading.c, heading.s};
    p.lifetime = UniformAround(e.lifetime, e.lifetime_spread, random);
    p.emitter = {slot, generations_[slot]};
    p.age = left;
    Advance(&p, m.gravity, Exp(-e.drag * left), left);
    if (p.age >= p.lifetime) continue;  // born and dead within the step
    farthest_ = std::max(farthest_, LengthSquared(p.position - birth.start));
    ++alive_counts_[slot];
    births_.push_back(birth);
  }
  owed_births_[slot] = owed - count;
  // Births the cap held back wait for room, but at most one: it comes at the next step's start.
  if (count < due) owed_births_[slot] = std::min(owed_births_[slot], 1.0);
}

void EffectSystem::Collide(const WorldDef& def, const Bodies& bodies, WorkerPool& pool) {
  double largest_radius = -1.0;
  for (std::uint32_t s = 0; s < defs_.size(); ++s) {
    const bool has_particles = alive_[s] || alive_counts_[s] > 0;
    if (defs_[s].collide && has_particles) largest_radius = std::max(largest_radius, motions_[s].radius);
  }
  if (largest_radius < 0.0 || particles_.empty() || bodies.live_ids.empty()) return;
  // Any particle's swept disc lies within the largest radius and the farthest move of its start.
  bins_.Build(bodies, largest_radius + std::sqrt(farthest_) + kTouch);
  if (bins_.Empty()) return;
  scratch_.resize(pool.Threads());
  ForBlocks(pool, particles_.size(), [&](std::size_t begin, std::size_t end, std::uint32_t thread) {
    for (std::size_t i = begin; i < end; ++i) {
      EffectParticle& p = particles_[i];
      const EmitterDef& e = defs_[p.emitter.index];
      if (!e.collide) continue;
      const Vec2 start = starts_[i];
      // Where the disc went this step, with the emitter's largest disc: a box, so no square root.
      const Vec2 grow{motions_[p.emitter.index].radius, motions_[p.emitter.index].radius};
      const AABB swept{Vec2{std::min(start.x, p.position.x), std::min(start.y, p.position.y)} - grow,
                       Vec2{std::max(start.x, p.position.x), std::max(start.y, p.position.y)} + grow};
      double radius = -1.0;  // worked out only for a particle near some body
      bins_.ForEachOverlapping(start, swept, [&](BodyIndex b) {
        if (radius < 0.0) radius = 0.5 * SizeOf(e, p);
        CollideWith(&p, start, radius, b, e, def, bodies, scratch_[thread]);
      });
    }
  });
}

// Planes are found where the particle began, so a fast one cannot pass through a thin body
// unseen (speculative contact, as Catto's "Speculative contacts", GDC 2013, and the soft bodies
// here do it); those it only passes beside the corner of are checked where it crosses them.
bool EffectSystem::CollideWith(EffectParticle* p, Vec2 start, double radius, BodyIndex body, const EmitterDef& e,
                               const WorldDef& def, const Bodies& bodies, PlaneScratch& scratch) {
  std::vector<BodyPlane>& planes = scratch.planes;
  std::vector<BodyPlane>& touching = scratch.touching;
  planes.clear();
  const double travel = Length(p->position - start);
  if (AppendBodyPlanes(bodies, body, start, radius, travel + kTouch, &planes) == 0) return false;
  const BodyState& state = bodies.states[body];
  bool hit = false, passed_beside = false;
  for (const BodyPlane& plane : planes) {
    const double before = Dot(plane.normal, start - plane.surface) - radius;
    const double after = Dot(plane.normal, p->position - plane.surface) - radius;
    if (after >= 0.0) continue;
    if (before > kTouch) {
      const Vec2 meet = start + (before / (before - after)) * (p->position - start);
      touching.clear();
      if (AppendBodyPlanes(bodies, body, meet, radius, 16.0 * kTouch, &touching) == 0) {
        passed_beside = true;  // the face's plane, not the face: a ghost
        continue;
      }
    }
    p->position += (-after) * plane.normal;
    Bounce(p, plane, radius, state, e, def.restitution_threshold);
    hit = true;
  }
  if (hit || !passed_beside) return hit;
  // Past a corner or round a curve: whatever the particle overlaps where it ended pushes it out.
  touching.clear();
  AppendBodyPlanes(bodies, body, p->position, radius, 0.0, &touching);
  for (const BodyPlane& plane : touching) {
    const double after = Dot(plane.normal, p->position - plane.surface) - radius;
    if (after >= 0.0) continue;
    p->position += (-after) * plane.normal;
    Bounce(p, plane, radius, state, e, def.restitution_threshold);
    hit = true;
  }
  return hit;
}

}  // namespace engine::detail
