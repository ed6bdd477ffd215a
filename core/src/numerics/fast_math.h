// Float exp and sin/cos for the Gabor kernel sums: branch-free polynomials that GCC vectorises
// (std::exp / std::cos are library calls, which block vectorisation and cost ~10 ns each).
// Accuracy: relative 2e-7 (exp on [−87, 0]), absolute 3e-7 (sin, cos) — far below what the
// noise needs (its values are sums of ~16 kernels; the tests compare with double precision).
#pragma once

#include <cstdint>
#include <cstring>

namespace stochtex {

/// e^x for x in [−87, 0] (callers clamp: a clamp here, a comparison, would keep the loop scalar).
inline float fast_exp(float x)
{
    const float y = x * 1.44269504f;  // log2(e)·x
    // Round to nearest by adding 1.5·2^23: the sum's low mantissa bits are then the integer
    // (read from the bits: a float→int conversion may trap, which keeps GCC from vectorising).
    const float shifted = y + 12582912.0f;
    const float rounded = shifted - 12582912.0f;
    const float f = y - rounded;  // [−½, ½]
    // 2^f = e^(f ln 2), Taylor to degree 6: error < 1e-7 on [−½, ½].
    float p = 1.5403530e-4f;
    p = p * f + 1.3333558e-3f;
    p = p * f + 9.6181291e-3f;
    p = p * f + 5.5504109e-2f;
    p = p * f + 2.4022651e-1f;
    p = p * f + 6.9314718e-1f;
    p = p * f + 1.0f;
    std::int32_t integer;
    std::memcpy(&integer, &shifted, sizeof integer);
    const std::int32_t bits = (integer - 0x4b400000 + 127) << 23;
    float scale;
    std::memcpy(&scale, &bits, sizeof scale);
    return p * scale;
}

/// sin(2π·turns) and cos(2π·turns), for |turns| < 2^20.
inline void fast_sincos_turns(float turns, float& sine, float& cosine)
{
    // Nearest quarter turn q, then the remainder x ∈ [−π/4, π/4] and a rotation by q·90°.
    const float shifted = turns * 4.0f + 12582912.0f;
    const float q = shifted - 12582912.0f;
    const float x = (turns - q * 0.25f) * 6.28318531f;
    const float x2 = x * x;
    const float s = x * (1.0f + x2 * (-1.6666667e-1f + x2 * (8.3333333e-3f + x2 * (-1.9841270e-4f + x2 * 2.7557319e-6f))));
    const float c = 1.0f + x2 * (-0.5f + x2 * (4.1666667e-2f + x2 * (-1.3888889e-3f + x2 * 2.4801587e-5f)));
    // Odd quadrants swap sine and cosine; quadrants 2, 3 negate the sine, 1, 2 the cosine (two's
    // complement makes −1 ≡ 3). Bit operations, not branches or selects, so the loop vectorises.
    std::uint32_t quadrant;
    std::memcpy(&quadrant, &shifted, sizeof quadrant);  // low bits: q (see fast_exp)
    const std::uint32_t swap = 0u - (quadrant & 1);
    std::uint32_t s_bits, c_bits;
    std::memcpy(&s_bits, &s, 4);
    std::memcpy(&c_bits, &c, 4);
    const std::uint32_t sine_bits = ((s_bits & ~swap) | (c_bits & swap)) ^ ((quadrant & 2) << 30);
    const std::uint32_t cosine_bits = ((c_bits & ~swap) | (s_bits & swap)) ^ (((quadrant + 1) & 2) << 30);
    std::memcpy(&sine, &sine_bits, 4);
    std::memcpy(&cosine, &cosine_bits, 4);
}

}  // namespace stochtex
