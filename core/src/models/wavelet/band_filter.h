// Anti-aliasing by band clamping (Norton, Rockwood & Skolmoski 1982), with a smooth fade.
#pragma once

#include <algorithm>
#include <cmath>

namespace stochtex {

/// Weight factor of a band whose highest frequency is 2^-(j+1) cycles per exemplar pixel, for
/// a footprint `footprint_px` exemplar pixels wide. The band is kept whole while its top
/// frequency is below the footprint's Nyquist limit (footprint ≤ 2^j), removed once even its
/// lowest frequency aliases (footprint ≥ 2^(j+1)), and faded smoothly (smoothstep in log2 of
/// the footprint) in between, so a zoom never pops.
inline float band_fade(int band, double footprint_px)
{
    if (footprint_px <= std::ldexp(1.0, band)) return 1.0f;
    const double t = std::log2(footprint_px) - band;
    if (t >= 1) return 0.0f;
    return float(1 - t * t * (3 - 2 * t));
}

}  // namespace stochtex
