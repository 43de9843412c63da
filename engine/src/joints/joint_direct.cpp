// The joints' direct solve: islands by union-find over the joints' moving bodies, each small
// island's equality rows solved together by a dense Cholesky factor of K = J·M⁻¹·Jᵀ, built anew
// each substep (the arms turn).
#include "joints/joint_direct.h"

#include <cmath>
#include <utility>

#include "joints/joint_solver.h"
#include "solver/cholesky.h"

namespace engine::detail {

namespace {

// The equality rows of a joint (at most three), from where its frames stand now.
// `point`: where the point's accumulated impulse lives (the joint's, or its lane's).
int EqualityRows(Joint& j, const JointWork& w, std::uint32_t work, std::pair<double*, double*> point,
                 JointRow* out) {
  const bool turns = w.ia + w.ib > 0.0;
  JointImpulses& p = j.impulses;
  int n = 0;
  auto point_rows = [&] {
    out[n++] = {work, {1.0, 0.0}, Cross(w.ra, {1.0, 0.0}), Cross(w.rb, {1.0, 0.0}), w.separation.x,
                w.drift_point.x, point.first};
    out[n++] = {work, {0.0, 1.0}, Cross(w.ra, {0.0, 1.0}), Cross(w.rb, {0.0, 1.0}), w.separation.y,
                w.drift_point.y, point.second};
  };
  auto angle_row = [&] {
    if (turns) out[n++] = {work, {}, 1.0, 1.0, w.angle, 0.0, &p.angle};
  };
  switch (j.def.type) {
    case JointType::kRevolute: point_rows(); break;
    case JointType::kWeld:
      if (j.def.spring) break;
      angle_row();
      point_rows();
      break;
    case JointType::kPrismatic: {
      const Vec2 perp = LeftPerp(w.axis);
      out[n++] = {work, perp, Cross(w.separation + w.ra, perp), Cross(w.rb, perp), Dot(perp, w.separation),
                  w.drift_point.x, &p.point.x};
      angle_row();
      break;
    }
    case JointType::kDistance: {
      const double length = Length(w.separation);
      if (!j.rigid_length || !(length > 1e-12)) break;
      const Vec2 u = w.separation / length;
      out[n++] = {work, u, Cross(w.ra, u), Cross(w.rb, u), length - j.length, w.drift_axis, &p.axial};
      break;
    }
    default: break;
  }
  return n;
}

// Row i's velocity response to a unit impulse on row j, through the bodies they share.
double Coupling(const JointRow& ri, const JointWork& wi, const JointRow& rj, const JointWork& wj) {
  double k = 0.0;
  auto add = [&](BodyIndex body, double sign, double arm, double inv_mass, double inv_inertia) {
    if (body == kNoBody) return;
    if (body == wj.a) k -= sign * (inv_mass * Dot(ri.d, rj.d) + inv_inertia * arm * rj.arm_a);
    if (body == wj.b) k += sign * (inv_mass * Dot(ri.d, rj.d) + inv_inertia * arm * rj.arm_b);
  };
  if (wi.ma != 0.0 || wi.ia != 0.0) add(wi.a, -1.0, ri.arm_a, wi.ma, wi.ia);
  if (wi.mb != 0.0 || wi.ib != 0.0) add(wi.b, 1.0, ri.arm_b, wi.mb, wi.ib);
  return k;
}

// A row whose pivot falls below this fraction of its diagonal depends on the rows before it (a
// taut straight chain between two pins has one more row along itself than its links have
// freedoms): it is left out of the factor and gets no impulse; the others carry its load.
constexpr double kDependent = 1e-9;

// K's diagonal is raised by this fraction (damped least squares, as Levenberg-Marquardt): near a
// singular pose (a taut straight chain between two pins, whose sag takes a tension growing
// without bound) the exact answer's impulses blew the bridge up in one step; this bounds them.
constexpr double kRegularisation = 1e-4;

}  // namespace

void JointSolver::PrepareDirect(std::span<const BodyInfo> infos) {
  JointDirect& d = direct_;
  d.islands.clear();
  d.island_works.clear();
  d.island_starts.clear();
  if (work_.size() < 2) {  // one joint alone: its own rows are solved exactly by Gauss-Seidel
    return;
  }
  d.linked.Reset(infos.size());
  for (const JointWork& w : work_) {
    if (w.a != kNoBody && !HasInfiniteMass(infos[w.a]) && !HasInfiniteMass(infos[w.b])) d.linked.Join(w.a, w.b);
  }
  // Group the joints by island (the root of a moving body), islands in order of their first joint.
  d.root_island.assign(infos.size(), ~0u);
  std::vector<std::uint32_t>& island_of = d.island_of;
  std::vector<std::uint32_t>& counts = d.counts;
  island_of.resize(work_.size());
  counts.clear();
  for (std::uint32_t i = 0; i < work_.size(); ++i) {
    const JointWork& w = work_[i];
    const BodyIndex body = HasInfiniteMass(infos[w.b]) ? w.a : w.b;
    const std::uint32_t root = d.linked.Find(body);
    if (d.root_island[root] == ~0u) {
      d.root_island[root] = static_cast<std::uint32_t>(counts.size());
      counts.push_back(0);
    }
    island_of[i] = d.root_island[root];
    ++counts[island_of[i]];
  }
  d.island_starts.assign(counts.size() + 1, 0);
  for (std::size_t k = 0; k < counts.size(); ++k) d.island_starts[k + 1] = d.island_starts[k] + counts[k];
  d.island_works.assign(work_.size(), 0);
  std::vector<std::uint32_t>& fill = d.fill;
  fill.assign(d.island_starts.begin(), d.island_starts.end() - 1);
  for (std::uint32_t i = 0; i < work_.size(); ++i) d.island_works[fill[island_of[i]]++] = i;
}

void JointSolver::SolveDirect(std::span<BodyState> states, PushVelocities* push, double rate) {
  JointDirect& d = direct_;
  const bool turning = push == nullptr || !push->angular.empty();
  for (std::size_t island = 0; island + 1 < d.island_starts.size(); ++island) {
    const std::uint32_t first = d.island_starts[island], last = d.island_starts[island + 1];
    if (last - first < 2) continue;
    d.rows.clear();
    for (std::uint32_t k = first; k < last; ++k) {
      const std::uint32_t wi = d.island_works[k];
      JointRow rows[3];
      const int n = EqualityRows(table_->joints[work_[wi].slot], work_[wi], wi, PointImpulse(wi), rows);
      for (int r = 0; r < n; ++r) d.rows.push_back(rows[r]);
      if (d.rows.size() > static_cast<std::size_t>(kJointDirectMaxRows)) break;
    }
    const int n = static_cast<int>(d.rows.size());
    if (n < 2 || n > kJointDirectMaxRows) continue;
    d.matrix.assign(static_cast<std::size_t>(n) * n, 0.0);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j <= i; ++j) {
        const double k = Coupling(d.rows[i], work_[d.rows[i].work], d.rows[j], work_[d.rows[j].work]);
        d.matrix[i * n + j] = d.matrix[j * n + i] = k;
      }
      d.matrix[i * n + i] *= 1.0 + kRegularisation;
    }
    d.dependent.resize(n);
    // A non-finite pivot: Gauss-Seidel's answer stands.
    if (!CholeskyFactor(d.matrix.data(), n, n, d.dependent.data(), kDependent)) continue;
    // The residual: each row's velocity less its target (push: its push velocity less the
    // fraction of its error pushed out).
    d.residual.resize(n);
    auto velocity_of = [&](BodyIndex i) -> std::pair<Vec2, double> {
      if (i == kNoBody) return {Vec2{}, 0.0};
      if (!push) return {states[i].velocity, states[i].angular_velocity};
      return {push->linear[i], turning ? push->angular[i] : 0.0};
    };
    for (int i = 0; i < n; ++i) {
      const JointRow& r = d.rows[i];
      const JointWork& w = work_[r.work];
      const auto [va, wa] = velocity_of(w.a);
      const auto [vb, wb] = velocity_of(w.b);
      const double velocity = Dot(r.d, vb - va) + r.arm_b * wb - r.arm_a * wa;
      d.residual[i] = -(velocity + (push ? rate * r.error : r.drift * rate));
    }
    CholeskySolve(d.matrix.data(), n, n, d.residual.data(), d.dependent.data());
    for (int i = 0; i < n; ++i) {
      const JointRow& r = d.rows[i];
      const JointWork& w = work_[r.work];
      const double lambda = d.residual[i];
      if (!push) *r.impulse += lambda;
      auto apply = [&](BodyIndex body, double sign, double inv_mass, double inv_inertia, double arm) {
        if (body == kNoBody) return;
        Vec2& v = push ? push->linear[body] : states[body].velocity;
        v += (sign * inv_mass * lambda) * r.d;
        if (!turning) return;
        double& omega = push ? push->angular[body] : states[body].angular_velocity;
        omega += sign * inv_inertia * lambda * arm;
      };
      apply(w.a, -1.0, w.ma, w.ia, r.arm_a);
      apply(w.b, 1.0, w.mb, w.ib, r.arm_b);
    }
  }
}

}  // namespace engine::detail
