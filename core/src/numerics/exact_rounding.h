// std::floor and std::round without a library call: the same doubles (sign of zero included)
// for every finite |v| < 2^63, in a few instructions. The x86-64 baseline (SSE2) has no
// rounding instruction, so the compiler calls libm for std::floor / std::round; the tiling
// and ptm raster paths round several times per sample. Positions there are bounded by
// max_position_pixels (texture.h), far inside the domain.
#pragma once

#include <cmath>
#include <cstdint>

namespace stochtex {

/// std::floor(v) for finite |v| < 2^63.
inline double floor_exact(double v)
{
    const double t = std::copysign(double(std::int64_t(v)), v);  // truncation, exact
    return t > v ? t - 1 : t;
}

/// std::round(v) (halves away from zero) for finite |v| < 2^63.
inline double round_exact(double v)
{
    const double t = std::copysign(double(std::int64_t(v)), v);
    return std::abs(v - t) >= 0.5 ? t + std::copysign(1.0, v) : t;  // v − t is exact
}

}  // namespace stochtex
