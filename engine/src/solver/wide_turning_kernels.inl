// The wide passes over turning contacts (TurningBlock), included after wide_kernels.inl. Each
// follows its one-at-a-time counterpart in substep_passes.cpp (WarmStartAll, SolveContacts with
// SolveTurning and SolveTwoPoints, PushOut for an angular SubstepConstraint) operation by
// operation: keep them in step. A lane's second point is worked on in every lane and kept only
// where the contact has two (Select), so a one-point contact's bodies see exactly one point. A
// block whose lanes all have one point (circles) skips its second points whole, never reading
// them (they are stored apart, WideTurningConstraints::second_points).

constexpr std::size_t kOmegaOffset = 5;  // BodyState::angular_velocity after position, velocity, angle
static_assert(sizeof(Rot) == 2 * sizeof(double));

// The passes' arithmetic below is written once for lanes `L`: a block's (Lanes, its fields read
// through TurningBlock) or two blocks' (Twin, through TwinBlock).
template <typename L>
using MaskFor = decltype(L(0.0) < L(0.0));

// The mask of the lanes whose bits are set.
template <typename L>
MaskFor<L> LanesOf(unsigned bits) {
  if constexpr (std::is_same_v<L, Twin>) {
    return TwinMaskOf(bits);
  } else {
    return MaskOf(bits);
  }
}

template <typename L>
MaskFor<L> NoLanes() {
  return LanesOf<L>(0);
}

// A body's velocity and angular velocity, as the passes work on them.
template <typename L>
struct Motion {
  L vx, vy, w;
  /// The body's angle, where its state is read and written as a row (kTwinRows): written back
  /// as read. Not read otherwise.
  L angle;
};

// Twins read and write the bodies' states in rows where they are one 512-bit vector (GatherRows).
template <typename L>
inline constexpr bool kRowsFor = kTwinRows && std::is_same_v<L, Twin>;

static_assert(offsetof(BodyState, angle) == (kVelocityOffset + 2) * sizeof(double) &&
              offsetof(BodyState, angular_velocity) == kOmegaOffset * sizeof(double));

template <typename L, typename Index>
[[gnu::always_inline]] inline Motion<L> GatherMotion(BodyState* states, Index index) {
  Motion<L> m;
  if constexpr (kRowsFor<L>) {
    GatherRows(&states[0].position.x + kVelocityOffset, kStateStride, index, &m.vx, &m.vy, &m.angle, &m.w);
  } else {
    Gather(&states[0].position.x + kVelocityOffset, kStateStride, index, &m.vx, &m.vy);
    m.w = GatherOne(&states[0].position.x + kOmegaOffset, kStateStride, index);
    m.angle = L(0.0);
  }
  return m;
}

template <typename L, typename Index>
[[gnu::always_inline]] inline void ScatterMotion(BodyState* states, Index index, const Motion<L>& m, unsigned write) {
  if constexpr (kRowsFor<L>) {
    ScatterRows(&states[0].position.x + kVelocityOffset, kStateStride, index, m.vx, m.vy, m.angle, m.w, write);
  } else {
    Scatter(&states[0].position.x + kVelocityOffset, kStateStride, index, m.vx, m.vy, write);
    ScatterOne(&states[0].position.x + kOmegaOffset, kStateStride, index, m.w, write);
  }
}

template <typename L>
[[gnu::always_inline]] inline Motion<L> Select(MaskFor<L> m, const Motion<L>& if_set, const Motion<L>& if_clear) {
  // The angle is the same in both: no pass changes it.
  return {Select(m, if_set.vx, if_clear.vx), Select(m, if_set.vy, if_clear.vy), Select(m, if_set.w, if_clear.w),
          if_clear.angle};
}

// One point's lanes: its anchors and the fields the passes read.
template <typename L>
struct PointLanes {
  L rax, ray, rbx, rby;
  L base_separation, normal_mass, tangent_mass, normal_impulse, tangent_impulse;
};

