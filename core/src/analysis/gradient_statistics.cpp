// stochtex — gradient orientation and sharpness statistics of a plane
// (analysis/gradient_statistics.h).
#include "analysis/gradient_statistics.h"

#include "numerics/constants.h"

#include <stochtex/error.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace stochtex {

GradientStatistics gradient_statistics(const std::vector<float>& plane, int width, int height, int orientation_bins) {
    if (width < 3 || height < 3 || plane.size() != std::size_t(width) * height)
        throw Error("gradient_statistics: plane of " + std::to_string(plane.size()) + " values does not match a " +
                    std::to_string(width) + "x" + std::to_string(height) + " image of at least 3x3");
    if (orientation_bins < 1)
        throw Error("gradient_statistics: orientation_bins must be at least 1, got " + std::to_string(orientation_bins));
    double mean = 0, mean_square = 0;
    for (float v : plane) mean += v, mean_square += double(v) * v;
    mean /= double(plane.size());
    const double sigma = std::sqrt(std::max(0.0, mean_square / double(plane.size()) - mean * mean));
    if (!(sigma > 0)) throw Error("gradient_statistics: the plane is constant (no gradient to describe)");

    GradientStatistics statistics;
    statistics.orientation.assign(orientation_bins, 0.0);
    statistics.magnitude_over_sigma.reserve(std::size_t(width - 2) * (height - 2));
    const auto at = [&](int x, int y) { return double(plane[std::size_t(y) * width + x]); };
    double total = 0;
    for (int y = 1; y < height - 1; ++y)
        for (int x = 1; x < width - 1; ++x) {
            const double gx = 0.5 * (at(x + 1, y) - at(x - 1, y));
            const double gy = 0.5 * (at(x, y - 1) - at(x, y + 1));  // y up, as spectral_orientation
            const double magnitude = std::hypot(gx, gy);
            statistics.magnitude_over_sigma.push_back(float(magnitude / sigma));
            if (magnitude == 0) continue;
            double position = std::atan2(gy, gx) / kPi * orientation_bins;  // in bins, centres at integers
            position -= orientation_bins * std::floor(position / orientation_bins);
            const int lower = std::min(int(position), orientation_bins - 1);
            const double upper_share = position - lower;
            statistics.orientation[lower] += magnitude * (1 - upper_share);
            statistics.orientation[(lower + 1) % orientation_bins] += magnitude * upper_share;
            total += magnitude;
        }
    for (double& h : statistics.orientation) h /= total;
    return statistics;
}

}  // namespace stochtex
