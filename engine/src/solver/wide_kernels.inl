// The wide passes' one source, included by each width's file after it defines `Lanes`: a type of
// L doubles side by side with +, −, ×, comparisons to masks, Select, MaxOf and MinOf, and gathers
// and scatters of the bodies' Vec2s. Everything here has internal linkage (the including file's
// anonymous namespace), so the AVX2 file's copy never stands in for another's.
//
// Each pass follows its one-at-a-time counterpart in substep_passes.cpp operation by operation:
// keep them in step. std::max(x, 0.0) is (x < 0 ? 0 : x), std::min(x, m) is (m < x ? m : x) and
// Clamp(v, lo, hi) is (v < lo ? lo : (v > hi ? hi : v)). The lanes take them with x86's max and
// min, MaxOf(a, b) = (a > b ? a : b) and MinOf(a, b) = (a < b ? a : b), one instruction each
// instead of a comparison and a blend, with the same answers, NaN and signed zeros included
// (Clamp's where hi >= 0, as a friction bound is); and x + −y as x − y, which IEEE rounds alike.
// Fewer vector operations a block let the next block's start sooner (wide_twin.inl).

// The doubles between one body's state and the next's, and from one Vec2 to the next.
constexpr std::size_t kStateStride = sizeof(BodyState) / sizeof(double);
constexpr std::size_t kVec2Stride = 2;
static_assert(sizeof(BodyState) == 6 * sizeof(double) && sizeof(Vec2) == 2 * sizeof(double));
constexpr std::size_t kVelocityOffset = 2;  // BodyState::velocity after position

// std::max(x, 0.0)
[[gnu::always_inline]] inline Lanes Max0(Lanes x) { return MaxOf(Lanes(0.0), x); }  // (0 > x ? 0 : x)

// The separation now of the lanes' contacts (CurrentSeparation), from the bodies' moves since
// the step's start (MeasureMoves).
[[gnu::always_inline]] inline Lanes SeparationNow(const LinearBlock& k, int o, const Vec2* moved, Lanes nx,
                                                  Lanes ny) {
  Lanes max, may, mbx, mby;
  Gather(&moved[0].x, kVec2Stride, k.a + o, &max, &may);
  Gather(&moved[0].x, kVec2Stride, k.b + o, &mbx, &mby);
  return Lanes::Load(k.base_separation + o) + ((mbx - max) * nx + (mby - may) * ny);
}

// Which lanes move their body: inverse mass not zero (a static or kinematic body is never
// written, as WriteBack).
[[gnu::always_inline]] inline unsigned Moving(const double* inv_mass) {
  return Bits(Lanes::Load(inv_mass) != Lanes(0.0));
}

void WarmStartBlocks(LinearBlock* blocks, std::size_t count, BodyState* states) {
  if (count == 0) return;  // no contacts: the bodies' arrays may be empty
  constexpr double kSliding = 1.0 - 1e-9;  // as WarmImpulse
  double* velocities = &states[0].position.x + kVelocityOffset;
  for (std::size_t i = 0; i < count; ++i) {
    LinearBlock& k = blocks[i];
    for (int o = 0; o < kBlockLanes; o += Lanes::kCount) {
      Lanes vax, vay, vbx, vby;
      Gather(velocities, kStateStride, k.a + o, &vax, &vay);
      Gather(velocities, kStateStride, k.b + o, &vbx, &vby);
      const Lanes nx = Lanes::Load(k.normal_x + o), ny = Lanes::Load(k.normal_y + o);
      const Lanes tx = -ny, ty = nx;
      const Lanes ni = Lanes::Load(k.normal_impulse + o);
      Lanes ti = Lanes::Load(k.tangent_impulse + o);
      const Lanes slide = ti * ((vbx - vax) * tx + (vby - vay) * ty);
      const Lanes edge = (Lanes(kSliding) * Lanes::Load(k.friction + o)) * ni;
      ti = Select((slide > Lanes(0.0)) & (Abs(ti) >= edge), Lanes(0.0), ti);
      ti.Store(k.tangent_impulse + o);
      const Lanes ix = ni * nx + ti * tx, iy = ni * ny + ti * ty;
      const Lanes ima = Lanes::Load(k.inv_mass_a + o), imb = Lanes::Load(k.inv_mass_b + o);
      vax = vax - ima * ix;
      vay = vay - ima * iy;
      vbx = vbx + imb * ix;
      vby = vby + imb * iy;
      Scatter(velocities, kStateStride, k.a + o, vax, vay, Moving(k.inv_mass_a + o));
      Scatter(velocities, kStateStride, k.b + o, vbx, vby, Moving(k.inv_mass_b + o));
    }
  }
}