template <typename L, typename Point>
[[gnu::always_inline]] inline PointLanes<L> LoadPoint(const Point& p, int o) {
  return {L::Load(p.anchor_a_x + o),   L::Load(p.anchor_a_y + o),      L::Load(p.anchor_b_x + o),
          L::Load(p.anchor_b_y + o),   L::Load(p.base_separation + o), L::Load(p.normal_mass + o),
          L::Load(p.tangent_mass + o), L::Load(p.normal_impulse + o),  L::Load(p.tangent_impulse + o)};
}

// The lanes' fields of a block that every pass reads.
template <typename L>
struct PairLanes {
  L nx, ny, ima, imb, iia, iib;
  unsigned moving_a, moving_b;  ///< lanes whose body moves (WriteBack)
  MaskFor<L> two;               ///< lanes with two points
};

template <typename L, typename Block>
[[gnu::always_inline]] inline PairLanes<L> LoadPair(const Block& k, int o) {
  // Which lanes move (Moving's answer), from the masses loaded here: one comparison for a Twin's
  // eight lanes.
  const L ima = L::Load(k.inv_mass_a + o), imb = L::Load(k.inv_mass_b + o);
  return {L::Load(k.normal_x + o),       L::Load(k.normal_y + o),       ima,
          imb,                           L::Load(k.inv_inertia_a + o),  L::Load(k.inv_inertia_b + o),
          Bits(ima != L(0.0)),           Bits(imb != L(0.0)),           L::Load(k.two_points + o) != L(0.0)};
}

// Dot(RelativeVelocity(p, a, b), d): (b.v + Cross(b.w, r_b)) − (a.v + Cross(a.w, r_a)) along d.
template <typename L>
[[gnu::always_inline]] inline L RelativeAlong(const PointLanes<L>& p, const Motion<L>& a, const Motion<L>& b, L dx,
                                              L dy) {
  // x + −w·r is x − w·r: IEEE negation and subtraction round alike.
  const L rx = (b.vx - b.w * p.rby) - (a.vx - a.w * p.ray);
  const L ry = (b.vy + b.w * p.rbx) - (a.vy + a.w * p.rax);
  return rx * dx + ry * dy;
}

// ApplyImpulse(sc, p, impulse, a, b).
template <typename L>
[[gnu::always_inline]] inline void ApplyAt(const PairLanes<L>& c, const PointLanes<L>& p, L ix, L iy, Motion<L>* a,
                                           Motion<L>* b) {
  a->vx = a->vx - c.ima * ix;
  a->vy = a->vy - c.ima * iy;
  a->w = a->w - c.iia * (p.rax * iy - p.ray * ix);
  b->vx = b->vx + c.imb * ix;
  b->vy = b->vy + c.imb * iy;
  b->w = b->w + c.iib * (p.rbx * iy - p.rby * ix);
}

// The bodies' centres and turns, for the separations now (CurrentSeparation, angular).
template <typename L>
struct PlaceLanes {
  L mx, my;              ///< how far b's centre has moved from a's since the step's start
  L tac, tas, tbc, tbs;  ///< each body's turn since then
};

// `moved`: each body's move since the step's start (MeasureMoves); `turned` (kTurns) each
// body's turn since then.
template <typename L, bool kTurns, typename Block>
[[gnu::always_inline]] inline PlaceLanes<L> GatherPlaces(const Block& k, int o, const Vec2* moved, const Rot* turned) {
  L max, may, mbx, mby;
  PlaceLanes<L> q;
  Gather(&moved[0].x, kVec2Stride, k.a + o, &max, &may);
  Gather(&moved[0].x, kVec2Stride, k.b + o, &mbx, &mby);
  if constexpr (kTurns) {
    const double* turns = &turned[0].c;
    Gather(turns, kVec2Stride, k.a + o, &q.tac, &q.tas);
    Gather(turns, kVec2Stride, k.b + o, &q.tbc, &q.tbs);
  }
  q.mx = mbx - max;
  q.my = mby - may;
  return q;
}

