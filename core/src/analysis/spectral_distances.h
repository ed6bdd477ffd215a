// stochtex — the spectral measures only compare_images and the tests call: the 2D log-PSD
// distances, the centred spectrum, and their shared core, one plane's windowed periodogram
// computed once and read as a radial, a polar and a centred spectrum, with the distances'
// NaN-returning forms the report prints as "n/a". The spectra and distances front-ends and
// models use are declared in metrics.h.
#pragma once

#include <stochtex/metrics.h>

#include <complex>
#include <vector>

namespace stochtex {

/// One plane's mean-removed, Hann-windowed spectrum, scaled to a density (the normalisation is
/// explained in spectral_distances.cpp).
struct WindowedSpectrum {
    int width = 0, height = 0;
    std::vector<std::complex<float>> half;  ///< real_fft_2d layout
    double density_scale = 0;               ///< S = |F|²·density_scale
};
/// Throws Error, its message starting with `caller`, unless `plane` is a width×height image of
/// at least 2×2.
WindowedSpectrum windowed_spectrum(const std::vector<float>& plane, int width, int height, const char* caller);

/// radial_psd, polar_psd and centred_spectrum of a spectrum already windowed; the callers
/// check the bin counts and size.
RadialPsd radial_psd_of(const WindowedSpectrum& spectrum, int bins_per_octave);
PolarPsd polar_psd_of(const WindowedSpectrum& spectrum, int bins_per_octave, int angle_bins);
CentredSpectrum centred_spectrum_of(const WindowedSpectrum& spectrum, int size);

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

/// One plane's CentredSpectrum (metrics.h): the report's plotted 2D spectrum.
CentredSpectrum centred_spectrum(const std::vector<float>& plane, int width, int height, int size);

/// polar_log_psd_distance_db and polar_log_psd_angular_db, or NaNs where no radius bin
/// qualifies (compare_images reports that as "n/a" rather than failing on small images the
/// other metrics handle).
struct PolarDistances {
    double total_db, angular_db;
};
PolarDistances polar_distances_or_nan(const PolarPsd& a, const PolarPsd& b, int min_samples);

/// log_psd_distance_db, or NaN where the spectra share bins with power but none that both
/// resolve (images too small for the measure: compare_images reports "n/a", as for the 2D one).
double log_psd_distance_or_nan(const RadialPsd& a, const RadialPsd& b, int min_samples);

}  // namespace stochtex
