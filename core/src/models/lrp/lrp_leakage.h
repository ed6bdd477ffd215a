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
//
// Strata of equal energy are sorted by density, not by frequency: the fine strata's windows
// (Δ of 1–5 px) spread over most of the plane and their expected spectra are nearly alike, so
// strata rows alone left the solve free to zero some of them and empty the top octave (gravel's
// second channel −15.6 dB in |k| ∈ [T/4, T/2), radial distance 9.1 dB). The solve therefore also
// matches the energy in each radial ring (4 per octave, the fidelity metric's rings), weighted
// 0.3 against the strata rows (docs/models/lrp.md, "Low frequencies and the top octave").
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
/// The same, and (ring_leakage non-null) the share landing in each ring (`rings`: a ring per bin, −1 none).
std::vector<std::vector<double>> stratum_leakage(const std::vector<LrpStratum>& strata, const std::vector<int>& label,
                                                 int size, const std::vector<int>* rings, int ring_count,
                                                 std::vector<std::vector<double>>* ring_leakage);

/// Replaces each stratum's σ per channel by the leakage-corrected solution (channels may be null).
/// `match_rings`: also the radial rings' energies (photos); analytic spectra (narrow rings, lobes,
/// numerically-zero tails between them) keep the strata rows only.
void correct_stratum_leakage(std::vector<LrpStratum>& strata, const std::vector<int>& label,
                             const std::array<const DiscreteSpectrum*, 3>& channels, bool match_rings = false);

}  // namespace stochtex