// base + Dot((moved + Rotate(turn_b, r_b)) − Rotate(turn_a, r_a), n); without turns (kTurns
// false: no body's turn moves its points), base + Dot((moved + r_b) − r_a, n).
template <bool kTurns, typename L>
[[gnu::always_inline]] inline L SeparationAt(const PlaceLanes<L>& q, const PointLanes<L>& p, const PairLanes<L>& c) {
  if constexpr (kTurns) {
    const L x = (q.mx + (q.tbc * p.rbx - q.tbs * p.rby)) - (q.tac * p.rax - q.tas * p.ray);
    const L y = (q.my + (q.tbs * p.rbx + q.tbc * p.rby)) - (q.tas * p.rax + q.tac * p.ray);
    return p.base_separation + (x * c.nx + y * c.ny);
  } else {
    const L x = (q.mx + p.rbx) - p.rax;
    const L y = (q.my + p.rby) - p.ray;
    return p.base_separation + (x * c.nx + y * c.ny);
  }
}

// One block's lanes [o, o + L::kCount) of TurningWarmStartBlocks (or two blocks', Twin).
template <typename L, typename Block, typename Second>
[[gnu::always_inline]] inline void WarmStartTurningLanes(Block& k, Second& second, int o, BodyState* states) {
  constexpr double kSliding = 1.0 - 1e-9;  // as WarmImpulse
  const PairLanes<L> c = LoadPair<L>(k, o);
  const L tx = -c.ny, ty = c.nx;
  const L edge_scale = L(kSliding) * L::Load(k.friction + o);
  Motion<L> a = GatherMotion<L>(states, k.a + o), b = GatherMotion<L>(states, k.b + o);
  const int points = Bits(c.two) != 0 ? 2 : 1;  // circles have one: their second is skipped whole
  for (int point = 0; point < points; ++point) {
    const PointLanes<L> p = point == 0 ? LoadPoint<L>(k.first, o) : LoadPoint<L>(second, o);
    const L slide = p.tangent_impulse * RelativeAlong(p, a, b, tx, ty);
    const L ti = Select((slide > L(0.0)) & (Abs(p.tangent_impulse) >= edge_scale * p.normal_impulse), L(0.0),
                        p.tangent_impulse);
    const L ix = p.normal_impulse * c.nx + ti * tx, iy = p.normal_impulse * c.ny + ti * ty;
    Motion<L> a2 = a, b2 = b;
    ApplyAt(c, p, ix, iy, &a2, &b2);
    if (point == 0) {
      ti.Store(k.first.tangent_impulse + o);
      a = a2, b = b2;
    } else {
      Select(c.two, ti, p.tangent_impulse).Store(second.tangent_impulse + o);
      a = Select<L>(c.two, a2, a), b = Select<L>(c.two, b2, b);
    }
  }
  ScatterMotion(states, k.a + o, a, c.moving_a);
  ScatterMotion(states, k.b + o, b, c.moving_b);
}

void TurningWarmStartBlocks(TurningBlock* blocks, TurningSecondLanes* seconds, std::size_t count, BodyState* states) {
  for (std::size_t i = 0; i < count; ++i) {
    for (int o = 0; o < kBlockLanes; o += Lanes::kCount) WarmStartTurningLanes<Lanes>(blocks[i], seconds[i], o, states);
  }
}

// How many blocks two runs take side by side (Twin): as many as the shorter has.
inline std::size_t TwinCount(TurningRun one, TurningRun two) { return one.count < two.count ? one.count : two.count; }

// The runs' first TwinCount blocks side by side, then the rest of each on its own.
void TurningWarmStartTwin(TurningRun one, TurningRun two, BodyState* states) {
  const std::size_t both = TwinCount(one, two);
  for (std::size_t i = 0; i < both; ++i) {
    TwinBlock k(one.blocks[i], two.blocks[i]);
    TwinSecondLanes second(one.seconds[i], two.seconds[i]);
    for (int o = 0; o < kBlockLanes; o += Lanes::kCount) WarmStartTurningLanes<Twin>(k, second, o, states);
  }
  TurningWarmStartBlocks(one.blocks + both, one.seconds + both, one.count - both, states);
  TurningWarmStartBlocks(two.blocks + both, two.seconds + both, two.count - both, states);
}

