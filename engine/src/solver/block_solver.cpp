// The four cases of the 2×2 complementarity problem, tried in order: both points pushing, only
// the first, only the second, neither.
#include "solver/block_solver.h"

namespace engine::detail {

bool SolveTwoPoints(const TwoPointMass& k, double a1, double a2, double vn1, double vn2, double t1,
                    double t2, double* x1, double* x2) {
  // Box2D's bound: beyond this condition number the 2×2 solve loses too much precision.
  constexpr double kMaxCondition = 1000.0;
  const double det = k.k11 * k.k22 - k.k12 * k.k12;
  if (!(k.k11 * k.k11 < kMaxCondition * det)) return false;

  // With x the new impulses: vn' = K·x + b, b = vn − t − K·a.
  const double b1 = vn1 - t1 - (k.k11 * a1 + k.k12 * a2);
  const double b2 = vn2 - t2 - (k.k12 * a1 + k.k22 * a2);

  // Both pushing: K·x = −b. Multiplied by reciprocals, which the lanes keep for the step (K is
  // fixed for it, WideTurningConstraints), not divided: a division in every pass held up the
  // lanes' solve (the turning pyramid of base 40 3.705 -> 3.476 ms/step with these and K packed).
  const double inv_det = 1.0 / det;
  double y1 = (-k.k22 * b1 + k.k12 * b2) * inv_det;
  double y2 = (k.k12 * b1 - k.k11 * b2) * inv_det;
  if (y1 >= 0.0 && y2 >= 0.0) return *x1 = y1, *x2 = y2, true;
  // Only the first: x2 = 0, vn1' = 0, and vn2' ≥ 0.
  y1 = -b1 * (1.0 / k.k11);
  if (y1 >= 0.0 && k.k12 * y1 + b2 >= 0.0) return *x1 = y1, *x2 = 0.0, true;
  // Only the second.
  y2 = -b2 * (1.0 / k.k22);
  if (y2 >= 0.0 && k.k12 * y2 + b1 >= 0.0) return *x1 = 0.0, *x2 = y2, true;
  // Neither: both already separate fast enough.
  if (b1 >= 0.0 && b2 >= 0.0) return *x1 = 0.0, *x2 = 0.0, true;
  return false;  // no case fits (rounding): fall back to one at a time
}

}  // namespace engine::detail
