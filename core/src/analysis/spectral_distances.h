// stochtex — the spectral measures only compare_images and the tests call: the 2D log-PSD
// distances between polar spectra, with the NaN-returning form the report prints as "n/a". The
// spectra they compare (and the radial distance the models' fits use) are in
// spectra/power_spectrum.h, below the models.
#pragma once

#include "spectra/power_spectrum.h"

#include <stochtex/metrics.h>

namespace stochtex {

/// The 2D (oriented) log-PSD distance, in dB. Estimator: in each radius bin both spectra have,
/// the finest grouping of the angle cells into d equal sectors (d a divisor of angle_bins, down
/// to d = 1: the radial PSD) in which every sector of both spectra holds ≥ min_samples FFT
/// samples, so periodogram noise (±4.3 dB per sample) stays ≲ 4.3/√(min_samples/2) dB per
/// sector; then RMS of 10·log10(Pa/Pb) over the sectors, each weighted 1/d so every radius bin
/// (a fixed share of an octave) weighs the same, as in log_psd_distance_db. Powers are first
/// raised to a floor 60 dB under the strongest sector of either (an 8-bit photo's quantisation
/// floor against a float render's nothing is a difference no one sees). Throws if no radius bin
/// qualifies (images too small, or different grids).
double polar_log_psd_distance_db(const PolarPsd& a, const PolarPsd& b, int min_samples = resolved_bin_samples);
/// The orientation part of polar_log_psd_distance_db: the same sectors and weights, each
/// sector's power divided by its radius bin's mean power (its own radial PSD there) before the
/// dB difference, so a level error shared by all directions (a missing octave, a gain) drops
/// out and only the angular profiles are compared. 0 in bins where only d = 1 qualifies.
double polar_log_psd_angular_db(const PolarPsd& a, const PolarPsd& b, int min_samples = resolved_bin_samples);

/// polar_log_psd_distance_db and polar_log_psd_angular_db, or NaNs where no radius bin
/// qualifies (compare_images reports that as "n/a" rather than failing on small images the
/// other metrics handle).
struct PolarDistances {
    double total_db, angular_db;
};
PolarDistances polar_distances_or_nan(const PolarPsd& a, const PolarPsd& b, int min_samples);

}  // namespace stochtex