// SolveTwoPoints for the lanes: the new impulses (x1, x2) and the lanes where a case fit.
// K, its determinant and reciprocals from the packed second points (TurningSecondLanes).
template <typename L, typename Second>
[[gnu::always_inline]] inline MaskFor<L> SolveTwoPointsLanes(const Second& q, int o, L a1, L a2, L vn1, L vn2, L t1,
                                                             L t2, L* x1, L* x2) {
  const L zero(0.0);
  const L k11 = L::Load(q.k11 + o), k12 = L::Load(q.k12 + o), k22 = L::Load(q.k22 + o);
  const L det = L::Load(q.det + o);
  const MaskFor<L> conditioned = k11 * k11 < L(1000.0) * det;
  const L b1 = (vn1 - t1) - (k11 * a1 + k12 * a2);
  const L b2 = (vn2 - t2) - (k12 * a1 + k22 * a2);
  const L inv_det = L::Load(q.inv_det + o);
  const L y1 = (-k22 * b1 + k12 * b2) * inv_det;
  const L y2 = (k12 * b1 - k11 * b2) * inv_det;
  const MaskFor<L> both = (y1 >= zero) & (y2 >= zero);
  const L z1 = -b1 * L::Load(q.inv_k11 + o);
  const MaskFor<L> first = (z1 >= zero) & (k12 * z1 + b2 >= zero);
  const L z2 = -b2 * L::Load(q.inv_k22 + o);
  const MaskFor<L> second = (z2 >= zero) & (k12 * z2 + b1 >= zero);
  const MaskFor<L> neither = (b1 >= zero) & (b2 >= zero);
  *x1 = Select(both, y1, Select(first, z1, zero));
  *x2 = Select(both, y2, Select(first, zero, Select(second, z2, zero)));
  return conditioned & (both | first | second | neither);
}

