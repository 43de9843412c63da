// Islands by union-find over the contacts of turning pairs; per island K = J·M⁻¹·Jᵀ built once
// per step (dense, and row by row as its non-zeros), and per substep a few box-constrained QPs
// solved by block principal pivoting on a Cholesky factor that is kept and updated row by row.
#include "solver/direct_solver.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "engine/portable_math.h"
#include "solver/cholesky.h"

namespace engine::detail {

bool IsHeavyPair(const SubstepConstraint& sc, std::span<const BodyInfo> infos) {
  if (!sc.angular || sc.inv_mass_a == 0.0 || sc.inv_mass_b == 0.0) return false;
  const double heavier = std::max(infos[sc.a].mass, infos[sc.b].mass);
  const double lighter = std::min(infos[sc.a].mass, infos[sc.b].mass);
  return heavier >= kDirectMassRatio * lighter;
}

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The QPs are regularised proximally (Rockafellar, "Monotone operators and the proximal point
// algorithm", 1976): ρ·diag(K) is added to K and ρ·diag(K)·x_previous taken off q, so each QP
// has one answer, the one nearest the last (a statically indeterminate island, a box on two
// legs, has many; without a choice the pivoting wandered among them). Repeating the QP from its
// own answer converges to the exact answer of the unregularised problem; kVelocityTolerance
// (m/s, on what is left of ρ·diag(K)·Δx) ends the repeats, at most kMaxSolves of them. The
// push-out takes the same ρ about zero.
constexpr double kProximal = 1e-5;
constexpr double kVelocityTolerance = 1e-7;
constexpr int kMaxSolves = 4;

// Friction limits are held fixed in each QP: the first takes the limits the last answer ended
// with, each later one μ times the normal impulses just found. They count as settled when no
// binding limit moved by more than this fraction of the island's largest.
constexpr double kLimitTolerance = 1e-6;

enum : std::uint8_t { kFree, kAtLower, kAtUpper };

// A row's Jacobian: direction d, and the arms' r × d for A and B.
struct Jacobian {
  Vec2 d;
  double ra, rb;
};

Jacobian RowJacobian(const SubstepConstraint& sc, std::int32_t point) {
  if (point >= 0) {
    const SubstepPoint& p = sc.points[point];
    return {sc.normal, Cross(p.anchor_a, sc.normal), Cross(p.anchor_b, sc.normal)};
  }
  Vec2 ra{}, rb{};
  for (int k = 0; k < sc.point_count; ++k) ra += sc.points[k].anchor_a, rb += sc.points[k].anchor_b;
  ra = ra / sc.point_count;
  rb = rb / sc.point_count;
  const Vec2 t = LeftPerp(sc.normal);
  return {t, Cross(ra, t), Cross(rb, t)};
}

// Row i's velocity response to a unit impulse on row j, through the bodies they share.
double Coupling(const SubstepConstraint& ci, const Jacobian& ji, const SubstepConstraint& cj,
                const Jacobian& jj) {
  double k = 0.0;
  // The body is A (sign −1) or B (+1) of row i; it adds where it is also A or B of row j.
  auto add = [&](BodyIndex body, double sign, double arm, double inv_mass, double inv_inertia) {
    if (body == cj.a) k -= sign * (inv_mass * Dot(ji.d, jj.d) + inv_inertia * arm * jj.ra);
    if (body == cj.b) k += sign * (inv_mass * Dot(ji.d, jj.d) + inv_inertia * arm * jj.rb);
  };
  if (ci.inv_mass_a != 0.0) add(ci.a, -1.0, ji.ra, ci.inv_mass_a, ci.inv_inertia_a);
  if (ci.inv_mass_b != 0.0) add(ci.b, 1.0, ji.rb, ci.inv_mass_b, ci.inv_inertia_b);
  return k;
}

// Removes row and column p from the n×n factor: the rows below move up one, and Givens
// rotations of neighbouring columns take out what they held right of the diagonal (rotations
// from the right leave L·Lᵀ unchanged). O(n²); false if a pivot vanishes.
bool DeleteFromFactor(double* l, int n, int stride, int p) {
  for (int i = p; i < n - 1; ++i) {
    for (int c = 0; c <= i + 1; ++c) l[i * stride + c] = l[(i + 1) * stride + c];
  }
  for (int j = p; j < n - 1; ++j) {
    const double a = l[j * stride + j], b = l[j * stride + j + 1];
    const double r = Hypot(a, b);
    if (!(r > 0.0)) return false;
    const double c = a / r, s = b / r;
    for (int i = j; i < n - 1; ++i) {
      const double u = l[i * stride + j], v = l[i * stride + j + 1];
      l[i * stride + j] = c * u + s * v;
      l[i * stride + j + 1] = c * v - s * u;
    }
  }
  return true;
}

// The box-constrained QP min ½·xᵀ(K + ρD)x + qᵀx over lo ≤ x ≤ hi (D = diag K), as the mixed
// complementarity problem w = (K + ρD)·x + q with w = 0 where x lies strictly inside its bounds,
// w ≥ 0 at lo and w ≤ 0 at hi. Block principal pivoting (Júdice and Pires, "A block principal
// pivoting algorithm for large-scale strictly monotone linear complementarity problems",
// Computers & Operations Research 21, 1994): solve the free rows with every other row at its
// bound, then move every row whose condition the answer breaks at once; after three such moves
// that do not reduce their number, move only the last one (Murty's rule), which ends for a
// positive definite matrix.
class BoxQp {
 public:
  /// K's rows are `stride` apart; `cache` names the solver's factor slot to keep and update.
  BoxQp(const double* k, int n, int stride, double rho, const DirectSolver::Sparse& sparse, DirectSolver* s,
        std::size_t cache)
      : k_(k), n_(n), stride_(stride), rho_(rho), sparse_(sparse), s_(s), cache_(cache) {}

  /// `bound` is the first guess of each row's state, and the answer's; false if the pivoting
  /// does not end within its budget or a factor fails.
  bool Solve(const double* q, const double* lo, const double* hi, std::uint8_t* bound, double* x) {
    int fewest = n_ + 1, patience = 3;
    for (int iteration = 0; iteration < 4 * n_ + 20; ++iteration) {
      for (int i = 0; i < n_; ++i) {
        if (lo[i] == hi[i]) bound[i] = kAtLower;
        if (bound[i] != kFree) x[i] = bound[i] == kAtLower ? lo[i] : hi[i];
      }
      if (!SolveFree(q, bound, x)) return false;
      std::vector<std::uint8_t>& wrong = s_->flagged;
      wrong.assign(n_, 0);
      int count = 0, last = -1;
      for (int i = 0; i < n_; ++i) {
        if (bound[i] == kFree) {
          wrong[i] = x[i] < lo[i] || x[i] > hi[i];
        } else if (lo[i] != hi[i]) {
          const double w = q[i] + rho_ * k_[i * stride_ + i] * x[i] + RowTimes(i, x);
          const double tolerance = 1e-10 * (1.0 + std::abs(q[i]));
          wrong[i] = bound[i] == kAtLower ? w < -tolerance : w > tolerance;
        }
        if (wrong[i]) ++count, last = i;
      }
      if (count == 0) return true;
      if (count < fewest) {
        fewest = count, patience = 3;
      } else if (patience > 0) {
        --patience;
      } else {
        Move(last, lo, bound, x);
        continue;
      }
      for (int i = 0; i < n_; ++i) {
        if (wrong[i]) Move(i, lo, bound, x);
      }
    }
    return false;
  }

 private:
  // Solves the free rows with every other row at its bound. The slot keeps its factor from call
  // to call and brings it to the new free rows by deleting and appending rows (O(f²) each); only
  // many changes at once, or a slot of a new step, are factored afresh (O(f³)).
  bool SolveFree(const double* q, const std::uint8_t* bound, double* x) {
    std::vector<std::uint32_t>& order = s_->factor_rows[cache_];
    std::vector<double>& l = s_->factor[cache_];
    const int stride = n_;
    l.resize(static_cast<std::size_t>(stride) * stride);
    int f = static_cast<int>(order.size());
    int gone = 0, free_count = 0;
    for (int p = 0; p < f; ++p) gone += bound[order[p]] != kFree;
    for (int i = 0; i < n_; ++i) free_count += bound[i] == kFree;
    const int added = free_count - (f - gone);
    bool fresh = !s_->factor_valid[cache_] || 4 * (gone + added) > f + 8;
    for (int p = f - 1; p >= 0 && !fresh; --p) {
      if (bound[order[p]] == kFree) continue;
      fresh = !DeleteFromFactor(l.data(), f, stride, p);
      order.erase(order.begin() + p);
      --f;
    }
    if (!fresh) {
      s_->in_factor.assign(n_, 0);
      for (std::uint32_t r : order) s_->in_factor[r] = 1;
      for (int i = 0; i < n_ && !fresh; ++i) {
        if (bound[i] != kFree || s_->in_factor[i]) continue;
        fresh = !AppendToFactor(l.data(), f, stride, order, static_cast<std::uint32_t>(i));
        order.push_back(static_cast<std::uint32_t>(i));
        ++f;
      }
    }
    if (fresh) {
      order.clear();
      for (int i = 0; i < n_; ++i) {
        if (bound[i] == kFree) order.push_back(static_cast<std::uint32_t>(i));
      }
      f = static_cast<int>(order.size());
      for (int r = 0; r < f; ++r) {
        for (int c = 0; c <= r; ++c) l[r * stride + c] = k_[order[r] * stride_ + order[c]];
        l[r * stride + r] *= 1.0 + rho_;
      }
      s_->factor_valid[cache_] = CholeskyFactor(l.data(), f, stride);
      if (!s_->factor_valid[cache_]) return false;
    }
    std::vector<double>& rhs = s_->rhs;
    rhs.resize(f);
    for (int r = 0; r < f; ++r) {
      double v = -q[order[r]];
      for (std::uint32_t e = sparse_.begin[order[r]]; e < sparse_.end[order[r]]; ++e) {
        const std::uint32_t j = sparse_.column[e];
        if (static_cast<int>(j) >= n_) break;
        if (bound[j] != kFree && x[j] != 0.0) v -= sparse_.value[e] * x[j];
      }
      rhs[r] = v;
    }
    CholeskySolve(l.data(), f, stride, rhs.data());
    for (int r = 0; r < f; ++r) x[order[r]] = rhs[r];
    return true;
  }

  // Appends row `row` to the f×f factor of the rows in `order`: its off-diagonal part solves
  // L·y = K[order, row]. False if the new pivot is not clearly positive.
  bool AppendToFactor(double* l, int f, int stride, const std::vector<std::uint32_t>& order,
                      std::uint32_t row) const {
    double* y = l + f * stride;
    double sum = 0.0;
    for (int p = 0; p < f; ++p) {
      double v = k_[order[p] * stride_ + row];
      for (int k = 0; k < p; ++k) v -= l[p * stride + k] * y[k];
      y[p] = v / l[p * stride + p];
      sum += y[p] * y[p];
    }
    const double diagonal = k_[row * stride_ + row] * (1.0 + rho_);
    const double d2 = diagonal - sum;
    if (!(d2 > 1e-12 * diagonal)) return false;
    y[f] = std::sqrt(d2);
    return true;
  }

  // Row i of K times x over the row's non-zeros (rows share few bodies), in the first n_ columns.
  double RowTimes(int i, const double* x) const {
    double sum = 0.0;
    for (std::uint32_t e = sparse_.begin[i]; e < sparse_.end[i]; ++e) {
      const std::uint32_t j = sparse_.column[e];
      if (static_cast<int>(j) >= n_) break;
      sum += sparse_.value[e] * x[j];
    }
    return sum;
  }

  void Move(int i, const double* lo, std::uint8_t* bound, const double* x) const {
    bound[i] = bound[i] != kFree ? kFree : x[i] < lo[i] ? kAtLower : kAtUpper;
  }

  const double* k_;
  int n_;
  int stride_;
  double rho_;
  DirectSolver::Sparse sparse_;
  DirectSolver* s_;
  std::size_t cache_;
};

void ApplyImpulse(const SubstepConstraint& sc, Vec2 anchor_a, Vec2 anchor_b, Vec2 impulse, Vec2& va,
                  double& wa, Vec2& vb, double& wb) {
  va -= sc.inv_mass_a * impulse;
  wa -= sc.inv_inertia_a * Cross(anchor_a, impulse);
  vb += sc.inv_mass_b * impulse;
  wb += sc.inv_inertia_b * Cross(anchor_b, impulse);
}

void ApplyImpulse(const SubstepConstraint& sc, const SubstepPoint& p, Vec2 impulse, std::span<BodyState> states) {
  BodyState& a = states[sc.a];
  BodyState& b = states[sc.b];
  ApplyImpulse(sc, p.anchor_a, p.anchor_b, impulse, a.velocity, a.angular_velocity, b.velocity, b.angular_velocity);
}

DirectSolver::Sparse SparseRows(const DirectSolver* s, const DirectSolver::Island& island) {
  return {s->sparse_begin.data() + island.first_row, s->sparse_end.data() + island.first_row,
          s->sparse_column.data(), s->sparse_value.data()};
}

// Takes this substep's impulses on the island's contacts (warm start and Gauss-Seidel) back off
// its bodies, which leaves their free velocities, and starts x from those impulses. The
// velocities are saved first, for a solve that fails.
void TakeOffImpulses(DirectSolver* s, const DirectSolver::Island& island,
                     std::span<const SubstepConstraint> constraints, std::span<BodyState> states) {
  const int m = static_cast<int>(island.rows);
  const int normals = static_cast<int>(island.normal_rows);
  const DirectSolver::Row* rows = s->rows.data() + island.first_row;
  double* x = s->x.data();
  s->saved.clear();
  for (std::uint32_t i = 0; i < island.body_count; ++i) s->saved.push_back(states[s->bodies[island.first_body + i]]);
  for (int i = normals; i < m; ++i) {
    const SubstepConstraint& sc = constraints[rows[i].constraint];
    const Vec2 t = LeftPerp(sc.normal);
    double friction = 0.0;
    for (int n = 0; n < sc.point_count; ++n) {
      const SubstepPoint& p = sc.points[n];
      ApplyImpulse(sc, p, -(p.normal_impulse * sc.normal + p.tangent_impulse * t), states);
      friction += p.tangent_impulse;
    }
    x[i] = friction;
  }
  for (int i = 0; i < normals; ++i) x[i] = constraints[rows[i].constraint].points[rows[i].point].normal_impulse;
}

// q = J·v_free − target, and the normal rows' bounds: touching contacts may not approach, a gap
// may close this substep.
void SetVelocityTargets(DirectSolver* s, const DirectSolver::Island& island,
                        std::span<const SubstepConstraint> constraints, std::span<const BodyState> states,
                        const StepStart& start, double inv_h) {
  const int m = static_cast<int>(island.rows);
  const DirectSolver::Row* rows = s->rows.data() + island.first_row;
  for (int i = 0; i < m; ++i) {
    const SubstepConstraint& sc = constraints[rows[i].constraint];
    const Jacobian j = RowJacobian(sc, rows[i].point);
    const BodyState& a = states[sc.a];
    const BodyState& b = states[sc.b];
    s->q[i] = Dot(j.d, b.velocity - a.velocity) + j.rb * b.angular_velocity - j.ra * a.angular_velocity;
    if (rows[i].point >= 0) {
      s->q[i] += std::max(CurrentSeparation(sc, sc.points[rows[i].point], states, start), 0.0) * inv_h;
      s->lo[i] = 0.0, s->hi[i] = kInfinity;
    }
  }
}

// Sets each friction row's bounds to ± its limit: the first QP (`first`) takes the limits the
// last answer ended with, each later one μ times the normal impulses just found. True if a
// binding limit moved, or the answer now lies outside its limit, by more than the tolerance.
bool UpdateFrictionLimits(DirectSolver* s, const DirectSolver::Island& island,
                          std::span<const SubstepConstraint> constraints, bool first) {
  const int m = static_cast<int>(island.rows);
  const int normals = static_cast<int>(island.normal_rows);
  const DirectSolver::Row* rows = s->rows.data() + island.first_row;
  const std::uint8_t* bound = s->bound.data() + island.first_row;
  const double* last_limit = s->last_limit.data() + island.first_row;
  const double* x = s->x.data();
  double largest = 0.0;
  for (int i = normals; i < m; ++i) {
    const SubstepConstraint& sc = constraints[rows[i].constraint];
    double normal = 0.0;
    for (int n = 0; n < sc.point_count; ++n) normal += x[rows[i].first_normal + n];
    s->limit[i] = first ? last_limit[i] : sc.friction * normal;
    largest = std::max(largest, s->limit[i]);
  }
  bool moved = false;
  for (int i = normals; i < m; ++i) {
    const double limit = s->limit[i];
    moved = moved || (bound[i] != kFree && std::abs(limit - s->hi[i]) > kLimitTolerance * largest) ||
            std::abs(x[i]) > limit + kLimitTolerance * largest;
    s->lo[i] = -limit, s->hi[i] = limit;
  }
  return moved;
}

// Each QP holds the friction limits fixed, so it is convex, and its answer can only take kinetic
// energy away: with fixed limits every row's impulse does non-positive work on the answer's
// velocity (up to the proximal term's residue). Repeats it from its own answer, with the limits
// brought up to date, until both settle; false if a solve fails.
bool SolveUntilSettled(DirectSolver* s, std::size_t index, std::span<const SubstepConstraint> constraints) {
  const DirectSolver::Island& island = s->islands[index];
  const int m = static_cast<int>(island.rows);
  const double* k = s->matrix.data() + island.matrix;
  std::uint8_t* bound = s->bound.data() + island.first_row;
  double* x = s->x.data();
  BoxQp qp(k, m, m, kProximal, SparseRows(s, island), s, index);
  bool solved = false;
  double residual = kInfinity;
  for (int repeat = 0; repeat < kMaxSolves; ++repeat) {
    const bool moved = UpdateFrictionLimits(s, island, constraints, repeat == 0);
    if (repeat > 0 && !moved && residual < kVelocityTolerance) break;
    for (int i = 0; i < m; ++i) s->centred[i] = s->q[i] - kProximal * k[i * m + i] * x[i];
    s->previous.assign(x, x + m);
    solved = qp.Solve(s->centred.data(), s->lo.data(), s->hi.data(), bound, x);
    if (!solved) break;
    residual = 0.0;
    for (int i = 0; i < m; ++i) residual = std::max(residual, kProximal * k[i * m + i] * std::abs(x[i] - s->previous[i]));
  }
  return solved;
}

// The answer, and the impulses for warm starting and the next pass: normals per point, friction
// shared evenly between the points, which applies it at their mean anchor as its row has it.
void ApplyAnswer(const DirectSolver* s, const DirectSolver::Island& island,
                 std::span<SubstepConstraint> constraints, std::span<BodyState> states) {
  const int m = static_cast<int>(island.rows);
  const int normals = static_cast<int>(island.normal_rows);
  const DirectSolver::Row* rows = s->rows.data() + island.first_row;
  const double* x = s->x.data();
  for (int i = 0; i < normals; ++i) {
    SubstepConstraint& sc = constraints[rows[i].constraint];
    SubstepPoint& p = sc.points[rows[i].point];
    p.normal_impulse = x[i];
    ApplyImpulse(sc, p, x[i] * sc.normal, states);
  }
  for (int i = normals; i < m; ++i) {
    SubstepConstraint& sc = constraints[rows[i].constraint];
    const double share = x[i] / sc.point_count;
    for (int n = 0; n < sc.point_count; ++n) {
      SubstepPoint& p = sc.points[n];
      p.tangent_impulse = share;
      ApplyImpulse(sc, p, share * LeftPerp(sc.normal), states);
    }
  }
}

bool SolveIsland(DirectSolver* s, std::size_t index, std::span<SubstepConstraint> constraints,
                 std::span<BodyState> states, const StepStart& start, double inv_h) {
  const DirectSolver::Island& island = s->islands[index];
  const int m = static_cast<int>(island.rows);
  s->x.resize(m), s->q.resize(m), s->lo.resize(m), s->hi.resize(m), s->limit.resize(m);
  s->centred.resize(m);
  TakeOffImpulses(s, island, constraints, states);
  SetVelocityTargets(s, island, constraints, states, start, inv_h);
  if (!SolveUntilSettled(s, index, constraints)) {
    for (std::uint32_t i = 0; i < island.body_count; ++i) states[s->bodies[island.first_body + i]] = s->saved[i];
    return false;  // the row states stay: the next substep's pivoting starts from them
  }
  double* last_limit = s->last_limit.data() + island.first_row;
  for (int i = static_cast<int>(island.normal_rows); i < m; ++i) last_limit[i] = s->hi[i];
  ApplyAnswer(s, island, constraints, states);
  return true;
}

// Forgets the last step's islands (their storage stays, for this step's).
void ClearIslands(DirectSolver* s) {
  s->rows.clear();
  s->islands.clear();
  s->matrix.clear();
  s->bodies.clear();
  s->bound.clear();
  s->push_bound.clear();
  s->sparse_begin.clear();
  s->sparse_end.clear();
  s->sparse_column.clear();
  s->sparse_value.clear();
  s->last_limit.clear();
  s->direct_contact.clear();
}

// Islands of bodies linked by contacts between turning pairs (static bodies link nothing), and
// which of them hold a heavy pair (`flagged`, by root).
void FlagHeavyIslands(std::span<const SubstepConstraint> constraints, std::span<const BodyInfo> infos,
                      DirectSolver* s) {
  const std::size_t n = infos.size();
  s->linked.Reset(n);
  for (const SubstepConstraint& sc : constraints) {
    if (!sc.angular || sc.inv_mass_a == 0.0 || sc.inv_mass_b == 0.0) continue;
    s->linked.Join(sc.a, sc.b);
  }
  s->flagged.assign(n, 0);
  for (const SubstepConstraint& sc : constraints) {
    if (IsHeavyPair(sc, infos)) s->flagged[s->linked.Find(sc.a)] = 1;
  }
}

// The turning contacts of the flagged islands, one group per island.
struct ContactGroups {
  std::vector<std::uint32_t> start;     ///< group i is contacts[start[i], start[i + 1])
  std::vector<std::uint32_t> contacts;  ///< constraint indices
  std::vector<std::uint32_t> count;     ///< per group: its contacts
  std::vector<std::uint32_t> rows;      ///< per group: its normal and friction rows

  std::span<const std::uint32_t> Group(std::size_t i) const { return {contacts.data() + start[i], count[i]}; }
};

// Each turning contact of a flagged island, numbered by island in the order of their first
// contacts, then grouped by a counting sort (each group stays in contact order).
ContactGroups GroupByIsland(std::span<const SubstepConstraint> constraints, DirectSolver* s) {
  ContactGroups groups;
  std::vector<std::int32_t> island_of_root(s->flagged.size(), -1), island_of(constraints.size(), -1);
  for (std::uint32_t c = 0; c < constraints.size(); ++c) {
    const SubstepConstraint& sc = constraints[c];
    if (!sc.angular) continue;
    const std::uint32_t root = s->linked.Find(sc.inv_mass_a != 0.0 ? sc.a : sc.b);
    if (!s->flagged[root]) continue;
    if (island_of_root[root] < 0) {
      island_of_root[root] = static_cast<std::int32_t>(groups.count.size());
      groups.count.push_back(0), groups.rows.push_back(0);
    }
    island_of[c] = island_of_root[root];
    ++groups.count[island_of[c]];
    groups.rows[island_of[c]] += sc.point_count + 1;
  }
  groups.start.assign(groups.count.size() + 1, 0);
  groups.contacts.resize(constraints.size());
  for (std::size_t i = 0; i < groups.count.size(); ++i) groups.start[i + 1] = groups.start[i] + groups.count[i];
  std::vector<std::uint32_t> fill(groups.start.begin(), groups.start.end() - 1);
  for (std::uint32_t c = 0; c < constraints.size(); ++c) {
    if (island_of[c] >= 0) groups.contacts[fill[island_of[c]]++] = c;
  }
  return groups;
}

// The island's rows: the normals, then one friction row per contact.
void AddRows(std::span<const SubstepConstraint> constraints, std::span<const std::uint32_t> group,
             DirectSolver* s, DirectSolver::Island* island) {
  island->first_row = static_cast<std::uint32_t>(s->rows.size());
  for (std::uint32_t c : group) {
    for (int k = 0; k < constraints[c].point_count; ++k) s->rows.push_back({c, k, 0});
  }
  island->normal_rows = static_cast<std::uint32_t>(s->rows.size()) - island->first_row;
  std::uint32_t first_normal = 0;
  for (std::uint32_t c : group) {
    s->rows.push_back({c, -1, first_normal});
    first_normal += constraints[c].point_count;
  }
  island->rows = static_cast<std::uint32_t>(s->rows.size()) - island->first_row;
}

// The island's moving bodies, ascending.
void AddBodies(std::span<const SubstepConstraint> constraints, std::span<const std::uint32_t> group,
               DirectSolver* s, DirectSolver::Island* island) {
  island->first_body = static_cast<std::uint32_t>(s->bodies.size());
  for (std::uint32_t c : group) {
    if (constraints[c].inv_mass_a != 0.0) s->bodies.push_back(constraints[c].a);
    if (constraints[c].inv_mass_b != 0.0) s->bodies.push_back(constraints[c].b);
  }
  std::sort(s->bodies.begin() + island->first_body, s->bodies.end());
  s->bodies.erase(std::unique(s->bodies.begin() + island->first_body, s->bodies.end()), s->bodies.end());
  island->body_count = static_cast<std::uint32_t>(s->bodies.size()) - island->first_body;
}

// The island's K = J·M⁻¹·Jᵀ (symmetric), and its non-zeros row by row, in column order.
void AddMatrix(std::span<const SubstepConstraint> constraints, DirectSolver* s, DirectSolver::Island* island) {
  const int m = static_cast<int>(island->rows);
  island->matrix = s->matrix.size();
  s->matrix.resize(island->matrix + static_cast<std::size_t>(m) * m);
  double* k = s->matrix.data() + island->matrix;
  const DirectSolver::Row* rows = s->rows.data() + island->first_row;
  for (int r = 0; r < m; ++r) {
    const SubstepConstraint& cr = constraints[rows[r].constraint];
    const Jacobian jr = RowJacobian(cr, rows[r].point);
    for (int c = 0; c <= r; ++c) {
      const SubstepConstraint& cc = constraints[rows[c].constraint];
      k[r * m + c] = k[c * m + r] = Coupling(cr, jr, cc, RowJacobian(cc, rows[c].point));
    }
  }
  for (int r = 0; r < m; ++r) {
    s->sparse_begin.push_back(static_cast<std::uint32_t>(s->sparse_column.size()));
    for (int c = 0; c < m; ++c) {
      if (k[r * m + c] == 0.0) continue;
      s->sparse_column.push_back(static_cast<std::uint32_t>(c));
      s->sparse_value.push_back(k[r * m + c]);
    }
    s->sparse_end.push_back(static_cast<std::uint32_t>(s->sparse_column.size()));
  }
}

// First guesses of the island's row states, from the impulses warm starting brought: the
// normals that pushed are free, friction is free within μ times its contact's normal impulses;
// nothing pushes out.
void AddFirstGuesses(std::span<const SubstepConstraint> constraints, const DirectSolver::Island& island,
                     DirectSolver* s) {
  const DirectSolver::Row* rows = s->rows.data() + island.first_row;
  for (std::uint32_t r = 0; r < island.rows; ++r) {
    const SubstepConstraint& sc = constraints[rows[r].constraint];
    double limit = 0.0;
    if (rows[r].point < 0) {
      for (int p = 0; p < sc.point_count; ++p) limit += sc.points[p].normal_impulse;
      limit *= sc.friction;
    }
    const bool pushed = rows[r].point < 0 || sc.points[rows[r].point].normal_impulse > 0.0;
    s->bound.push_back(pushed ? kFree : kAtLower);
    s->push_bound.push_back(kAtLower);
    s->last_limit.push_back(limit);
  }
}

// The contacts solved directly this step, in pair order, for the next step's hand-off.
void RecordDirectContacts(std::span<const SubstepConstraint> constraints, DirectSolver* s) {
  s->direct_contact.assign(constraints.size(), 0);
  for (const DirectSolver::Row& row : s->rows) s->direct_contact[row.constraint] = 1;
  for (std::uint32_t c = 0; c < constraints.size(); ++c) {
    if (s->direct_contact[c]) s->pairs.push_back({constraints[c].a, constraints[c].b});
  }
}

// Factor slots: one per island for the velocities, one for the push-out, none valid yet.
void ResetFactorSlots(DirectSolver* s) {
  s->factor.resize(2 * s->islands.size());
  s->factor_rows.resize(2 * s->islands.size());
  s->factor_valid.assign(2 * s->islands.size(), 0);
  for (std::vector<std::uint32_t>& slot : s->factor_rows) slot.clear();
}

bool BuildIslands(std::span<const SubstepConstraint> constraints, std::span<const BodyInfo> infos,
                  DirectSolver* s, bool any_heavy) {
  ClearIslands(s);
  if (!any_heavy) return false;  // the common case: nothing more to do, nothing allocated
  FlagHeavyIslands(constraints, infos, s);
  const ContactGroups groups = GroupByIsland(constraints, s);
  for (std::size_t i = 0; i < groups.count.size(); ++i) {
    if (groups.rows[i] > static_cast<std::uint32_t>(kDirectMaxRows)) continue;  // too large for a dense solve
    DirectSolver::Island island;
    AddRows(constraints, groups.Group(i), s, &island);
    AddBodies(constraints, groups.Group(i), s, &island);
    AddMatrix(constraints, s, &island);
    AddFirstGuesses(constraints, island, s);
    s->islands.push_back(island);
  }
  RecordDirectContacts(constraints, s);
  ResetFactorSlots(s);
  return !s->islands.empty();
}

// A contact solved directly last step but left to Gauss-Seidel now (its island grew past the
// limit, or lost its heavy pair) starts from zero: the exact solve may have left it an impulse
// that only balanced against contacts that are gone (a heavy body stopped within one substep, a
// wedge), and Gauss-Seidel warm started with it would launch the bodies.
void HandOff(std::span<SubstepConstraint> constraints, DirectSolver* s) {
  std::size_t j = 0;
  for (std::uint32_t c = 0; c < constraints.size() && j < s->previous_pairs.size(); ++c) {
    SubstepConstraint& sc = constraints[c];
    const BodyPair pair{sc.a, sc.b};
    while (j < s->previous_pairs.size() && s->previous_pairs[j] < pair) ++j;
    if (j == s->previous_pairs.size() || !(s->previous_pairs[j] == pair)) continue;
    if (!s->direct_contact.empty() && s->direct_contact[c]) continue;
    for (int k = 0; k < sc.point_count; ++k) sc.points[k].normal_impulse = sc.points[k].tangent_impulse = 0.0;
  }
}

}  // namespace

bool PrepareDirectSolve(std::span<SubstepConstraint> constraints, std::span<const BodyInfo> infos,
                        DirectSolver* s, bool any_heavy) {
  assert(any_heavy == std::any_of(constraints.begin(), constraints.end(),
                                  [&](const SubstepConstraint& sc) { return IsHeavyPair(sc, infos); }));
  s->previous_pairs.swap(s->pairs);
  s->pairs.clear();
  const bool any = BuildIslands(constraints, infos, s, any_heavy);
  if (!s->previous_pairs.empty()) HandOff(constraints, s);
  return any;
}

void SolveDirect(DirectSolver* s, std::span<SubstepConstraint> constraints, std::span<BodyState> states,
                 const StepStart& start, double inv_h) {
  for (std::size_t i = 0; i < s->islands.size(); ++i) SolveIsland(s, i, constraints, states, start, inv_h);
}

void PushOutDirect(DirectSolver* s, std::span<SubstepConstraint> constraints, std::span<const BodyState> states,
                   const StepStart& start, PushVelocities push, double push_out_rate, double max_push_out_speed,
                   double linear_slop) {
  for (std::size_t index = 0; index < s->islands.size(); ++index) {
    const DirectSolver::Island& island = s->islands[index];
    const int normals = static_cast<int>(island.normal_rows);
    const DirectSolver::Row* rows = s->rows.data() + island.first_row;
    std::uint8_t* bound = s->push_bound.data() + island.first_row;
    s->x.assign(normals, 0.0), s->q.resize(normals), s->lo.assign(normals, 0.0), s->hi.resize(normals);
    s->limit.resize(normals);  // here: Gauss-Seidel's push impulses, to restore on a failure
    // Rows overlapping beyond the slop push apart at the push-out speed; the others take no part
    // (held at zero), as in Gauss-Seidel's push-out. Gauss-Seidel's push impulses on these rows
    // come off first: the answer replaces them.
    bool any = false;
    for (int i = 0; i < normals; ++i) {
      SubstepConstraint& sc = constraints[rows[i].constraint];
      SubstepPoint& p = sc.points[rows[i].point];
      ApplyImpulse(sc, p.anchor_a, p.anchor_b, -p.push_impulse * sc.normal, push.linear[sc.a],
                   push.angular[sc.a], push.linear[sc.b], push.angular[sc.b]);
      s->limit[i] = p.push_impulse;
      p.push_impulse = 0.0;
      const double separation = CurrentSeparation(sc, p, states, start);
      const bool overlapping = separation < -linear_slop;
      s->q[i] = overlapping ? -std::min(push_out_rate * -(separation + linear_slop), max_push_out_speed) : 0.0;
      s->hi[i] = overlapping ? kInfinity : 0.0;
      any = any || overlapping;
    }
    for (int i = 0; !any && i < normals; ++i) s->x[i] = s->limit[i];  // nothing to push: as it was
    for (int i = 0; any && i < normals; ++i) {
      const SubstepConstraint& sc = constraints[rows[i].constraint];
      if (s->hi[i] == 0.0) continue;
      const Jacobian j = RowJacobian(sc, rows[i].point);
      s->q[i] += Dot(j.d, push.linear[sc.b] - push.linear[sc.a]) + j.rb * push.angular[sc.b] -
                 j.ra * push.angular[sc.a];
    }
    BoxQp qp(s->matrix.data() + island.matrix, normals, static_cast<int>(island.rows), kProximal,
             SparseRows(s, island), s, s->islands.size() + index);
    if (any && !qp.Solve(s->q.data(), s->lo.data(), s->hi.data(), bound, s->x.data())) {
      std::fill(bound, bound + normals, kAtLower);
      for (int i = 0; i < normals; ++i) s->x[i] = s->limit[i];  // Gauss-Seidel's push stands
    }
    for (int i = 0; i < normals; ++i) {
      if (s->x[i] == 0.0) continue;
      SubstepConstraint& sc = constraints[rows[i].constraint];
      SubstepPoint& p = sc.points[rows[i].point];
      p.push_impulse = s->x[i];
      ApplyImpulse(sc, p.anchor_a, p.anchor_b, s->x[i] * sc.normal, push.linear[sc.a], push.angular[sc.a],
                   push.linear[sc.b], push.angular[sc.b]);
    }
  }
}

}  // namespace engine::detail
