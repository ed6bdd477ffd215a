// Per-band power of a photo channel (paper 000, §4.2, eqs. 9–10), generalised to any size.
//
// Band j (j = 0 finest) holds the DFT bins whose frequency ν = max(|fx|, |fy|), in cycles per
// pixel, lies in [2^-(j+2), 2^-(j+1)) — the square annuli of eq. 10 — so a W×H photo of any
// size and aspect ratio is used whole, without cropping or resampling.
// Policy for bins outside every band (documented in docs/models/wavelet.md):
//   * DC: excluded (the mean is stored separately);
//   * ν = 1/2 (Nyquist row/column of even sizes): folded into band 0 (it is real variance);
//   * below the coarsest band (long, non-power-of-two sides): folded into the coarsest band.
// Hence Σ_j P_j equals the channel variance exactly (Parseval), for either PSD estimator.
#pragma once

#include <string>
#include <vector>

namespace stochtex {

/// How the photo's power spectrum is estimated (docs/models/wavelet.md, "PSD estimator").
enum class PsdEstimator {
    periodic,         ///< raw periodogram of the photo as if it tiled (paper 000)
    periodic_smooth,  ///< Moisan's periodic + smooth decomposition: no "+"-shaped edge leak
};
const char* to_string(PsdEstimator estimator);
PsdEstimator psd_estimator_from_string(const std::string& name);  // throws Error

/// Number of bands a W×H photo supports: those whose lowest frequency is at least one cycle
/// per image along the shorter side, i.e. floor(log2(min(W, H))) − 1 (8 for 512²).
int supported_band_count(int width, int height);

/// Mean-square power P_j of each band (band_count of them) of a channel (width*height floats).
std::vector<double> band_powers(const std::vector<float>& plane, int width, int height, int band_count,
                                PsdEstimator estimator);

/// Band of frequency ν > 0 (cycles per pixel), before folding: −1 for ν = 1/2, j ≥ 0 otherwise.
int band_of_frequency(double nu);

}  // namespace stochtex