// One block's lanes [o, o + L::kCount) of TurningSolveBlocks (or two blocks', Twin), `kTwo`
// whether any has a second point (`second`): a template, so that the lanes of circles are
// compiled without it. `kFirst`: the substep's first pass, which works out the least normal
// speeds from the moves and keeps them (min_normal_speed) for the later passes, which read them
// instead of gathering the moves and turns again (the turning pyramid of base 40 1.81 -> 1.77
// ms/step: little, as the passes wait mostly on the chain of blocks, wide_twin.inl).
template <typename L, bool kTwo, bool kTurns, bool kFirst, typename Block, typename Second>
[[gnu::always_inline]] inline void SolveTurningLanes(Block& k, Second& second, int o, BodyState* states,
                                                     const Vec2* moved, const Rot* turned, L inv_h,
                                                     bool block_solve) {
  const PairLanes<L> c = LoadPair<L>(k, o);
  const L tx = -c.ny, ty = c.nx;
  // Without a second point, p1 stands in for it where the arithmetic needs a value and is
  // never kept.
  const PointLanes<L> p0 = LoadPoint<L>(k.first, o), p1 = kTwo ? LoadPoint<L>(second, o) : p0;
  L min_vn0, min_vn1;
  if constexpr (kFirst) {
    const PlaceLanes<L> q = GatherPlaces<L, kTurns>(k, o, moved, turned);
    min_vn0 = -Max0(SeparationAt<kTurns>(q, p0, c)) * inv_h;
    min_vn1 = kTwo ? -Max0(SeparationAt<kTurns>(q, p1, c)) * inv_h : L(0.0);
    min_vn0.Store(k.first.min_normal_speed + o);
    if constexpr (kTwo) min_vn1.Store(second.min_normal_speed + o);
  } else {
    min_vn0 = L::Load(k.first.min_normal_speed + o);
    min_vn1 = kTwo ? L::Load(second.min_normal_speed + o) : L(0.0);
  }
  const Motion<L> a0 = GatherMotion<L>(states, k.a + o), b0 = GatherMotion<L>(states, k.b + o);

  // Both normals together, where two points allow (the block solver).
  MaskFor<L> blocked = NoLanes<L>();  // none yet
  Motion<L> ab = a0, bb = b0;
  L xb0 = p0.normal_impulse, xb1 = p1.normal_impulse;
  if (kTwo && block_solve) {
    const L vn0 = RelativeAlong(p0, a0, b0, c.nx, c.ny), vn1 = RelativeAlong(p1, a0, b0, c.nx, c.ny);
    blocked = c.two & SolveTwoPointsLanes<L>(second, o, p0.normal_impulse, p1.normal_impulse, vn0, vn1, min_vn0,
                                             min_vn1, &xb0, &xb1);
    const L d0 = xb0 - p0.normal_impulse, d1 = xb1 - p1.normal_impulse;
    ApplyAt(c, p0, d0 * c.nx, d0 * c.ny, &ab, &bb);
    ApplyAt(c, p1, d1 * c.nx, d1 * c.ny, &ab, &bb);
  }
  // One point after the other, elsewhere (padding lanes, with no moving body, need neither).
  Motion<L> as = a0, bs = b0;
  L xs0 = p0.normal_impulse, xs1 = p1.normal_impulse;
  if (((c.moving_a | c.moving_b) & ~Bits(blocked)) != 0) {
    const L v0 = RelativeAlong(p0, as, bs, c.nx, c.ny);
    xs0 = Max0(p0.normal_impulse + p0.normal_mass * (min_vn0 - v0));
    const L d0 = xs0 - p0.normal_impulse;
    ApplyAt(c, p0, d0 * c.nx, d0 * c.ny, &as, &bs);
    if constexpr (kTwo) {
      Motion<L> a1 = as, b1 = bs;
      const L v1 = RelativeAlong(p1, a1, b1, c.nx, c.ny);
      const L new1 = Max0(p1.normal_impulse + p1.normal_mass * (min_vn1 - v1));
      const L d1 = new1 - p1.normal_impulse;
      ApplyAt(c, p1, d1 * c.nx, d1 * c.ny, &a1, &b1);
      xs1 = Select(c.two, new1, p1.normal_impulse);
      as = Select<L>(c.two, a1, as), bs = Select<L>(c.two, b1, bs);
    }
  }
  Motion<L> a = Select<L>(blocked, ab, as), b = Select<L>(blocked, bb, bs);
  const L n0 = Select(blocked, xb0, xs0), n1 = Select(blocked, xb1, xs1);
  n0.Store(k.first.normal_impulse + o);
  if constexpr (kTwo) n1.Store(second.normal_impulse + o);

  // Coulomb friction at each point, within the cone of its normal impulse.
  const L friction = L::Load(k.friction + o);
  for (int point = 0; point < (kTwo ? 2 : 1); ++point) {
    const PointLanes<L>& p = point == 0 ? p0 : p1;
    const L vt = RelativeAlong(p, a, b, tx, ty);
    const L max_friction = friction * (point == 0 ? n0 : n1);
    const L free = p.tangent_impulse - p.tangent_mass * vt;
    // Clamp(free, -max, max): (max < free ? max : free), then (-max > that ? -max : that), the
    // same as max >= 0 (friction and normal impulse are), or where either is NaN.
    const L new_tangent = MaxOf(-max_friction, MinOf(max_friction, free));
    const L d = new_tangent - p.tangent_impulse;
    Motion<L> a2 = a, b2 = b;
    ApplyAt(c, p, d * tx, d * ty, &a2, &b2);
    if (point == 0) {
      new_tangent.Store(k.first.tangent_impulse + o);
      a = a2, b = b2;
    } else {
      Select(c.two, new_tangent, p.tangent_impulse).Store(second.tangent_impulse + o);
      a = Select<L>(c.two, a2, a), b = Select<L>(c.two, b2, b);
    }
  }
  ScatterMotion(states, k.a + o, a, c.moving_a);
  ScatterMotion(states, k.b + o, b, c.moving_b);
}

