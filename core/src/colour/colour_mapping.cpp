#include "colour/colour_mapping.h"

#include "colour/gaussian.h"

namespace stochtex {

ColourMapping::ColourMapping(const TextureDescription& description, const std::array<double, 3>& sigma_m)
    : sigma_m_(sigma_m), chroma_(description.chroma_given_brightness), mean_(description.mean), basis_(description.basis)
{
    for (int c = 0; c < 3; ++c) {
        const HistogramMap& map = description.histograms[c];
        if (map.enabled()) maps_[c] = MonotoneCubic(map.z, map.value);
    }
}

double ColourMapping::map_channel(int c, double z, double dropped_sigma) const
{
    // A Gaussian channel is linear in z: filtering only removes zero-mean detail.
    if (maps_[c].empty()) return z * sigma_m_[c];
    // Below this the quadrature changes the value by less than float precision.
    if (dropped_sigma < 1e-4) return maps_[c](z);
    const GaussHermite& rule = GaussHermite::standard_normal();
    double sum = 0;
    for (int i = 0; i < GaussHermite::count; ++i) sum += rule.weight[i] * maps_[c](z + dropped_sigma * rule.node[i]);
    return sum;
}

Rgb ColourMapping::to_rgb(const std::array<double, 3>& z, const std::array<double, 3>& dropped_sigma) const
{
    std::array<double, 3> y;
    for (int c = 0; c < 3; ++c) y[c] = map_channel(c, z[c], dropped_sigma[c]);
    condition(z[0], dropped_sigma[0], y);
    return combine(y);
}

Rgb ColourMapping::combine(const std::array<double, 3>& y) const
{
    Rgb rgb;
    for (int r = 0; r < 3; ++r)
        rgb[r] = float(mean_[r] + basis_[r][0] * y[0] + basis_[r][1] * y[1] + basis_[r][2] * y[2]);
    return rgb;
}

}  // namespace stochtex
