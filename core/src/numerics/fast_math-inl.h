// Vector e^x and sin/cos(2π·turns) for the Highway kernels (gabor's impulse sums, lrp's term
// tables): numerics/fast_math.h's polynomials, lane-wise and operation for operation, so a
// kernel's values equal the scalar mirror's on every instruction set. Only Mul, Add, Sub and bit
// operations (never MulAdd: a fused multiply-add would round differently on the targets that
// have one). Accuracy: relative 2e-7 (exp on [−87, 0]), absolute 3e-7 (sin, cos).
//
// Included from a kernel file after hwy/highway.h, once per target (foreach_target.h): the
// guard below is Highway's per-target toggle, not a plain include guard.
#if defined(STOCHTEX_NUMERICS_FAST_MATH_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef STOCHTEX_NUMERICS_FAST_MATH_INL_H_
#undef STOCHTEX_NUMERICS_FAST_MATH_INL_H_
#else
#define STOCHTEX_NUMERICS_FAST_MATH_INL_H_
#endif

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace stochtex::fast_math::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

/// e^x for x in [−87, 0] (callers clamp). Rounds log2(e)·x to the nearest integer n by adding
/// 1.5·2^23 (the sum's low mantissa bits are n, read from the bits), 2^f for the remainder
/// f ∈ [−½, ½] by Taylor to degree 6 (error < 1e-7), and 2^n built as an exponent field.
template <class DF, class V>
HWY_INLINE V FastExp(DF df, V x)
{
    const hn::RebindToSigned<DF> di;
    const auto y = hn::Mul(x, hn::Set(df, 1.44269504f));
    const auto shifted = hn::Add(y, hn::Set(df, 12582912.0f));
    const auto rounded = hn::Sub(shifted, hn::Set(df, 12582912.0f));
    const auto f = hn::Sub(y, rounded);
    auto p = hn::Set(df, 1.5403530e-4f);
    p = hn::Add(hn::Mul(p, f), hn::Set(df, 1.3333558e-3f));
    p = hn::Add(hn::Mul(p, f), hn::Set(df, 9.6181291e-3f));
    p = hn::Add(hn::Mul(p, f), hn::Set(df, 5.5504109e-2f));
    p = hn::Add(hn::Mul(p, f), hn::Set(df, 2.4022651e-1f));
    p = hn::Add(hn::Mul(p, f), hn::Set(df, 6.9314718e-1f));
    p = hn::Add(hn::Mul(p, f), hn::Set(df, 1.0f));
    const auto bits = hn::ShiftLeft<23>(hn::Sub(hn::BitCast(di, shifted), hn::Set(di, 0x4b400000 - 127)));
    return hn::Mul(p, hn::BitCast(df, bits));
}

/// sin(2π·turns) and cos(2π·turns) for |turns| < 2^20: fast_sincos_turns (fast_math.h) lane by
/// lane — the nearest quarter turn q, the remainder x ∈ [−π/4, π/4], the two odd/even Taylor
/// polynomials, then a rotation by q·90°.
template <class DF, class V>
HWY_INLINE void FastSinCosTurns(DF df, V turns, V& sine, V& cosine)
{
    const hn::RebindToUnsigned<DF> du;
    const auto shifted = hn::Add(hn::Mul(turns, hn::Set(df, 4.0f)), hn::Set(df, 12582912.0f));
    const auto q = hn::Sub(shifted, hn::Set(df, 12582912.0f));
    const auto x = hn::Mul(hn::Sub(turns, hn::Mul(q, hn::Set(df, 0.25f))), hn::Set(df, 6.28318531f));
    const auto x2 = hn::Mul(x, x);
    auto s = hn::Add(hn::Set(df, -1.9841270e-4f), hn::Mul(x2, hn::Set(df, 2.7557319e-6f)));
    s = hn::Add(hn::Set(df, 8.3333333e-3f), hn::Mul(x2, s));
    s = hn::Add(hn::Set(df, -1.6666667e-1f), hn::Mul(x2, s));
    s = hn::Mul(x, hn::Add(hn::Set(df, 1.0f), hn::Mul(x2, s)));
    auto c = hn::Add(hn::Set(df, -1.3888889e-3f), hn::Mul(x2, hn::Set(df, 2.4801587e-5f)));
    c = hn::Add(hn::Set(df, 4.1666667e-2f), hn::Mul(x2, c));
    c = hn::Add(hn::Set(df, -0.5f), hn::Mul(x2, c));
    c = hn::Add(hn::Set(df, 1.0f), hn::Mul(x2, c));
    // Odd quadrants swap sine and cosine; quadrants 2, 3 negate the sine, 1, 2 the cosine (the
    // scalar mirror does the swap with masks and bit operations: a select gives the same bits).
    const auto quadrant = hn::BitCast(du, shifted);
    const auto one = hn::Set(du, 1u), two = hn::Set(du, 2u);
    const auto swap = hn::Eq(hn::And(quadrant, one), one);
    const auto s_bits = hn::BitCast(du, s), c_bits = hn::BitCast(du, c);
    const auto sine_bits = hn::Xor(hn::IfThenElse(swap, c_bits, s_bits), hn::ShiftLeft<30>(hn::And(quadrant, two)));
    const auto cosine_bits =
        hn::Xor(hn::IfThenElse(swap, s_bits, c_bits), hn::ShiftLeft<30>(hn::And(hn::Add(quadrant, one), two)));
    sine = hn::BitCast(df, sine_bits);
    cosine = hn::BitCast(df, cosine_bits);
}

}  // namespace stochtex::fast_math::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // per-target include guard