// A block's lanes (or two blocks', Twin) of TurningSolveBlocks, the circles' without their
// second points.
template <typename L, bool kTurns, bool kFirst, typename Block, typename Second>
[[gnu::always_inline]] inline void SolveTurningBlockLanes(Block& k, Second& second, int o, BodyState* states,
                                                          const Vec2* moved, const Rot* turned, L inv_h,
                                                          bool block_solve) {
  if (Bits(L::Load(k.two_points + o) != L(0.0)) != 0) {
    SolveTurningLanes<L, true, kTurns, kFirst>(k, second, o, states, moved, turned, inv_h, block_solve);
  } else {  // circles have one point: their second is skipped whole
    SolveTurningLanes<L, false, kTurns, kFirst>(k, second, o, states, moved, turned, inv_h, block_solve);
  }
}

template <bool kTurns, bool kFirst>
void SolveTurningBlocks(TurningBlock* blocks, TurningSecondLanes* seconds, std::size_t count, BodyState* states,
                        const Vec2* moved, const Rot* turned, double inv_h_scalar, bool block_solve) {
  const Lanes inv_h(inv_h_scalar);
  for (std::size_t i = 0; i < count; ++i) {
    for (int o = 0; o < kBlockLanes; o += Lanes::kCount) {
      SolveTurningBlockLanes<Lanes, kTurns, kFirst>(blocks[i], seconds[i], o, states, moved, turned, inv_h,
                                                    block_solve);
    }
  }
}

// The runs' first TwinCount blocks side by side, then the rest of each on its own.
template <bool kTurns, bool kFirst>
void SolveTurningTwin(TurningRun one, TurningRun two, BodyState* states, const Vec2* moved, const Rot* turned,
                      double inv_h, bool block_solve) {
  const std::size_t both = TwinCount(one, two);
  const Twin twin_inv_h(inv_h);
  for (std::size_t i = 0; i < both; ++i) {
    TwinBlock k(one.blocks[i], two.blocks[i]);
    TwinSecondLanes second(one.seconds[i], two.seconds[i]);
    for (int o = 0; o < kBlockLanes; o += Lanes::kCount) {
      SolveTurningBlockLanes<Twin, kTurns, kFirst>(k, second, o, states, moved, turned, twin_inv_h, block_solve);
    }
  }
  SolveTurningBlocks<kTurns, kFirst>(one.blocks + both, one.seconds + both, one.count - both, states, moved, turned,
                                     inv_h, block_solve);
  SolveTurningBlocks<kTurns, kFirst>(two.blocks + both, two.seconds + both, two.count - both, states, moved, turned,
                                     inv_h, block_solve);
}

// `turned` null: no body's turn moves its points (the anchors stay where they were).
void TurningSolveTwin(TurningRun one, TurningRun two, BodyState* states, const Vec2* moved, const Rot* turned,
                      double inv_h, bool block_solve, bool first_pass) {
  if (!first_pass) {
    SolveTurningTwin<false, false>(one, two, states, moved, turned, inv_h, block_solve);
  } else if (turned) {
    SolveTurningTwin<true, true>(one, two, states, moved, turned, inv_h, block_solve);
  } else {
    SolveTurningTwin<false, true>(one, two, states, moved, turned, inv_h, block_solve);
  }
}

