// Thin, thread-safe wrapper over FFTW3 (single precision) for the analysis and the metrics.
#pragma once

#include <complex>
#include <vector>

namespace stochtex {

/// Unnormalised forward DFT of a real width×height plane (rows contiguous). Returns the half
/// spectrum: height rows of width/2 + 1 bins (FFTW's r2c layout). Safe to call from any thread
/// (FFTW's planner is not, so planning is serialised inside).
std::vector<std::complex<float>> real_fft_2d(const std::vector<float>& plane, int width, int height);

}  // namespace stochtex
