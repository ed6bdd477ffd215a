// stochtex — the orientation of one channel's power spectrum (SpectralOrientation, metrics.h,
// says what it measures): for the measures that compare orientations (ptm's truth comparison,
// the gradient statistics) rather than for front-ends.
#pragma once

#include <stochtex/metrics.h>

#include <vector>

namespace stochtex {

/// Throws Error unless `plane` is a width×height image of at least 2×2.
SpectralOrientation spectral_orientation(const std::vector<float>& plane, int width, int height);

}  // namespace stochtex