// `turned` null: no body's turn moves its points (the anchors stay where they were).
void TurningSolveBlocks(TurningBlock* blocks, TurningSecondLanes* seconds, std::size_t count, BodyState* states,
                        const Vec2* moved, const Rot* turned, double inv_h, bool block_solve, bool first_pass) {
  if (!first_pass) {  // the least normal speeds are known: neither moves nor turns are read
    SolveTurningBlocks<false, false>(blocks, seconds, count, states, moved, turned, inv_h, block_solve);
  } else if (turned) {
    SolveTurningBlocks<true, true>(blocks, seconds, count, states, moved, turned, inv_h, block_solve);
  } else {
    SolveTurningBlocks<false, true>(blocks, seconds, count, states, moved, turned, inv_h, block_solve);
  }
}

// One block's lanes [o, o + L::kCount) of PushOutTurningBlocks (or two blocks', Twin).
template <typename L, bool kTurns, typename Block, typename Second>
[[gnu::always_inline]] inline void PushOutTurningLanes(Block& k, Second& second, int o, const Vec2* moved,
                                                       const Rot* turned, double* push_linear, double* push_angular,
                                                       L rate, L max_speed, L slop) {
  const unsigned all = (1u << L::kCount) - 1;
  const PairLanes<L> c = LoadPair<L>(k, o);
  const PlaceLanes<L> q = GatherPlaces<L, kTurns>(k, o, moved, turned);
  // Each point's separation and lanes past the slop first: the separations read the moves alone,
  // and a block with no such lane (in the settled turning pour, 98 in 100) is passed over without
  // gathering the push velocities.
  const bool two = Bits(c.two) != 0;
  const PointLanes<L> p0 = LoadPoint<L>(k.first, o), p1 = two ? LoadPoint<L>(second, o) : p0;
  const L s0 = SeparationAt<kTurns>(q, p0, c), s1 = two ? SeparationAt<kTurns>(q, p1, c) : s0;
  // Overlap within the slop is left alone.
  const unsigned active0 = ~Bits(s0 >= -slop) & all, active1 = two ? ~Bits(s1 >= -slop) & Bits(c.two) : 0u;
  if ((active0 | active1) == 0) return;
  // The push velocities as stored: point 1 reads what point 0 wrote, where it wrote.
  L vax, vay, vbx, vby;
  Gather(push_linear, kVec2Stride, k.a + o, &vax, &vay);
  Gather(push_linear, kVec2Stride, k.b + o, &vbx, &vby);
  L wa = GatherOne(push_angular, 1, k.a + o), wb = GatherOne(push_angular, 1, k.b + o);
  unsigned written_a = 0, written_b = 0;
  for (int point = 0; point < (two ? 2 : 1); ++point) {
    const PointLanes<L>& p = point == 0 ? p0 : p1;
    const L s = point == 0 ? s0 : s1;
    const unsigned active = point == 0 ? active0 : active1;
    if (active == 0) continue;
    const L wanted = rate * -(s + slop);
    const L target = MinOf(max_speed, wanted);  // (max_speed < wanted ? max_speed : wanted)
    L vn = (vbx - vax) * c.nx + (vby - vay) * c.ny;
    // −wb·rby − −wa·ray is wa·ray − wb·rby: IEEE negation, addition and subtraction round alike.
    const L cx = wa * p.ray - wb * p.rby, cy = wb * p.rbx - wa * p.rax;
    vn = vn + (cx * c.nx + cy * c.ny);
    const L dp = Max0(p.normal_mass * (target - vn));
    const L sa = c.ima * dp, sb = c.imb * dp;
    const L ix = dp * c.nx, iy = dp * c.ny;
    const unsigned write_a = active & c.moving_a, write_b = active & c.moving_b;
    const MaskFor<L> wa_mask = LanesOf<L>(write_a), wb_mask = LanesOf<L>(write_b);
    vax = Select(wa_mask, vax - sa * c.nx, vax);
    vay = Select(wa_mask, vay - sa * c.ny, vay);
    vbx = Select(wb_mask, vbx + sb * c.nx, vbx);
    vby = Select(wb_mask, vby + sb * c.ny, vby);
    wa = Select(wa_mask, wa - c.iia * (p.rax * iy - p.ray * ix), wa);
    wb = Select(wb_mask, wb + c.iib * (p.rbx * iy - p.rby * ix), wb);
    written_a |= write_a;
    written_b |= write_b;
  }
  Scatter(push_linear, kVec2Stride, k.a + o, vax, vay, written_a);
  Scatter(push_linear, kVec2Stride, k.b + o, vbx, vby, written_b);
  ScatterOne(push_angular, 1, k.a + o, wa, written_a);
  ScatterOne(push_angular, 1, k.b + o, wb, written_b);
}

