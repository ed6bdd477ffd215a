// stochtex — texture statistics and distances: the one place where "how close is this
// synthesis to that photo" is defined. Used by tests, `stex compare` and the benchmarks.
#pragma once

#include <stochtex/image.h>

#include <array>
#include <string>
#include <vector>

namespace stochtex {

/// Radially averaged power spectrum of one channel (mean removed, Hann window with power
/// compensation, so non-periodic photos do not leak a "+" into high frequencies).
/// Bins are log-spaced (bins_per_octave per octave) from 1/min(w,h) to 0.5 cycles per pixel;
/// power is the mean |F|² per bin, normalised so that Σ over all bins of the periodogram equals
/// the channel variance (Parseval). Empty bins are dropped.
struct RadialPsd {
    std::vector<double> frequency;  ///< bin centre, cycles per pixel
    std::vector<double> power;      ///< mean periodogram power in the bin
};
RadialPsd radial_psd(const std::vector<float>& plane, int width, int height, int bins_per_octave = 4);

/// RMS over the frequency bins both spectra have (matched by frequency) of 10·log10(Pa/Pb), in dB.
double log_psd_distance_db(const RadialPsd& a, const RadialPsd& b);

/// The orientation of one channel's power spectrum (mean removed; Moisan's periodic component,
/// so image edges add no "+"): the power-weighted mean of e^{2iθ} over all frequencies, θ a
/// frequency's angle from the x axis towards y up. strength in [0, 1] (0: no preferred
/// direction); angle in (−90°, 90°], the dominant frequency direction. A rough surface lit from
/// azimuth φ gains power along φ: relit textures must match their truth in this too.
struct SpectralOrientation {
    double strength = 0, angle_degrees = 0;
};
SpectralOrientation spectral_orientation(const std::vector<float>& plane, int width, int height);

/// 1-Wasserstein distance between the empirical distributions of two samples (any sizes).
double wasserstein1(const std::vector<float>& a, const std::vector<float>& b);

std::array<double, 3> channel_means(const Image& rgb);
std::array<std::array<double, 3>, 3> colour_covariance(const Image& rgb);
/// ‖cov(test) − cov(reference)‖_F / ‖cov(reference)‖_F.
double covariance_relative_error(const Image& reference, const Image& test);

/// Everything `stex compare` prints, per RGB channel where it applies.
struct ComparisonReport {
    std::array<double, 3> mean_reference{}, mean_test{};
    std::array<double, 3> stddev_reference{}, stddev_test{};
    double covariance_error = 0;            ///< relative Frobenius
    std::array<double, 3> w1{};             ///< per channel
    std::array<double, 3> w1_relative{};    ///< w1 / stddev_reference
    std::array<double, 3> log_psd_db{};     ///< per channel
    RadialPsd psd_reference_luma, psd_test_luma;  ///< for plots
};
ComparisonReport compare_images(const Image& reference, const Image& test);
std::string format_report(const ComparisonReport& report);

}  // namespace stochtex
