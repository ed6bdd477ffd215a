// stochtex — Local random-phase noise: the parameters block of an lrp .stex (models/lrp/).
// The declaration of these fields (keys, ranges, defaults, docs) is the model's parameter schema,
// in core/src/models/lrp/; docs/stex-format.md lists it.
#pragma once

#include <array>
#include <optional>
#include <vector>

namespace stochtex {

/// One stratum of local random-phase noise (paper 003, §4; docs/models/lrp.md): a part of the
/// spectrum holding an equal share of its energy, with its own lattice of windows, sampled by
/// sub-strata. Every lattice point draws one frequency per sub-stratum, with random phases.
struct LrpStratum {
    /// Δ_S: lattice spacing (and window size), exemplar pixels.
    double spacing = 1;
    /// Standard deviation of the stratum's noise in each decorrelated channel.
    std::array<double, 3> sigma{0, 0, 0};
    /// substrata[j]: frequency bins kx0, ky0, kx1, ky1, … of sub-stratum j, in units of
    /// 1 / spectrum_size cycles per exemplar pixel, on one half of the symmetric spectrum. A
    /// lattice point draws one of them uniformly and jitters it within its bin.
    std::vector<std::vector<int>> substrata;
};

/// One block of the fixed-phase structure: per channel c,
/// Σ_t coefficients[c][2t]·cos θ_t − coefficients[c][2t+1]·sin θ_t, θ_t = 2π k_t·(x − x_b) / fit_size,
/// x_b the block's centre (its window's lattice point).
struct LrpBlock {
    std::vector<int> frequencies;                     ///< kx0, ky0, kx1, ky1, …
    std::array<std::vector<double>, 3> coefficients;  ///< per channel: re0, im0, re1, im1, …
};

/// The fixed-phase region R of texture by example (paper 003, §5): the strongest frequencies of
/// a spectrum_size² crop of the photo, reproduced blockwise; the crop repeats every spectrum_size
/// exemplar pixels, broken by random placement and turbulence.
struct LrpStructure {
    int block_size = 0;  ///< B, exemplar pixels: the crop holds (spectrum_size / B)² blocks
    int fit_size = 0;    ///< E: block frequencies are k / E cycles per exemplar pixel
    bool random_placement = true;  ///< shift blocks of half a crop by random offsets (blended)
    double turbulence = 0;         ///< standard deviation of the displacement, exemplar pixels; 0: none
    /// The blocks' coefficients are stored in files as integer multiples of this step (rounded
    /// on writing): short text, and a round trip that changes nothing.
    double coefficient_step = 1e-4;
    std::vector<LrpBlock> blocks;  ///< row-major
};

/// Local random-phase noise (paper 003): random-phase strata plus an optional fixed-phase structure.
struct LrpParameters {
    int spectrum_size = 256;  ///< T: frequency bins are k / T cycles per exemplar pixel
    std::vector<LrpStratum> strata;
    std::optional<LrpStructure> structure;  ///< absent: noise by example only (r = 0)
};

}  // namespace stochtex
