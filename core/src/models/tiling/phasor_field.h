// Phasor noise (Tricard et al. 2019) rasterised as a periodic exemplar pair for colour mapping
// (paper 002 §6.4, Fig. 13; notes P2.6: the authors rasterise it and tile-and-blend the pair).
//
// G(x) = Σ_k exp(−π a² |x − x_k|²) · exp(i (2π f_k · (x − x_k) + φ_k)) over random impulses on a
// torus (differences wrap, so the field is periodic); the phasor field is φ(x) = arg G(x) and
// the pair is ((sin φ + 1)/2, (cos φ + 1)/2) ∈ [0, 1]²: a colour map profile ∘ atan2 turns it
// into stripes of constant contrast whatever the local amplitude of G.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace stochtex {

struct PhasorFieldOptions {
    int size = 256;                  ///< pixels per side (a power of two)
    double frequency = 1.0 / 16;     ///< cycles per pixel
    double orientation = 0.5;        ///< radians: the mean frequency direction
    double orientation_spread = 0.6; ///< radians: kernels' directions spread uniformly over this
    double impulses_per_kernel = 8;  ///< mean number of kernels overlapping a point
    std::uint32_t seed = 1;
};

/// The (sin, cos) pair mapped to [0, 1], two planes of size² values.
std::array<std::vector<float>, 2> phasor_field(const PhasorFieldOptions& options);

}  // namespace stochtex