template <bool kTurns>
void PushOutTurningBlocks(TurningBlock* blocks, TurningSecondLanes* seconds, std::size_t count, const Vec2* moved,
                          const Rot* turned, Vec2* push, double* push_angular,
                          double push_out_rate, double max_push_out_speed, double linear_slop) {
  if (count == 0) return;  // no contacts: the bodies' arrays may be empty
  const Lanes rate(push_out_rate), max_speed(max_push_out_speed), slop(linear_slop);
  for (std::size_t i = 0; i < count; ++i) {
    for (int o = 0; o < kBlockLanes; o += Lanes::kCount) {
      PushOutTurningLanes<Lanes, kTurns>(blocks[i], seconds[i], o, moved, turned, &push[0].x, push_angular, rate,
                                         max_speed, slop);
    }
  }
}

// The runs' first TwinCount blocks side by side, then the rest of each on its own.
template <bool kTurns>
void PushOutTurningTwin(TurningRun one, TurningRun two, const Vec2* moved, const Rot* turned, Vec2* push,
                        double* push_angular, double push_out_rate, double max_push_out_speed, double linear_slop) {
  const std::size_t both = TwinCount(one, two);
  const Twin rate(push_out_rate), max_speed(max_push_out_speed), slop(linear_slop);
  for (std::size_t i = 0; i < both; ++i) {
    TwinBlock k(one.blocks[i], two.blocks[i]);
    TwinSecondLanes second(one.seconds[i], two.seconds[i]);
    for (int o = 0; o < kBlockLanes; o += Lanes::kCount) {
      PushOutTurningLanes<Twin, kTurns>(k, second, o, moved, turned, &push[0].x, push_angular, rate, max_speed, slop);
    }
  }
  PushOutTurningBlocks<kTurns>(one.blocks + both, one.seconds + both, one.count - both, moved, turned, push,
                               push_angular, push_out_rate, max_push_out_speed, linear_slop);
  PushOutTurningBlocks<kTurns>(two.blocks + both, two.seconds + both, two.count - both, moved, turned, push,
                               push_angular, push_out_rate, max_push_out_speed, linear_slop);
}

// `turned` null: no body's turn moves its points.
void TurningPushOutBlocks(TurningBlock* blocks, TurningSecondLanes* seconds, std::size_t count, const Vec2* moved,
                          const Rot* turned, Vec2* push, double* push_angular, double push_out_rate,
                          double max_push_out_speed, double linear_slop) {
  if (turned) {
    PushOutTurningBlocks<true>(blocks, seconds, count, moved, turned, push, push_angular, push_out_rate,
                               max_push_out_speed, linear_slop);
  } else {
    PushOutTurningBlocks<false>(blocks, seconds, count, moved, turned, push, push_angular, push_out_rate,
                                max_push_out_speed, linear_slop);
  }
}

// `turned` null: no body's turn moves its points.
void TurningPushOutTwin(TurningRun one, TurningRun two, const Vec2* moved, const Rot* turned, Vec2* push,
                        double* push_angular, double push_out_rate, double max_push_out_speed, double linear_slop) {
  if (turned) {
    PushOutTurningTwin<true>(one, two, moved, turned, push, push_angular, push_out_rate, max_push_out_speed,
                             linear_slop);
  } else {
    PushOutTurningTwin<false>(one, two, moved, turned, push, push_angular, push_out_rate, max_push_out_speed,
                              linear_slop);
  }
}
