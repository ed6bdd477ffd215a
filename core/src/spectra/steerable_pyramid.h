// The complex steerable pyramid (Simoncelli & Freeman 1995; Portilla & Simoncelli 2000, IJCV
// 40(1)), built in the frequency domain on FFTW: the band-pass decomposition whose statistics
// tell structure (edges, cracks, grains) from a spectrum alone.
#pragma once

#include <complex>
#include <vector>

namespace stochtex {

struct SteerablePyramidLevel {
    int width = 0, height = 0;  ///< the level's resolution: the image's halved s times
    /// The low-pass image entering this level (the image with everything finer removed),
    /// rows contiguous.
    std::vector<float> lowpass;
    /// One complex band per orientation θ_k = k·180°/orientations: analytic (one-sided in
    /// frequency), so its real part is the real steerable band and its modulus the local
    /// amplitude, its argument the local phase.
    std::vector<std::vector<std::complex<float>>> bands;
    /// The next coarser level's bands computed at this level's resolution (exactly, as the band
    /// is band-limited): the "parents" P–S correlates with. Empty at the coarsest level.
    std::vector<std::vector<std::complex<float>>> parent_bands;
};

struct SteerablePyramid {
    std::vector<SteerablePyramidLevel> levels;  ///< finest first
    int residual_width = 0, residual_height = 0;
    std::vector<float> residual_lowpass;        ///< what is left under the coarsest band
};

/// The pyramid of a real plane with `scales` levels of `orientations` bands. The plane is taken
/// as its Moisan periodic component (periodic_component_fft_2d), so a photo's edges, which the
/// FFT would join, add no false structure. The high-pass residual above the finest band is
/// dropped. Throws Error unless width and height are positive multiples of 2^scales.
SteerablePyramid build_steerable_pyramid(const std::vector<float>& plane, int width, int height, int scales,
                                         int orientations);

}  // namespace stochtex
