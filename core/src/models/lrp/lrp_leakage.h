// Spectral leakage of local random-phase strata, and the stratum variances that undo it.
//
// A stratum's windows spread each cosine's energy over the window's spectrum (radius ~0.41/Δ_S):
// the narrow, strong strata near DC lose energy to their neighbours and the wide, weak ones at
// high frequencies gain it (measured on photos: 0.34 … 1.5 of the target per stratum). As the
// wavelet model's band_leakage does for its bands, the expected spectrum of each stratum is
// computed — its frequencies' density convolved with the power spectrum of its variance-
// normalised window, on the T×T grid of a render at the exemplar's pixel scale (so frequencies
// past Nyquist fold back as they do in a render) — and the strata's variances are solved
// (non-negative least squares, relative errors) so that the energy landing in each stratum's
// bins is the photo's, with the total variance kept as one more equation.
#pragma once

#include "models/lrp/discrete_spectrum.h"

#include <stochtex/texture_description.h>
#include <stochtex/models/lrp_parameters.h>

#include <array>
#include <vector>

namespace stochtex {

/// The expected PSD of a stratum's noise at unit variance (sums to 1) on the size² grid.
DiscreteSpectrum expected_stratum_spectrum(const LrpStratum& stratum, int size);

/// leakage[a][b]: the share of stratum b's variance that lands in the bins labelled a.
std::vector<std::vector<double>> stratum_leakage(const std::vector<LrpStratum>& strata, const std::vector<int>& label,
                                                 int size);

/// Replaces each stratum's σ per channel by the leakage-corrected solution (channels may be null).
void correct_stratum_leakage(std::vector<LrpStratum>& strata, const std::vector<int>& label,
                             const std::array<const DiscreteSpectrum*, 3>& channels);

}  // namespace stochtex
