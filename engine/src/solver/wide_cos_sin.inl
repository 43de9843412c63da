// Rotations of many bodies in lanes (WidePasses::rotations), included after wide_kernels.inl.
// Each lane does CosSinOf's operations (engine/portable_math.h) in CosSinOf's order: + − × of
// doubles round alike in a lane and alone, so a body's rotation has the same bits either way.
// The steps CosSinOf takes on integers are taken here on whole numbers held in doubles, exactly.
// The Taylor polynomials are CosSinOf's own (portable_detail::SinTaylor, CosTaylor, written for
// either). A group of lanes holding an angle past kLargestExactAngle, a NaN or an infinity goes
// one angle at a time through StoreRot (none does in a scene that runs).
//
// Why: one body at a time, with its branches on the quadrant, the joint grid's rotation of every
// joined body each substep took 11.8 % of its step.

// x rounded toward zero, exactly, for |x| < 2^51: as the conversion to an integer and back.
inline Lanes TowardZero(Lanes x) {
  const Lanes size = Abs(x), two52(0x1p52);
  Lanes whole = (size + two52) - two52;                   // |x| rounded to the nearest whole number
  whole = Select(whole > size, whole - Lanes(1.0), whole);  // down, where that went up
  return Select(x < Lanes(0.0), Lanes(0.0) - whole, whole);  // +0, not −0, as (double)0 is
}

// CosSinOf for lanes whose angles are all within kLargestExactAngle (NaN excluded).
inline void CosSinLanes(Lanes angle, Lanes* c, Lanes* s) {
  using portable_detail::kPiOver2A;
  using portable_detail::kPiOver2B;
  using portable_detail::kPiOver2C;
  using portable_detail::kTwoOverPi;
  const Lanes y = angle * Lanes(kTwoOverPi);
  // k: y rounded to a whole number, halves away from zero. (Where y is −0, +0.5 is added instead
  // of −0.5: k is 0 either way.)
  const Lanes k = TowardZero(y + Select(y < Lanes(0.0), Lanes(-0.5), Lanes(0.5)));
  const Lanes r = ((angle - k * Lanes(kPiOver2A)) - k * Lanes(kPiOver2B)) - k * Lanes(kPiOver2C);
  const Lanes sin_r = portable_detail::SinTaylor(r);
  const Lanes cos_r = portable_detail::CosTaylor(r);
  // The quadrant, k mod 4 in [0, 4) (as k & 3 in two's complement).
  Lanes quadrant = k - Lanes(4.0) * TowardZero(k * Lanes(0.25));
  quadrant = Select(quadrant < Lanes(0.0), quadrant + Lanes(4.0), quadrant);
  const auto odd = ((quadrant > Lanes(0.5)) & (quadrant < Lanes(1.5))) | (quadrant > Lanes(2.5));
  const auto upper = quadrant > Lanes(1.5);                                  // 2 or 3
  const auto cos_negative = (quadrant > Lanes(0.5)) & (quadrant < Lanes(2.5));  // 1 or 2
  const Lanes sine = Select(odd, cos_r, sin_r), cosine = Select(odd, sin_r, cos_r);
  *s = Select(upper, -sine, sine);
  *c = Select(cos_negative, -cosine, cosine);
  // No turn: (1, the angle), its sign kept.
  const auto turned = angle != Lanes(0.0);
  *c = Select(turned, *c, Lanes(1.0));
  *s = Select(turned, *s, angle);
}

void RotationsOf(const double* angles, std::size_t stride, const BodyIndex* bodies, std::size_t count,
                 Rot* rotations) {
  constexpr unsigned kAll = (1u << Lanes::kCount) - 1;
  std::size_t k = 0;
  for (; k + Lanes::kCount <= count; k += Lanes::kCount) {
    std::int32_t index[Lanes::kCount];
    for (int j = 0; j < Lanes::kCount; ++j) index[j] = static_cast<std::int32_t>(bodies[k + static_cast<std::size_t>(j)]);
    const Lanes angle = GatherOne(angles, stride, index);
    if (Bits(Lanes(portable_detail::kLargestExactAngle) >= Abs(angle)) != kAll) {
      for (int j = 0; j < Lanes::kCount; ++j) {
        const BodyIndex body = bodies[k + static_cast<std::size_t>(j)];
        StoreRot(&rotations[body], angles[body * stride]);
      }
      continue;
    }
    Lanes c, s;
    CosSinLanes(angle, &c, &s);
    Scatter(&rotations[0].c, 2, index, c, s, kAll);
  }
  for (; k < count; ++k) StoreRot(&rotations[bodies[k]], angles[bodies[k] * stride]);
}
