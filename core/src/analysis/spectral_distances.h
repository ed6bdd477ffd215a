// stochtex — the spectral measures' shared core: one plane's windowed periodogram, computed once
// and read as a radial, a polar and a centred spectrum (compare_images does so for each image),
// and the distances' NaN-returning forms the report prints as "n/a". The spectra and distances
// front-ends and models use are declared in metrics.h.
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
