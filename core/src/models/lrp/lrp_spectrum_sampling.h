// Stratified spectral sampling for local random-phase noise (paper 003, §4.1–4.4, Fig. 4):
// a discrete spectrum becomes L strata of equal energy, each with its own window size Δ_S,
// standard deviation and J_S sub-strata (k-means on its eroded half-spectrum) from which every
// lattice point draws one frequency.
//
// Choices the paper leaves open, fixed here and in docs/models/lrp.md:
//   * Strata are built on one half of the symmetric spectrum (f and −f are one cosine); a bin
//     and its mirror always share a stratum. The least energetic bins holding 0.1 % of the
//     energy in total are left out: an analytic spectrum's numerically-zero tails would
//     otherwise make the last stratum cover the whole plane.
//   * By example, a steep spectrum's weakest stratum (many octaves of little energy up to
//     Nyquist, one tiny window whose spread is nearly white) is split by octave (`octave_span`).
//   * Budget: J_S = J / L, the remainder to the most energetic strata; J_S ≤ the eroded
//     stratum's bin count (a stratum of three peaks gets three cosines). By example, the lowest
//     octave first gets a stratum of its own (`resolve`), one cosine per bin.
//   * Δ_S = T √(coverage · J_S / |S_half|): the paper's T √J_S / √(2|S|) is coverage = ¼ with
//     |S| counted on the full spectrum. By example, ⅛: smaller windows, more of them — with ¼
//     the mid strata of photos show their few plane waves (a fine hatching), for 0–0.3 dB of
//     PSD fidelity (docs/models/lrp.md). Analytic spectra may set Δ instead (`spacing`).
//   * Sub-strata by k-means weighted by each bin's power (the paper's is unweighted): a stratum
//     of equal energy still spans a wide range of densities, and with equal-area sub-strata
//     every cosine of equal amplitude would flatten it (measured: 4.76 → 4.68 dB at L = 4,
//     2.81 → 2.48 dB at L = 8, mean radial log-PSD distance on four photos).
//   * Erosion by the window's 1D 75 %-energy radius (0.28 T / Δ_S bins), per connected
//     component: a component thinner than that keeps its innermost bins instead of vanishing.
//   * A sub-stratum is stored as at most `representatives` of its bins (k-means centres snapped
//     to bins), which keeps a .stex file a few kilobytes; synthesis jitters the drawn bin
//     within its cell.
#pragma once

#include "models/lrp/discrete_spectrum.h"

#include <stochtex/texture_description.h>
#include <stochtex/models/lrp_parameters.h>

#include <array>
#include <cstdint>
#include <vector>

namespace stochtex {

struct LrpSamplingOptions {
    int strata = 8;           ///< L (with the lowest octave's stratum, at most max_lrp_strata − 1 are made)
    int cosines = 48;         ///< J for the random-phase strata (Σ J_S)
    int representatives = 4;  ///< stored bins per sub-stratum
    double coverage = 0.25;   ///< the paper's; analysis by example uses ⅛ (LrpFitOptions)
    double spacing = 0;       ///< > 0: every stratum's Δ (exemplar pixels), instead of the coverage rule
    /// > 0: the lowest octave (bins with |k| < 2, at most J/2 of them) is a stratum of its own,
    /// one cosine per bin, with Δ = resolve / f, f its energy-weighted 10 % quantile of |f| (cycles
    /// per pixel): the window's 2D spread 0.41/Δ stays below f (⅔ f at the fit's 0.6) instead of
    /// carrying the longest wavelengths' energy upward. The other strata share the remaining cosines. 0 (analytic
    /// spectra): no such stratum (docs/models/lrp.md, "Low frequencies and the top octave").
    double resolve = 0;
    /// > 0: a stratum spanning more than this many octaves of |f|, from where its energy begins
    /// (10 % quantile of energy) to where its bins end (90 % quantile of bin count), whose bins
    /// reach the top two octaves (≥ 1/8 cycle per pixel), is split into one stratum per octave,
    /// within max_lrp_strata (the fit's 2.5; 0, analytic spectra: strata of equal energy only).
    double octave_span = 0;
    /// k-means weighted by the power of each bin: sub-strata of similar energy rather than area.
    bool power_weighted = true;
    std::uint64_t seed = 1;   ///< k-means seeding
};

struct StratifiedSpectrum {
    std::vector<LrpStratum> strata;
    /// Per bin (DiscreteSpectrum indexing): its stratum, or −1 (DC, excluded, left-out tail).
    std::vector<int> label;
};

/// `partition` defines the strata (the sum of the channels' spectra); each channel's energy in
/// a stratum becomes its σ² there (a null channel has σ = 0). Bins with `excluded[bin]` set (the
/// fixed-phase region; empty vector: none) belong to no stratum.
StratifiedSpectrum stratify_spectrum(const DiscreteSpectrum& partition,
                                     const std::array<const DiscreteSpectrum*, 3>& channels,
                                     const std::vector<char>& excluded, const LrpSamplingOptions& options);

/// The mirror bin of k (−k, with +T/2 folded onto −T/2).
inline int mirror_bin(int k, int size) { return k == -size / 2 ? k : -k; }

}  // namespace stochtex
