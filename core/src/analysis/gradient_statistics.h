// stochtex — gradient statistics of one plane (the gradient part of compare_images;
// docs/metrics.md).
#pragma once

#include <vector>

namespace stochtex {

/// Gradients of one plane (central differences on interior pixels, so photos need not tile):
/// orientation φ = atan2(gy, gx) mod 180° with gy towards y up, magnitude |∇|. Histograms of these
/// see edge sharpness (blur lowers |∇| relative to σ) and anisotropy (where the edges point).
struct GradientStatistics {
    /// |∇|-weighted orientation histogram: orientation_bins bins centred on k·180°/orientation_bins,
    /// each φ shared linearly between the two nearest centres (no aliasing of 8-bit gradients'
    /// preferred angles into one bin); sums to 1.
    std::vector<double> orientation;
    /// |∇| / σ of every interior pixel, σ the plane's standard deviation: contrast-free sharpness.
    std::vector<float> magnitude_over_sigma;
};
GradientStatistics gradient_statistics(const std::vector<float>& plane, int width, int height,
                                       int orientation_bins = 36);

}  // namespace stochtex
