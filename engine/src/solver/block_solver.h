// The two-point block solver (Catto, Box2D 2.x "block solver", 2008): both normal impulses of a
// two-point manifold found together, as a 2×2 linear complementarity problem, so that a box
// resting on its face gets no spurious spin from solving one corner before the other. Internal.
#pragma once

namespace engine::detail {

/// The normal-velocity response of two points: Δvn = K·Δimpulse, K symmetric positive definite.
struct TwoPointMass {
  double k11, k12, k22;
};

/// Given accumulated impulses (a1, a2) ≥ 0, the normal velocities now (vn1, vn2) and the
/// targets (t1, t2), the new accumulated impulses x ≥ 0 with vn + K·(x − a) ≥ t and
/// complementarity (x_i > 0 only where vn_i reaches t_i exactly). Returns false when K is too
/// ill-conditioned (the two points nearly coincide): solve them one at a time then.
bool SolveTwoPoints(const TwoPointMass& k, double a1, double a2, double vn1, double vn2, double t1,
                    double t2, double* x1, double* x2);

}  // namespace engine::detail