void SolveBlocks(LinearBlock* blocks, std::size_t count, BodyState* states, const Vec2* moved,
                 double inv_h_scalar) {
  if (count == 0) return;  // no contacts: the bodies' arrays may be empty
  double* velocities = &states[0].position.x + kVelocityOffset;
  const Lanes inv_h(inv_h_scalar);
  for (std::size_t i = 0; i < count; ++i) {
    LinearBlock& k = blocks[i];
    for (int o = 0; o < kBlockLanes; o += Lanes::kCount) {
      const Lanes nx = Lanes::Load(k.normal_x + o), ny = Lanes::Load(k.normal_y + o);
      const Lanes min_vn = -Max0(SeparationNow(k, o, moved, nx, ny)) * inv_h;
      Lanes vax, vay, vbx, vby;
      Gather(velocities, kStateStride, k.a + o, &vax, &vay);
      Gather(velocities, kStateStride, k.b + o, &vbx, &vby);
      const Lanes ima = Lanes::Load(k.inv_mass_a + o), imb = Lanes::Load(k.inv_mass_b + o);
      const Lanes mass = Lanes::Load(k.normal_mass + o);

      const Lanes vn = (vbx - vax) * nx + (vby - vay) * ny;
      const Lanes normal = Lanes::Load(k.normal_impulse + o);
      const Lanes new_normal = Max0(normal + mass * (min_vn - vn));
      const Lanes dn = new_normal - normal;
      new_normal.Store(k.normal_impulse + o);
      const Lanes sa = ima * dn, sb = imb * dn;
      vax = vax - sa * nx;
      vay = vay - sa * ny;
      vbx = vbx + sb * nx;
      vby = vby + sb * ny;

      // Coulomb friction, with the effective mass of any direction.
      const Lanes tx = -ny, ty = nx;
      const Lanes vt = (vbx - vax) * tx + (vby - vay) * ty;
      const Lanes max_friction = Lanes::Load(k.friction + o) * new_normal;
      const Lanes tangent = Lanes::Load(k.tangent_impulse + o);
      const Lanes free = tangent - mass * vt;
      // Clamp(free, -max, max) as (-max > m ? -max : m), m = (max < free ? max : free): the same
      // for max >= 0 (friction and normal impulse are) or NaN.
      const Lanes new_tangent = MaxOf(-max_friction, MinOf(max_friction, free));
      const Lanes dt = new_tangent - tangent;
      new_tangent.Store(k.tangent_impulse + o);
      const Lanes ta = ima * dt, tb = imb * dt;
      vax = vax - ta * tx;
      vay = vay - ta * ty;
      vbx = vbx + tb * tx;
      vby = vby + tb * ty;
      Scatter(velocities, kStateStride, k.a + o, vax, vay, Moving(k.inv_mass_a + o));
      Scatter(velocities, kStateStride, k.b + o, vbx, vby, Moving(k.inv_mass_b + o));
    }
  }
}

void PushOutBlocks(LinearBlock* blocks, std::size_t count, const Vec2* moved, Vec2* push, double push_out_rate,
                   double max_push_out_speed, double linear_slop) {
  if (count == 0) return;  // no contacts: the bodies' arrays may be empty
  double* push_velocities = &push[0].x;
  const Lanes rate(push_out_rate), max_speed(max_push_out_speed), slop(linear_slop);
  for (std::size_t i = 0; i < count; ++i) {
    LinearBlock& k = blocks[i];
    for (int o = 0; o < kBlockLanes; o += Lanes::kCount) {
      const Lanes nx = Lanes::Load(k.normal_x + o), ny = Lanes::Load(k.normal_y + o);
      const Lanes s = SeparationNow(k, o, moved, nx, ny);
      // Overlap within the slop is left alone: a block with none past it is passed over (in a
      // resting pile, always), and in the others those lanes write back the velocities they read
      // (a store a lane by whether it pushed was mispredicted in a settling pour).
      const Mask within_slop = s >= -slop;
      if (Bits(within_slop) == (1u << Lanes::kCount) - 1) continue;
      const Lanes wanted = rate * -(s + slop);
      const Lanes target = MinOf(max_speed, wanted);  // (max_speed < wanted ? max_speed : wanted)
      Lanes vax, vay, vbx, vby;
      Gather(push_velocities, kVec2Stride, k.a + o, &vax, &vay);
      Gather(push_velocities, kVec2Stride, k.b + o, &vbx, &vby);
      const Lanes vn = (vbx - vax) * nx + (vby - vay) * ny;
      const Lanes dp = Max0(Lanes::Load(k.normal_mass + o) * (target - vn));
      const Lanes sa = Lanes::Load(k.inv_mass_a + o) * dp, sb = Lanes::Load(k.inv_mass_b + o) * dp;
      vax = Select(within_slop, vax, vax - sa * nx);
      vay = Select(within_slop, vay, vay - sa * ny);
      vbx = Select(within_slop, vbx, vbx + sb * nx);
      vby = Select(within_slop, vby, vby + sb * ny);
      Scatter(push_velocities, kVec2Stride, k.a + o, vax, vay, Moving(k.inv_mass_a + o));
      Scatter(push_velocities, kVec2Stride, k.b + o, vbx, vby, Moving(k.inv_mass_b + o));
    }
  }
}
