// Thin, thread-safe wrapper over FFTW3 (single precision) for the analysis and the metrics.
#pragma once

#include <complex>
#include <vector>

namespace stochtex {

/// Unnormalised forward DFT of a real width×height plane (rows contiguous). Returns the half
/// spectrum: height rows of width/2 + 1 bins (FFTW's r2c layout). Safe to call from any thread
/// (FFTW's planner is not, so planning is serialised inside).
std::vector<std::complex<float>> real_fft_2d(const std::vector<float>& plane, int width, int height);

/// real_fft_2d of Moisan's periodic component p of the plane (u = p + s, s smooth): the
/// spectrum of the plane as if it tiled, without the "+" of leakage its edge jumps would add.
/// The DC bin is the plane's.
std::vector<std::complex<float>> periodic_component_fft_2d(const std::vector<float>& plane, int width, int height);

/// Unnormalised inverse of real_fft_2d: the real width×height plane whose DFT has this half
/// spectrum, times width·height.
std::vector<float> real_inverse_fft_2d(const std::vector<std::complex<float>>& half_spectrum, int width, int height);

/// Unnormalised complex DFT of a width×height array in place (forward: e^{−2πi·k·x/n};
/// inverse: e^{+2πi·k·x/n}, without the 1/(width·height)). For analytic (one-sided) band-pass
/// filters, whose outputs are complex: the steerable pyramid's.
void complex_fft_2d(std::vector<std::complex<float>>& data, int width, int height, bool inverse);

}  // namespace stochtex
