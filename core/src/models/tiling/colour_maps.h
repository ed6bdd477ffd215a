// Named 2D colour maps for colour-mapped noise (paper 002 Figs. 4–13): S(a, b) over [0, 1]²,
// a = noise 0 along x, b = noise 1 along y, as sRGB-encoded values in [0, 1].
#pragma once

#include <string>
#include <vector>

namespace stochtex {

/// green (smooth shades: the paper's Fig. 4–7 kind), rgb (saturated red, green and blue
/// sectors around the middle, a yellow disc: strong discontinuities, Fig. 8–11), and the
/// phasor profiles phasor-sine, phasor-square, phasor-sawtooth (profile ∘ atan2 of the
/// (sin, cos) pair, Fig. 13).
const std::vector<std::string>& colour_map_names();

/// size × size × 3 sRGB values (rows along b). Throws Error for an unknown name.
std::vector<float> named_colour_map(const std::string& name, int size);

}  // namespace stochtex
