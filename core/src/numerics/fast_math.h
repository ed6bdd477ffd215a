// Float exp and sin/cos for the Gabor kernel sums: branch-free polynomials that GCC vectorises
// (std::exp / std::cos are library calls, which block vectorisation and cost ~10 ns each).
// Accuracy: relative 2e-7 (exp on [−87, 0]), absolute 3e-7 (sin, cos) — far below what the
// noise needs (its values are sums of ~16 kernels; the tests compare with double precision).
#pragma once

#include <cstdint>
#include <cstring>

namespace stochtex {

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
