// A colour map pre-blurred along one of its diagonals (ColourMapFilter's tables for lines along
// them: a pair indexing the map by one noise twice, or by a noise and its mirror, lies on a
// diagonal, and its rank-one line then reads a table already blurred along it).
//
// Level k holds T_k(p) = ∫ S(clamp(p + s · (1, sign))) φ_σk(s) ds, σ_k = 2^(k−1) texel steps
// (each step moves one texel along both axes), S the bilinear map clamped to its edge per axis as
// lookups clamp their nodes — past an edge the path runs along it, past a corner it stays there.
// The integral is composite Simpson on half steps: the bilinear map along a diagonal is
// quadratic between texel centres, so Simpson is exact there and only the Gaussian's own
// curvature is approximated (a plain sum over whole steps would miss each cell's twist
// (f00 + f11 − f10 − f01) / 6, large where an edge of a saturated map crosses).
#pragma once

#include <vector>

namespace stochtex {

/// Levels 1…levels of the size × size RGB map `rgb` (interleaved, linear) blurred along the
/// diagonal (1, sign), sign ±1, each size² RGB texels plus one float of padding (lookups read a
/// texel as four floats) — the layout of ColourMapFilter's tables.
std::vector<std::vector<float>> diagonal_blurs(const std::vector<float>& rgb, int size, int sign, int levels);

}  // namespace stochtex
