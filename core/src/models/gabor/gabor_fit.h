// "Gabor octaves" by example: the octave weights, frequencies, bandwidth and orientation of a
// gabor texture from a photo's decorrelated (and Gaussianised) channels (paper 001, Fig. 6/7
// pipeline, on paper 000's analysis).
//
// Each channel's radially averaged spectrum (metrics.h, as variance per octave,
// octave_spectrum.h) is fitted by non-negative least squares with octave-spaced copies of one
// octave's spectrum (fit_octaves), the octaves shared by the three channels. The octave spectrum
// is that of the *slice* the renders show, not the 2D ring of a textbook Gabor octave: a slice of
// isotropic solid noise projects the sphere of frequencies onto the plane, so each octave also
// puts power below its frequency (about 13 % of it more than an octave lower), and a fit with
// rings would render solid slices with too much low-frequency power (measured in
// tests/gabor_test.cpp, docs/models/gabor.md). The weights are then scaled so each channel's
// variance is the photo's exactly.
//
// Oriented octaves (kind oriented, gabor_parameters.h). Each octave k's annulus of the photo's 2D
// power spectrum, [F_k/√2, F_k·√2], gives the power-weighted mean of e^{2iθ} over its
// frequencies: its argument is the octave's orientation, and its length — debiased for the
// periodogram's noise, then divided by the length an all-oriented octave of this bandwidth has
// in that annulus — the octave's oriented fraction (an isotropic octave's length is 0, and a
// mixture's is linear in the fraction). The weights are then refitted with the sliced spectrum
// of the octaves' mean mixture.
#pragma once

#include <stochtex/texture_description.h>
#include <stochtex/models/gabor_parameters.h>

#include <array>
#include <vector>

namespace stochtex {

struct GaborFitOptions {
    GaborKind kind = GaborKind::isotropic;
    /// With kind oriented: write kind isotropic (no per-octave arrays) when no octave is oriented,
    /// the isotropic fit exactly (`--gabor-kind auto`).
    bool isotropic_if_unoriented = false;
    double impulses_per_kernel = 16;
    double bandwidth = 0;  ///< a/F; 0: chosen by the fit (isotropic, hybrid) or from the anisotropy
    int octaves = 8;
    /// Fit the sliced octave spectra (the default). false: the 2D rings, to measure what the
    /// correction brings.
    bool slice_correction = true;
};

/// The fitted parameters; channels are width·height planes. Throws Error for unusable input.
GaborParameters fit_gabor_octaves(const std::array<std::vector<float>, 3>& channels, int width, int height,
                                  const GaborFitOptions& options);

}  // namespace stochtex
