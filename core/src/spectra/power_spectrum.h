// stochtex — one plane's windowed periodogram and the spectra read from it (radial, polar,
// centred), with the radial log-PSD distance: below the models, whose fits measure with them.
// radial_psd and log_psd_distance_db are public (metrics.h); the rest is internal, for the
// models' fits, compare_images (analysis/) and the tests.
#pragma once

#include <stochtex/metrics.h>

#include <complex>
#include <vector>

namespace stochtex {

/// The same periodogram density as radial_psd (mean removed, Hann window, power-compensated,
/// density per unit frequency area, so sizes compare) on a log-polar grid: radial_psd's
/// log-spaced radius bins crossed with angle_bins cells of the frequency angle θ mod 180°
/// (θ from the x axis towards y up; cell k centred on k·180°/angle_bins; a real image's
/// spectrum is point-symmetric, so θ and θ + 180° are the same samples).
struct PolarPsd {
    int bins_per_octave = 4, angle_bins = 12;
    std::vector<double> frequency;  ///< radius bin centres, ascending, as radial_psd's
    /// frequency.size()·angle_bins, radius-major: the mean density and the number of FFT samples
    /// (mirrors counted) of each cell; 0 and 0 where no sample falls.
    std::vector<double> power, samples;
};
PolarPsd polar_psd(const std::vector<float>& plane, int width, int height, int bins_per_octave = 4,
                   int angle_bins = 12);

/// One plane's mean-removed, Hann-windowed spectrum, scaled to a density (the normalisation is
/// explained in power_spectrum.cpp).
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

/// One plane's CentredSpectrum (metrics.h): the report's plotted 2D spectrum.
CentredSpectrum centred_spectrum(const std::vector<float>& plane, int width, int height, int size);

/// log_psd_distance_db, or NaN where the spectra share bins with power but none that both
/// resolve (images too small for the measure: compare_images reports "n/a", as for the 2D one).
double log_psd_distance_or_nan(const RadialPsd& a, const RadialPsd& b, int min_samples);

}  // namespace stochtex
