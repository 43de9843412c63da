// The joints' rows, after Box2D's revolute, prismatic, distance, weld and mouse joints (Catto,
// "Modeling and Solving Constraints", GDC 2009), solved rigidly at the velocity level; position
// errors go out through push velocities, as the contacts' overlap does (substep_passes.cpp).
#include "joints/joint_solver.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "solver/constraint_groups.h"

namespace engine::detail {

namespace {

// K⁻¹·v, or zero when K is singular (both bodies of infinite mass: nothing to solve).
Vec2 Solve22(const Mat22& k, Vec2 v) {
  const double det = k.k11 * k.k22 - k.k12 * k.k12;
  if (!(det > 0.0)) return {};
  const double inv = 1.0 / det;
  return {inv * (k.k22 * v.x - k.k12 * v.y), inv * (k.k11 * v.y - k.k12 * v.x)};
}

// Velocity of B's anchor relative to A's.
Vec2 PointVelocity(const JointWork& w, const BodyState& a, const BodyState& b) {
  return (b.velocity + Cross(b.angular_velocity, w.rb)) - (a.velocity + Cross(a.angular_velocity, w.ra));
}

void ApplyPoint(const JointWork& w, Vec2 impulse, BodyState& a, BodyState& b) {
  a.velocity -= w.ma * impulse;
  a.angular_velocity -= w.ia * Cross(w.ra, impulse);
  b.velocity += w.mb * impulse;
  b.angular_velocity += w.ib * Cross(w.rb, impulse);
}

void ApplyAngle(const JointWork& w, double impulse, BodyState& a, BodyState& b) {
  a.angular_velocity -= w.ia * impulse;
  b.angular_velocity += w.ib * impulse;
}

// A row along direction d through the anchors (distance, prismatic axis): its arms.
struct AxisRow {
  Vec2 d;
  double arm_a, arm_b;  ///< (rA [+ separation for prismatic]) × d, rB × d
  double mass;          ///< 1 / effective mass; 0 when nothing can move along it
};

AxisRow MakeAxisRow(const JointWork& w, Vec2 d, Vec2 arm_a) {
  AxisRow row{d, Cross(arm_a, d), Cross(w.rb, d), 0.0};
  const double k = w.ma + w.mb + w.ia * row.arm_a * row.arm_a + w.ib * row.arm_b * row.arm_b;
  row.mass = k > 0.0 ? 1.0 / k : 0.0;
  return row;
}

double RowVelocity(const AxisRow& row, const BodyState& a, const BodyState& b) {
  return Dot(row.d, b.velocity - a.velocity) + row.arm_b * b.angular_velocity - row.arm_a * a.angular_velocity;
}

void ApplyRow(const JointWork& w, const AxisRow& row, double impulse, BodyState& a, BodyState& b) {
  a.velocity -= (w.ma * impulse) * row.d;
  a.angular_velocity -= w.ia * impulse * row.arm_a;
  b.velocity += (w.mb * impulse) * row.d;
  b.angular_velocity += w.ib * impulse * row.arm_b;
}

// The distance joint's row: along the anchors' line (none while the anchors coincide).
bool DistanceRow(const JointWork& w, AxisRow* row) {
  const double length = Length(w.separation);
  if (!(length > 1e-12)) return false;
  *row = MakeAxisRow(w, w.separation / length, w.ra);
  return true;
}

// The prismatic joint's rows: along the axis (limits, motor) and across it with the angle.
AxisRow PrismaticAxisRow(const JointWork& w) { return MakeAxisRow(w, w.axis, w.separation + w.ra); }

struct PrismaticBlock {
  Vec2 perp;
  double s1, s2;
  Mat22 k;
};

PrismaticBlock MakePrismaticBlock(const JointWork& w) {
  const Vec2 perp = LeftPerp(w.axis);
  const double s1 = Cross(w.separation + w.ra, perp), s2 = Cross(w.rb, perp);
  const double k22 = w.ia + w.ib;
  return {perp, s1, s2,
          {w.ma + w.mb + w.ia * s1 * s1 + w.ib * s2 * s2, w.ia * s1 + w.ib * s2, k22 > 0.0 ? k22 : 1.0}};
}

Vec2 BlockVelocity(const PrismaticBlock& p, const BodyState& a, const BodyState& b) {
  return {Dot(p.perp, b.velocity - a.velocity) + p.s2 * b.angular_velocity - p.s1 * a.angular_velocity,
          b.angular_velocity - a.angular_velocity};
}

void ApplyBlock(const JointWork& w, const PrismaticBlock& p, Vec2 impulse, BodyState& a, BodyState& b) {
  a.velocity -= (w.ma * impulse.x) * p.perp;
  a.angular_velocity -= w.ia * (impulse.x * p.s1 + impulse.y);
  b.velocity += (w.mb * impulse.x) * p.perp;
  b.angular_velocity += w.ib * (impulse.x * p.s2 + impulse.y);
}

// The spring's impulse over one (sub)step of length h for a row of error C and rate Cdot, as a
// factor on the effective mass: λ = −factor(C, Cdot)·m. Soft enough (ω·h ≤ the limit), the force
// is taken at the position the step starts from (symplectic Euler: no energy drift) with the
// damping implicit; stiffer, both implicit (backward Euler: stable at any stiffness).
struct SpringRate {
  double on_error, on_rate;  ///< λ = −m·(on_error·C + on_rate·Cdot)
};

SpringRate MakeSpringRate(const JointSpring& spring, double h) {
  const double omega = 2.0 * std::numbers::pi * spring.hertz;
  const double damping = 2.0 * spring.damping_ratio * omega;
  if (omega * h <= kExplicitSpringLimit) {
    const double scale = h / (1.0 + damping * h);
    return {scale * omega * omega, scale * damping};
  }
  const double scale = h / (1.0 + h * h * omega * omega + damping * h);
  return {scale * omega * omega, scale * (h * omega * omega + damping)};
}

// The most a limit row may let the error close this substep: what is left of the gap (a
// speculative limit, like a speculative contact), nothing once it is reached.
double LimitTarget(double gap, double inv_h) { return -std::max(gap, 0.0) * inv_h; }

// Accumulated-impulse update of a one-sided row (impulse ≥ 0).
double ClampedStep(double* accumulated, double step) {
  const double updated = std::max(*accumulated + step, 0.0);
  const double applied = updated - *accumulated;
  *accumulated = updated;
  return applied;
}

bool HasSpring(const Joint& j) { return j.def.spring.has_value(); }

}  // namespace

Mat22 PointMass(const JointWork& w) {
  const double m = w.ma + w.mb;
  return {m + w.ia * w.ra.y * w.ra.y + w.ib * w.rb.y * w.rb.y,
          -w.ia * w.ra.x * w.ra.y - w.ib * w.rb.x * w.rb.y,
          m + w.ia * w.ra.x * w.ra.x + w.ib * w.rb.x * w.rb.x};
}

bool JointSolver::Prepare(JointTable* table, std::span<const BodyState> states,
                          std::span<const BodyInfo> infos, std::span<const std::uint8_t> moving,
                          const WorldDef& def, WorkerPool& pool) {
  table_ = table;
  pool_ = &pool;
  work_.clear();
  for (const std::uint32_t slot : table->acting) {
    const Joint& j = table->joints[slot];
    const bool a_moves = j.a != kNoBody && moving[j.a];
    if (!a_moves && !moving[j.b]) continue;
    JointWork w{};
    w.slot = slot;
    w.type = j.def.type;
    w.a = j.a;
    w.b = j.b;
    if (j.a != kNoBody) {
      w.ma = infos[j.a].inv_mass;
      w.ia = infos[j.a].inv_inertia;
    }
    w.mb = infos[j.b].inv_mass;
    w.ib = infos[j.b].inv_inertia;
    w.local_a = j.local_a;
    w.local_b = j.local_b;
    w.local_axis = j.local_axis;
    w.reference_angle = j.reference_angle;
    work_.push_back(w);
  }
  joined_.assign(states.size(), 0);
  for (const JointWork& w : work_) {
    if (w.a != kNoBody) joined_[w.a] = 1;
    joined_[w.b] = 1;
  }
  joined_bodies_.clear();
  for (std::size_t i = 0; i < joined_.size(); ++i) {
    if (joined_[i]) joined_bodies_.push_back(static_cast<BodyIndex>(i));
  }
  rotations_.resize(states.size());
  rotation_lanes_ = &WidePassesFor(def.substep_features.lanes);
  PrepareDirect(infos);
  // The lanes need the bodies' angular velocities (and push velocities) to be there.
  wide_passes_ = nullptr;
  if (def.rotation && wide_.Pack(work_, *table, states.size()) > 0) {
    wide_passes_ = &WidePassesFor(def.substep_features.lanes);
  }
  scalar_works_.clear();
  for (std::uint32_t i = 0; i < work_.size(); ++i) {
    if (!wide_passes_ || wide_.lane_of[i] == WideJoints::kNotWide) scalar_works_.push_back(i);
  }
  return !work_.empty();
}

template <typename Pass>
void JointSolver::ForEachJointBlock(Pass&& pass) {
  ForEachGroup(*pool_, wide_.order, [&](std::uint32_t begin, std::uint32_t end) {
    pass(wide_.blocks.data() + begin, std::size_t{end - begin});
  }, kBlockLanes);
}

std::pair<double*, double*> JointSolver::PointImpulse(std::uint32_t i) {
  if (wide_passes_ && wide_.lane_of[i] != WideJoints::kNotWide) {
    JointBlock& k = wide_.blocks[wide_.lane_of[i] / kBlockLanes];
    const std::uint32_t lane = wide_.lane_of[i] % kBlockLanes;
    return {&k.impulse_x[lane], &k.impulse_y[lane]};
  }
  Vec2& point = table_->joints[work_[i].slot].impulses.point;
  return {&point.x, &point.y};
}

void JointSolver::End() {
  if (wide_passes_) wide_.UnpackImpulses(work_, table_);
}

BodyState& JointSolver::StateA(const JointWork& w, std::span<BodyState> states) {
  if (w.a != kNoBody) return states[w.a];
  ground_ = BodyState{};
  ground_.position = table_->joints[w.slot].def.target;
  return ground_;
}

void JointSolver::UpdateFrames(std::span<const BodyState> states) {
  // Each body's rotation once: a body of a grid holds four joints. Each joint's frames are its
  // own, so the threads share them out with the same bits.
  // In lanes, a run of the bodies at a time (WidePasses::rotations).
  const auto joined = static_cast<std::uint32_t>(joined_bodies_.size());
  constexpr std::uint32_t kRun = 64;
  pool_->ParallelFor((joined + kRun - 1) / kRun, kMinParallelJoints / kRun, [&](std::uint32_t run) {
    const std::uint32_t begin = run * kRun;
    rotation_lanes_->rotations(&states[0].angle, sizeof(BodyState) / sizeof(double), joined_bodies_.data() + begin,
                               std::min(kRun, joined - begin), rotations_.data());
  });
  pool_->ParallelFor(static_cast<std::uint32_t>(work_.size()), kMinParallelJoints, [&](std::uint32_t i) {
    JointWork& w = work_[i];
    const BodyState& b = states[w.b];
    w.rb = Rotate(rotations_[w.b], w.local_b);
    Vec2 anchor_a;
    double angle_a = 0.0;
    if (w.a != kNoBody) {
      const BodyState& a = states[w.a];
      const Rot qa = rotations_[w.a];
      w.ra = Rotate(qa, w.local_a);
      anchor_a = a.position + w.ra;
      angle_a = a.angle;
      if (w.type == JointType::kPrismatic) w.axis = Rotate(qa, w.local_axis);
    } else {
      w.ra = {};
      anchor_a = table_->joints[w.slot].def.target;
    }
    w.separation = (b.position + w.rb) - anchor_a;
    w.angle = b.angle - angle_a - w.reference_angle;
  });
  if (wide_passes_) wide_.LoadFrames(work_, *pool_);
}

void JointSolver::Begin(std::span<BodyState> states, double h, bool aim_at_drift) {
  h_ = h;
  UpdateFrames(states);
  if (wide_passes_) {  // the lanes' warm start first, as their passes go first
    ForEachJointBlock([&](JointBlock* blocks, std::size_t count) {
      wide_passes_->joint_warm_start(blocks, count, states.data());
    });
  }
  for (const std::uint32_t i : scalar_works_) {
    JointWork& w = work_[i];
    Joint& j = table_->joints[w.slot];
    BodyState& a = StateA(w, states);
    BodyState& b = states[w.b];
    // Springs: one impulse for the (sub)step, before the rigid rows see the velocities.
    if (HasSpring(j)) {
      const SpringRate rate = MakeSpringRate(*j.def.spring, h);
      switch (j.def.type) {
        case JointType::kDistance: {
          AxisRow row;
          if (j.min_length < j.max_length && DistanceRow(w, &row) && row.mass > 0.0) {
            const double c = Length(w.separation) - j.length;
            ApplyRow(w, row, -row.mass * (rate.on_error * c + rate.on_rate * RowVelocity(row, a, b)), a, b);
          }
          break;
        }
        case JointType::kWeld: {
          const double k = w.ia + w.ib;
          if (k > 0.0) {
            const double cdot = b.angular_velocity - a.angular_velocity;
            ApplyAngle(w, -(rate.on_error * w.angle + rate.on_rate * cdot) / k, a, b);
          }
          const Vec2 error = rate.on_error * w.separation + rate.on_rate * PointVelocity(w, a, b);
          ApplyPoint(w, -Solve22(PointMass(w), error), a, b);
          break;
        }
        case JointType::kTarget: {
          const Vec2 error = rate.on_error * w.separation + rate.on_rate * PointVelocity(w, a, b);
          Vec2 impulse = -Solve22(PointMass(w), error);
          // The pull is capped: a grabbed body caught on something does not tear through it.
          const double cap = j.def.max_force * h;
          const double size = Length(impulse);
          if (size > cap) impulse = (cap / size) * impulse;
          ApplyPoint(w, impulse, a, b);
          break;
        }
        default: break;
      }
    }
    // Warm start: the rigid rows' impulses of the last substep, again.
    const JointImpulses& p = j.impulses;
    switch (j.def.type) {
      case JointType::kRevolute:
        ApplyAngle(w, p.motor + p.lower - p.upper, a, b);
        ApplyPoint(w, p.point, a, b);
        break;
      case JointType::kWeld:
        if (!HasSpring(j)) {
          ApplyAngle(w, p.angle, a, b);
          ApplyPoint(w, p.point, a, b);
        }
        break;
      case JointType::kPrismatic: {
        ApplyRow(w, PrismaticAxisRow(w), p.motor + p.lower - p.upper, a, b);
        ApplyBlock(w, MakePrismaticBlock(w), {p.point.x, p.angle}, a, b);
        break;
      }
      case JointType::kDistance: {
        AxisRow row;
        if (DistanceRow(w, &row)) ApplyRow(w, row, p.axial + p.lower - p.upper, a, b);
        break;
      }
      case JointType::kTarget: break;
    }
  }
  if (aim_at_drift) {
    PredictDrift(states, h);
  } else {
    for (JointWork& w : work_) w.drift_point = {}, w.drift_axis = 0.0;
  }
  if (wide_passes_) wide_.LoadDrift(work_, *pool_);
}

void JointSolver::PredictDrift(std::span<BodyState> states, double h) {
  // Where each anchor would be after h at today's velocities, less where the rows' linear part
  // puts it. The arms turn by ω·h: to second order r + ω·h·r⊥ − ½(ω·h)²·r while that is within
  // (ω·h)³/6 ≈ 2e-5 of the turn, exactly beyond (a whipping link, a long step).
  auto turned = [](Vec2 r, double turn) {
    if (std::abs(turn) > 0.05) return Rotate(MakeRot(turn), r);
    return r + turn * LeftPerp(r) - (0.5 * turn * turn) * r;
  };
  // Each joint's drift is its own: the threads share them out with the same bits.
  pool_->ParallelFor(static_cast<std::uint32_t>(work_.size()), kMinParallelJoints, [&](std::uint32_t i) {
    JointWork& w = work_[i];
    w.drift_point = {};
    w.drift_axis = 0.0;
    // Target joints, the only ones without a body A, have none: StateA's shared ground stays
    // unused. (The type from JointWork: most joints need nothing else from the table here.)
    if (w.type == JointType::kTarget || (w.type == JointType::kWeld && HasSpring(table_->joints[w.slot]))) return;
    const BodyState& a = StateA(w, states);
    const BodyState& b = states[w.b];
    const double turn_a = a.angular_velocity * h, turn_b = b.angular_velocity * h;
    const Vec2 ra = turned(w.ra, turn_a), rb = turned(w.rb, turn_b);
    const Vec2 separation = (b.position + h * b.velocity + rb) - (a.position + h * a.velocity + ra);
    switch (w.type) {
      case JointType::kRevolute:
      case JointType::kWeld:
        w.drift_point = separation - w.separation - h * PointVelocity(w, a, b);
        break;
      case JointType::kPrismatic: {
        const Vec2 axis = turned(w.axis, turn_a);
        const PrismaticBlock block = MakePrismaticBlock(w);
        w.drift_point.x = Dot(LeftPerp(axis), separation) - Dot(block.perp, w.separation) -
                          h * BlockVelocity(block, a, b).x;
        const AxisRow row = PrismaticAxisRow(w);
        w.drift_axis = Dot(axis, separation) - Dot(w.axis, w.separation) - h * RowVelocity(row, a, b);
        break;
      }
      case JointType::kDistance: {
        AxisRow row;
        if (DistanceRow(w, &row)) {
          w.drift_axis = Length(separation) - Length(w.separation) - h * RowVelocity(row, a, b);
        }
        break;
      }
      default: break;
    }
  });
}

void JointSolver::Solve(std::span<BodyState> states, double inv_h) {
  if (wide_passes_) {
    ForEachJointBlock([&](JointBlock* blocks, std::size_t count) {
      wide_passes_->joint_solve(blocks, count, states.data(), inv_h);
    });
  }
  for (const std::uint32_t i : scalar_works_) {
    JointWork& w = work_[i];
    Joint& j = table_->joints[w.slot];
    JointImpulses& p = j.impulses;
    BodyState& a = StateA(w, states);
    BodyState& b = states[w.b];
    switch (j.def.type) {
      case JointType::kRevolute: {
        const double k = w.ia + w.ib;
        if (k > 0.0) {
          if (j.def.motor) {
            const double cap = j.def.motor->max_force * h_;
            const double cdot = b.angular_velocity - a.angular_velocity - j.def.motor->speed;
            const double updated = Clamp(p.motor - cdot / k, -cap, cap);
            ApplyAngle(w, updated - p.motor, a, b);
            p.motor = updated;
          }
          if (j.def.limits) {
            const double rel = b.angular_velocity - a.angular_velocity;
            const double lower_gap = w.angle - j.def.limits->lower;
            ApplyAngle(w, ClampedStep(&p.lower, (LimitTarget(lower_gap, inv_h) - rel) / k), a, b);
            const double rel2 = a.angular_velocity - b.angular_velocity;
            const double upper_gap = j.def.limits->upper - w.angle;
            ApplyAngle(w, -ClampedStep(&p.upper, (LimitTarget(upper_gap, inv_h) - rel2) / k), a, b);
          }
        }
        const Vec2 impulse = -Solve22(PointMass(w), PointVelocity(w, a, b) + inv_h * w.drift_point);
        p.point += impulse;
        ApplyPoint(w, impulse, a, b);
        break;
      }
      case JointType::kWeld: {
        if (HasSpring(j)) break;
        const double k = w.ia + w.ib;
        if (k > 0.0) {
          const double impulse = -(b.angular_velocity - a.angular_velocity) / k;
          p.angle += impulse;
          ApplyAngle(w, impulse, a, b);
        }
        const Vec2 impulse = -Solve22(PointMass(w), PointVelocity(w, a, b) + inv_h * w.drift_point);
        p.point += impulse;
        ApplyPoint(w, impulse, a, b);
        break;
      }
      case JointType::kPrismatic: {
        const AxisRow row = PrismaticAxisRow(w);
        if (row.mass > 0.0) {
          if (j.def.motor) {
            const double cap = j.def.motor->max_force * h_;
            const double cdot = RowVelocity(row, a, b) - j.def.motor->speed;
            const double updated = Clamp(p.motor - row.mass * cdot, -cap, cap);
            ApplyRow(w, row, updated - p.motor, a, b);
            p.motor = updated;
          }
          if (j.def.limits) {
            const double translation = Dot(w.axis, w.separation);
            const double lower_gap = translation - j.def.limits->lower;
            const double lower_target = LimitTarget(lower_gap, inv_h) - w.drift_axis * inv_h;
            ApplyRow(w, row, ClampedStep(&p.lower, row.mass * (lower_target - RowVelocity(row, a, b))), a, b);
            const double upper_gap = j.def.limits->upper - translation;
            const double upper_target = LimitTarget(upper_gap, inv_h) + w.drift_axis * inv_h;
            ApplyRow(w, row, -ClampedStep(&p.upper, row.mass * (upper_target + RowVelocity(row, a, b))), a, b);
          }
        }
        const PrismaticBlock block = MakePrismaticBlock(w);
        const Vec2 impulse = -Solve22(block.k, BlockVelocity(block, a, b) + Vec2{inv_h * w.drift_point.x, 0.0});
        p.point.x += impulse.x;
        p.angle += impulse.y;
        ApplyBlock(w, block, impulse, a, b);
        break;
      }
      case JointType::kDistance: {
        AxisRow row;
        if (!DistanceRow(w, &row) || row.mass == 0.0) break;
        if (j.rigid_length) {
          const double impulse = -row.mass * (RowVelocity(row, a, b) + inv_h * w.drift_axis);
          p.axial += impulse;
          ApplyRow(w, row, impulse, a, b);
          break;
        }
        const double length = Length(w.separation);
        if (j.min_length > 0.0) {
          const double gap = length - j.min_length;
          const double target = LimitTarget(gap, inv_h) - w.drift_axis * inv_h;
          ApplyRow(w, row, ClampedStep(&p.lower, row.mass * (target - RowVelocity(row, a, b))), a, b);
        }
        if (std::isfinite(j.max_length)) {
          const double gap = j.max_length - length;
          const double target = LimitTarget(gap, inv_h) + w.drift_axis * inv_h;
          ApplyRow(w, row, -ClampedStep(&p.upper, row.mass * (target + RowVelocity(row, a, b))), a, b);
        }
        break;
      }
      case JointType::kTarget: break;
    }
  }
}

void JointSolver::PushOut(std::span<const BodyState> states, PushVelocities push, double inv_h, int passes) {
  UpdateFrames(states);
  const double rate = kJointPushFraction * inv_h;
  const bool turning = !push.angular.empty();
  // The push velocities of a body, as a BodyState the row helpers can read and write.
  auto load = [&](BodyIndex i) {
    BodyState s;
    if (i == kNoBody) return s;
    s.velocity = push.linear[i];
    s.angular_velocity = turning ? push.angular[i] : 0.0;
    return s;
  };
  auto store = [&](BodyIndex i, const BodyState& s) {
    if (i == kNoBody) return;
    push.linear[i] = s.velocity;
    if (turning) push.angular[i] = s.angular_velocity;
  };
  for (JointWork& w : work_) w.push_lower = w.push_upper = 0.0;
  for (int pass = 0; pass < passes; ++pass) {
    if (wide_passes_) {
      ForEachJointBlock([&](JointBlock* blocks, std::size_t count) {
        wide_passes_->joint_push_out(blocks, count, push.linear.data(), push.angular.data(), rate);
      });
    }
    for (const std::uint32_t i : scalar_works_) {
      JointWork& w = work_[i];
      const Joint& j = table_->joints[w.slot];
      if (j.def.type == JointType::kTarget) continue;
      if (HasSpring(j) && j.def.type == JointType::kWeld) continue;
      BodyState a = load(w.a), b = load(w.b);
      switch (j.def.type) {
        case JointType::kRevolute:
        case JointType::kWeld: {
          if (j.def.type == JointType::kWeld && w.ia + w.ib > 0.0) {
            const double impulse = -(rate * w.angle + (b.angular_velocity - a.angular_velocity)) / (w.ia + w.ib);
            ApplyAngle(w, impulse, a, b);
          }
          if (j.def.type == JointType::kRevolute && j.def.limits && w.ia + w.ib > 0.0) {
            const double k = w.ia + w.ib;
            const double rel = b.angular_velocity - a.angular_velocity;
            const double lower_gap = w.angle - j.def.limits->lower;
            if (lower_gap < 0.0 || w.push_lower > 0.0) {
              ApplyAngle(w, ClampedStep(&w.push_lower, (-rate * std::min(lower_gap, 0.0) - rel) / k), a, b);
            }
            const double upper_gap = j.def.limits->upper - w.angle;
            if (upper_gap < 0.0 || w.push_upper > 0.0) {
              const double rel2 = a.angular_velocity - b.angular_velocity;
              ApplyAngle(w, -ClampedStep(&w.push_upper, (-rate * std::min(upper_gap, 0.0) - rel2) / k), a, b);
            }
          }
          const Vec2 target = -rate * w.separation;
          ApplyPoint(w, Solve22(PointMass(w), target - PointVelocity(w, a, b)), a, b);
          break;
        }
        case JointType::kPrismatic: {
          const AxisRow row = PrismaticAxisRow(w);
          if (j.def.limits && row.mass > 0.0) {
            const double translation = Dot(w.axis, w.separation);
            const double lower_gap = translation - j.def.limits->lower;
            if (lower_gap < 0.0 || w.push_lower > 0.0) {
              ApplyRow(w, row, ClampedStep(&w.push_lower, row.mass * (-rate * std::min(lower_gap, 0.0) - RowVelocity(row, a, b))), a, b);
            }
            const double upper_gap = j.def.limits->upper - translation;
            if (upper_gap < 0.0 || w.push_upper > 0.0) {
              ApplyRow(w, row, -ClampedStep(&w.push_upper, row.mass * (-rate * std::min(upper_gap, 0.0) + RowVelocity(row, a, b))), a, b);
            }
          }
          const PrismaticBlock block = MakePrismaticBlock(w);
          const Vec2 target{-rate * Dot(block.perp, w.separation), -rate * w.angle};
          ApplyBlock(w, block, Solve22(block.k, target - BlockVelocity(block, a, b)), a, b);
          break;
        }
        case JointType::kDistance: {
          AxisRow row;
          if (!DistanceRow(w, &row) || row.mass == 0.0) break;
          const double length = Length(w.separation);
          if (j.rigid_length) {
            ApplyRow(w, row, row.mass * (-rate * (length - j.length) - RowVelocity(row, a, b)), a, b);
            break;
          }
          const double lower_gap = length - j.min_length;
          if (j.min_length > 0.0 && (lower_gap < 0.0 || w.push_lower > 0.0)) {
            ApplyRow(w, row, ClampedStep(&w.push_lower, row.mass * (-rate * std::min(lower_gap, 0.0) - RowVelocity(row, a, b))), a, b);
          }
          const double upper_gap = j.max_length - length;
          if (std::isfinite(j.max_length) && (upper_gap < 0.0 || w.push_upper > 0.0)) {
            ApplyRow(w, row, -ClampedStep(&w.push_upper, row.mass * (-rate * std::min(upper_gap, 0.0) + RowVelocity(row, a, b))), a, b);
          }
          break;
        }
        case JointType::kTarget: break;
      }
      store(w.a, a);
      store(w.b, b);
    }
  }
  SolveDirect({}, &push, rate);
}

void JointSolver::MarkBodies(std::vector<std::uint8_t>* pushed) const {
  if (pushed->empty()) return;  // semi-implicit Euler: every body moves by h·v anyway
  for (const JointWork& w : work_) {
    if (w.a != kNoBody) (*pushed)[w.a] = 1;
    (*pushed)[w.b] = 1;
  }
}

}  // namespace engine::detail
