// A T×T discrete power spectrum, and Welch's estimate of one from a photo channel (paper 003,
// §4.4): the spectra local random-phase noise is fitted to and measured against.
#pragma once

#include <complex>
#include <cstddef>
#include <vector>

namespace stochtex {

/// Power per frequency bin k = (kx, ky), kx, ky in [−T/2, T/2), in cycles per pixel k / T.
/// Normalised by Parseval: Σ_k power = the variance of the signal (a density per bin).
struct DiscreteSpectrum {
    int size = 0;  ///< T
    std::vector<double> power;

    DiscreteSpectrum() = default;
    explicit DiscreteSpectrum(int t) : size(t), power(std::size_t(t) * t, 0.0) {}
    std::size_t index(int kx, int ky) const { return std::size_t(ky + size / 2) * size + std::size_t(kx + size / 2); }
    double& at(int kx, int ky) { return power[index(kx, ky)]; }
    double at(int kx, int ky) const { return power[index(kx, ky)]; }
    double total() const;
};

/// T for a W×H photo: the largest power of two strictly below min(W, H) (paper §4.4), so Welch
/// has several crops along each axis; at most `max_size`.
int welch_size(int width, int height, int max_size = 512);

/// Welch: the average periodogram of T×T crops with 50 % overlap (the last crop of each axis
/// ends on the photo's edge), each with its mean removed and a Hann taper whose power is
/// compensated, so that Σ_k P(k) is the photo's variance. DC is 0.
DiscreteSpectrum welch_psd(const std::vector<float>& plane, int width, int height, int size);

/// Analytic spectra (paper 003, Figs. 3 and 10), sampled on a T×T grid and scaled to `variance`:
/// a ring of radius `radius` with a Gaussian radial profile of standard deviation `width`, and a
/// symmetric pair of Gaussian lobes at ±(fx, fy) with standard deviations `along` (radially) and
/// `across`. Frequencies in cycles per pixel.
DiscreteSpectrum ring_spectrum(int size, double radius, double width, double variance = 1);
DiscreteSpectrum lobe_spectrum(int size, double fx, double fy, double along, double across, double variance = 1);

/// Spectral fidelity (paper 003, P3.8 test 1): the RMS over the bins where the target holds at
/// least `floor` of its peak of 10·log10(measured / target), in dB; and, per label ℓ ≥ 0 (a
/// stratum), Σ measured / Σ target over the bins labelled ℓ.
double log_spectrum_distance_db(const DiscreteSpectrum& measured, const DiscreteSpectrum& target, double floor = 0.01);
/// The same distance between radial averages (log-spaced rings, `bins_per_octave` per octave,
/// from 1/T to Nyquist; DC left out): the shape of an isotropic spectrum without the per-bin
/// noise of a Welch estimate from one photo.
double radial_log_spectrum_distance_db(const DiscreteSpectrum& measured, const DiscreteSpectrum& target,
                                       int bins_per_octave = 4);
std::vector<double> energy_ratios(const DiscreteSpectrum& measured, const DiscreteSpectrum& target,
                                  const std::vector<int>& label);

/// Resemblance of structure: the best normalised cross-correlation (Pearson, in [−1, 1]) of a
/// patch_size² patch with the same-sized windows of a periodic size² reference, over all
/// shifts (1: the patch is a copy of part of the reference). A random-phase synthesis shares no
/// phases with the exemplar and scores only chance-level peaks whatever its spectrum; copies of
/// the exemplar's structure, displaced, raise the peak.
double cross_correlation_peak(const std::vector<float>& patch, int patch_size, const std::vector<float>& reference,
                              int size);

/// Centred bin coordinate of row/column `i` of a T-point DFT (FFTW order): i, or i − T above T/2.
inline int centred_bin(int i, int size) { return i < size / 2 ? i : i - size; }

/// The r2c half spectrum (real_fft_2d layout) of a T×T plane as a full centred complex
/// spectrum c(k), scaled so that plane(n) = Σ_k c(k) e^{2πi k·n/T}.
std::vector<std::complex<double>> full_fourier_coefficients(const std::vector<std::complex<float>>& half, int size);

}  // namespace stochtex
