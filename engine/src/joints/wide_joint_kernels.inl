// The wide passes over revolute joints' point rows (JointBlock), included after
// wide_turning_kernels.inl (Motion, GatherMotion, ScatterMotion). Each follows JointSolver's
// arithmetic for a revolute joint's point (ApplyPoint, PointVelocity, Solve22, joint_solver.cpp)
// operation by operation, with K and 1 / det K worked out once per frame (WideJoints::LoadFrames):
// keep them in step.

// The lanes' fields of a block that every pass reads.
struct JointLanes {
  Lanes ma, mb, ia, ib, rax, ray, rbx, rby, k11, k12, k22, inv_det;
  unsigned moving_a, moving_b;  ///< lanes whose body moves: inverse mass or inertia not zero
};

[[gnu::always_inline]] inline JointLanes LoadJoint(const JointBlock& k, int o) {
  JointLanes j{Lanes::Load(k.inv_mass_a + o),    Lanes::Load(k.inv_mass_b + o), Lanes::Load(k.inv_inertia_a + o),
               Lanes::Load(k.inv_inertia_b + o), Lanes::Load(k.arm_a_x + o),    Lanes::Load(k.arm_a_y + o),
               Lanes::Load(k.arm_b_x + o),       Lanes::Load(k.arm_b_y + o),    Lanes::Load(k.k11 + o),
               Lanes::Load(k.k12 + o),           Lanes::Load(k.k22 + o),        Lanes::Load(k.inv_det + o),
               0u,                               0u};
  const Lanes zero(0.0);
  j.moving_a = Bits((j.ma != zero) | (j.ia != zero));
  j.moving_b = Bits((j.mb != zero) | (j.ib != zero));
  return j;
}

// PointVelocity: (b.v + Cross(b.w, r_b)) − (a.v + Cross(a.w, r_a)).
[[gnu::always_inline]] inline void PointVelocityLanes(const JointLanes& j, const Motion<Lanes>& a, const Motion<Lanes>& b, Lanes* x,
                                                      Lanes* y) {
  *x = (b.vx + -b.w * j.rby) - (a.vx + -a.w * j.ray);
  *y = (b.vy + b.w * j.rbx) - (a.vy + a.w * j.rax);
}

// Solve22: K⁻¹·v.
[[gnu::always_inline]] inline void Solve22Lanes(const JointLanes& j, Lanes vx, Lanes vy, Lanes* x, Lanes* y) {
  *x = j.inv_det * (j.k22 * vx - j.k12 * vy);
  *y = j.inv_det * (j.k11 * vy - j.k12 * vx);
}

// ApplyPoint.
[[gnu::always_inline]] inline void ApplyPointLanes(const JointLanes& j, Lanes ix, Lanes iy, Motion<Lanes>* a, Motion<Lanes>* b) {
  a->vx = a->vx - j.ma * ix;
  a->vy = a->vy - j.ma * iy;
  a->w = a->w - j.ia * (j.rax * iy - j.ray * ix);
  b->vx = b->vx + j.mb * ix;
  b->vy = b->vy + j.mb * iy;
  b->w = b->w + j.ib * (j.rbx * iy - j.rby * ix);
}

// The warm start: last substep's point impulse, again.
void JointWarmStartBlocks(JointBlock* blocks, std::size_t count, BodyState* states) {
  for (std::size_t i = 0; i < count; ++i) {
    JointBlock& k = blocks[i];
    for (int o = 0; o < kBlockLanes; o += Lanes::kCount) {
      const JointLanes j = LoadJoint(k, o);
      Motion<Lanes> a = GatherMotion<Lanes>(states, k.a + o), b = GatherMotion<Lanes>(states, k.b + o);
      ApplyPointLanes(j, Lanes::Load(k.impulse_x + o), Lanes::Load(k.impulse_y + o), &a, &b);
      ScatterMotion(states, k.a + o, a, j.moving_a);
      ScatterMotion(states, k.b + o, b, j.moving_b);
    }
  }
}

// One Gauss-Seidel pass over the point rows (JointSolver::Solve's revolute case).
void JointSolveBlocks(JointBlock* blocks, std::size_t count, BodyState* states, double inv_h_scalar) {
  const Lanes inv_h(inv_h_scalar);
  for (std::size_t i = 0; i < count; ++i) {
    JointBlock& k = blocks[i];
    for (int o = 0; o < kBlockLanes; o += Lanes::kCount) {
      const JointLanes j = LoadJoint(k, o);
      Motion<Lanes> a = GatherMotion<Lanes>(states, k.a + o), b = GatherMotion<Lanes>(states, k.b + o);
      Lanes vx, vy;
      PointVelocityLanes(j, a, b, &vx, &vy);
      vx = vx + inv_h * Lanes::Load(k.drift_x + o);
      vy = vy + inv_h * Lanes::Load(k.drift_y + o);
      Lanes ix, iy;
      Solve22Lanes(j, vx, vy, &ix, &iy);
      ix = -ix;
      iy = -iy;
      (Lanes::Load(k.impulse_x + o) + ix).Store(k.impulse_x + o);
      (Lanes::Load(k.impulse_y + o) + iy).Store(k.impulse_y + o);
      ApplyPointLanes(j, ix, iy, &a, &b);
      ScatterMotion(states, k.a + o, a, j.moving_a);
      ScatterMotion(states, k.b + o, b, j.moving_b);
    }
  }
}

// One push-out pass over the point rows through the push velocities (JointSolver::PushOut's
// revolute case): `rate` of the separation per second.
void JointPushOutBlocks(JointBlock* blocks, std::size_t count, Vec2* push, double* push_angular, double rate_scalar) {
  if (count == 0) return;
  double* push_linear = &push[0].x;
  const Lanes minus_rate(-rate_scalar);
  for (std::size_t i = 0; i < count; ++i) {
    JointBlock& k = blocks[i];
    for (int o = 0; o < kBlockLanes; o += Lanes::kCount) {
      const JointLanes j = LoadJoint(k, o);
      Motion<Lanes> a, b;
      Gather(push_linear, kVec2Stride, k.a + o, &a.vx, &a.vy);
      Gather(push_linear, kVec2Stride, k.b + o, &b.vx, &b.vy);
      a.w = GatherOne(push_angular, 1, k.a + o);
      b.w = GatherOne(push_angular, 1, k.b + o);
      Lanes vx, vy;
      PointVelocityLanes(j, a, b, &vx, &vy);
      vx = minus_rate * Lanes::Load(k.separation_x + o) - vx;
      vy = minus_rate * Lanes::Load(k.separation_y + o) - vy;
      Lanes ix, iy;
      Solve22Lanes(j, vx, vy, &ix, &iy);
      ApplyPointLanes(j, ix, iy, &a, &b);
      Scatter(push_linear, kVec2Stride, k.a + o, a.vx, a.vy, j.moving_a);
      Scatter(push_linear, kVec2Stride, k.b + o, b.vx, b.vy, j.moving_b);
      ScatterOne(push_angular, 1, k.a + o, a.w, j.moving_a);
      ScatterOne(push_angular, 1, k.b + o, b.w, j.moving_b);
    }
  }
}
