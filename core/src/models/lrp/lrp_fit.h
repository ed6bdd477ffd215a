// Local random-phase noise by example (paper 003, §4.4 and §5; Fig. 5): the parameters of an
// lrp texture from a photo's decorrelated (and optionally Gaussianised) channels, and from an
// analytic spectrum.
//
//   1. T = the largest power of two below the photo's shorter side (at most 512); each
//      channel's Welch PSD on T×T crops (discrete_spectrum.h).
//   2. r > 0: the fixed-phase structure R and its blocks (lrp_structure_fit.h), J_R = round(rJ)
//      cosines per block (at least one).
//   3. The rest of the spectrum (R left out) in L strata of equal energy of the channels' summed
//      PSD, J − J_R cosines among them (lrp_spectrum_sampling.h); a stratum's σ² per channel is
//      that channel's energy there, then corrected for the windows' leakage (lrp_leakage.h).
#pragma once

#include "colour/colour_basis.h"
#include "models/lrp/discrete_spectrum.h"
#include "models/lrp/lrp_structure_fit.h"

#include <stochtex/texture_description.h>
#include <stochtex/models/lrp_parameters.h>

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace stochtex {

struct LrpFitOptions {
    int cosines = 50;                 ///< J
    int strata = 8;                   ///< L (the paper's 4 measured worse: docs/models/lrp.md)
    double structure_fraction = 0.1;  ///< r: energy share of the fixed-phase region (0: none)
    int representatives = 4;          ///< stored bins per sub-stratum
    double coverage = 0.125;          ///< Δ_S = T √(coverage J_S / |S_half|)
    double resolve = 0.6;             ///< the lowest octave's own stratum, Δ = resolve / f (LrpSamplingOptions::resolve)
    double octave_span = 2.5;         ///< strata wider than this many octaves split by octave (LrpSamplingOptions::octave_span)
    bool power_weighted = true;       ///< sub-strata of equal energy rather than equal area
    bool random_placement = true;
    double turbulence = -1;           ///< displacement σ, exemplar pixels; < 0: automatic
    int max_structure_terms = 96;     ///< blocks × J_R
    int max_spectrum_size = 512;
    /// Solve the strata's variances against their measured leakage (lrp_leakage.h); false: each
    /// stratum's σ² is its own energy, as in the paper.
    bool leakage_correction = true;
    /// The correction also matches each radial ring's energy (lrp_leakage.h); false: strata only.
    bool match_rings = true;
    std::uint64_t seed = 1;
};

/// What the fit measured, for reports and tests.
struct LrpFitReport {
    std::array<DiscreteSpectrum, 3> channel_spectra;  ///< Welch PSDs
    std::vector<int> stratum_of_bin;                   ///< per T×T bin: its stratum, −1 for none
    std::optional<LrpStructureFit> structure;
};

LrpParameters fit_lrp(const std::array<std::vector<float>, 3>& channels, int width, int height, const Matrix3& basis,
                      const LrpFitOptions& options, LrpFitReport* report = nullptr);

/// Random-phase strata for an analytic spectrum (one channel: σ in channel 0 only). `spacing` > 0
/// sets every stratum's Δ (exemplar pixels) instead of the coverage rule: for a continuous
/// spectrum the user chooses the spatial/spectral trade-off (paper §3.5), e.g. a window whose
/// spectral spread 0.41/Δ matches the spectrum's own width.
LrpParameters lrp_for_spectrum(const DiscreteSpectrum& spectrum, int cosines, int strata, double spacing = 0,
                               std::uint64_t seed = 1, std::vector<int>* stratum_of_bin = nullptr);

/// The automatic turbulence: a tenth of the energy-weighted mean wavelength of R (features are
/// distorted by a fraction of their size, not broken), in exemplar pixels.
double lrp_automatic_turbulence(const std::vector<char>& region, const DiscreteSpectrum& power);

}  // namespace stochtex
