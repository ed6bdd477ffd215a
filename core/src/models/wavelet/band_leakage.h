// How much of each wavelet band's power the analysis sees in each FFT band, and the weight
// solve that undoes it (beyond paper 000, whose eq. 9 assumes perfectly band-limited bands).
//
// Real bands overlap their neighbours (paper Fig. 3): rendered alone, band j puts only ~80 %
// of its power in FFT band j. Eq. 9 then mixes neighbouring weights, which biases recovered
// weights by 7–17 % even on synthetic input. We compute the leakage matrix L(b, j) — the
// fraction of band j's power that band_powers() assigns to band b, with the same folding
// rules — exactly from this build's tile: the band's PSD is |DFT(coefficients)|² times the
// quadratic B-spline's sinc⁶, and sampling at one exemplar pixel folds it into [−½, ½)².
// The weights then solve P = σ_N² L w² with w² ≥ 0 (non-negative least squares).
#pragma once

#include <vector>

namespace stochtex {

/// L(b, j) as rows b, columns j, for band_count bands; each column sums to 1. Cached, thread-safe.
const std::vector<std::vector<double>>& band_leakage(int band_count);

/// Band weights from observed band powers: argmin ‖L σ_N² x − P‖², x ≥ 0, then w = sqrt(x).
/// Only the first `corrected_bands` columns use the leakage model; coarser bands keep eq. 9's
/// identity column: a photo holds too few cycles of them for their overlap to be estimated,
/// and measurement (tests/wavelet_test.cpp, weight recovery) shows that de-mixing them only
/// amplifies their sampling noise.
std::vector<double> solve_band_weights(const std::vector<double>& power, double band_variance, int corrected_bands);

/// Bands with at least 8 cycles of their lowest frequency across the photo's shorter side.
int leakage_corrected_band_count(int width, int height);

}  // namespace stochtex
