// Texture by example with structure (paper 003, §5.1 and §5.3, Figs. 6 and 9): the region R of
// fixed phases and its blockwise approximation with a budget of J_R cosines per block.
//
//   * R holds the strongest bins of one crop (the centred T×T crop's periodic component —
//     Moisan's decomposition, so that the crop's edge jumps do not put a "+" of leakage into
//     R) until they carry a fraction r of its energy (DC excluded: the mean is stored apart).
//   * The structure image is R's inverse FFT. Blocks of B = T, T/2, … pixels each keep the J_R
//     (9 J_R for the single block B = T, which needs no windows: same cost) strongest bins of the FFT of an E×E window of the structure image centred on the block
//     (E = B as in the paper, or wider: the windows of neighbouring blocks reach that far), and
//     the windowed reconstruction (lrp_structure_noise.h, exactly as synthesis computes it) is
//     compared with the structure image: subdivision stops when the mean colour error is below
//     1/256 (paper), or when the next level would store more than `max_terms` cosines (the file
//     would grow past a few kilobytes), keeping the best level reached.
#pragma once

#include "colour/colour_basis.h"

#include <stochtex/texture_description.h>
#include <stochtex/models/lrp_parameters.h>

#include <array>
#include <vector>

namespace stochtex {

struct LrpStructureFitOptions {
    double energy_fraction = 0.1;   ///< r
    int cosines = 5;                ///< J_R per block
    double colour_tolerance = 1.0 / 256;  ///< mean |Δ linear RGB| per channel
    int max_terms = 96;             ///< blocks × J_R at most
    int min_block_size = 8;
    int fit_extent = 1;             ///< E = fit_extent · B
    bool random_placement = true;
    double turbulence = 0;          ///< exemplar pixels
    /// Bins nearer DC than this stay out of R. Random placement shifts the structure per cell of
    /// half a crop, which decorrelates every wavelength longer than a cell: R's lowest octave came
    /// out 5–17 dB weak (docs/models/lrp.md); the random-phase strata hold it instead.
    double min_radius_bins = 0;
};

struct LrpStructureFit {
    LrpStructure structure;
    /// R as a mask over the T×T bins (DiscreteSpectrum indexing; symmetric).
    std::vector<char> region;
    double energy_fraction = 0;      ///< the share of the crop's energy R holds
    /// Mean colour error of each level tried (block sizes T, T/2, …) and of the level kept.
    std::vector<std::pair<int, double>> level_errors;
    double colour_error = 0;
    /// The structure image (three channel planes, T×T): what n_R approximates.
    std::array<std::vector<float>, 3> structure_image;
};

/// channels: the decorrelated (optionally Gaussianised) planes, width × height; basis: their RGB
/// directions (colour errors are measured in RGB); size: T.
LrpStructureFit fit_lrp_structure(const std::array<std::vector<float>, 3>& channels, int width, int height, int size,
                                  const Matrix3& basis, const LrpStructureFitOptions& options);

/// Mean over the pixels and the RGB channels of |basis · (a − b)| for two T×T three-plane images.
double mean_colour_error(const std::array<std::vector<float>, 3>& a, const std::array<std::vector<float>, 3>& b,
                         const Matrix3& basis);

}  // namespace stochtex
