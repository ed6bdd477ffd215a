#include "models/tiling/tiling_noise.h"

#include <algorithm>
#include <cmath>

namespace stochtex {

TilingNoise::TilingNoise(std::shared_ptr<const MomentPyramid> pyramid, TilingGrid grid)
    : pyramid_(std::move(pyramid)), grid_(grid), global_(pyramid_->global())
{
}

Moments TilingNoise::estimate(double x, double y, double level, TexelInterpolation interpolation,
                              const TileBlend& blend) const
{
    Moments result;
    result.channels = channels();
    result.mean = global_.mean;
    for (const TileVertex& vertex : blend) {
        if (vertex.weight == 0) continue;
        const std::array<double, 2> t = tile_position(vertex, x, y, width(), height());
        const Moments tile = pyramid_->sample(level, t[0], t[1], interpolation);
        const double w = vertex.weight, w2 = w * w;
        for (int a = 0; a < channels(); ++a) {
            result.mean[a] += w * (tile.mean[a] - global_.mean[a]);
            for (int b = 0; b < channels(); ++b) result.moment(a, b) += w2 * tile.moment(a, b);
        }
    }
    return result;
}

Moments TilingNoise::texel_estimate(double x, double y, double level, TexelInterpolation interpolation) const
{
    return estimate(x, y, level, interpolation, grid_.blend(x, y));
}

Moments TilingNoise::footprint_estimate(double x, double y, const Footprint2D& footprint_px,
                                        const FootprintSampling& sampling) const
{
    // The footprint's columns a = ∂(x, y)/∂screen x and b = ∂(x, y)/∂screen y, in exemplar pixels.
    const double a[2] = {footprint_px.dudx, footprint_px.dvdx}, b[2] = {footprint_px.dudy, footprint_px.dvdy};
    const double length_a = std::hypot(a[0], a[1]);
    const double length_b = std::hypot(b[0], b[1]);
    // Taps per axis: `taps` along the shorter axis, proportionally more along the longer one
    // (bounded); an axis shorter than a pixel needs no taps (level 0 is the exemplar itself).
    const double minor = std::max(1e-12, std::min(length_a, length_b));
    auto taps_along = [&](double length) {
        if (length <= 1) return 1;
        return std::clamp(int(std::lround(sampling.taps * length / std::max(minor, 1.0))), std::max(1, sampling.taps),
                          std::max(sampling.taps, sampling.max_taps));
    };
    const int na = taps_along(length_a), nb = taps_along(length_b);
    // Each tap stands for a (length/n)-sized piece: its level is that size's log2.
    const double piece = std::max(length_a / na, length_b / nb);
    const double level = piece > 1 ? std::log2(piece) : 0.0;
    if (na == 1 && nb == 1) return texel_estimate(x, y, level, sampling.interpolation);
    MomentMixture mixture(channels());
    const double weight = 1.0 / (na * nb);
    for (int j = 0; j < nb; ++j)
        for (int i = 0; i < na; ++i) {
            const double s = (i + 0.5) / na - 0.5, t = (j + 0.5) / nb - 0.5;
            const double px = x + s * a[0] + t * b[0];
            const double py = y + s * a[1] + t * b[1];
            mixture.add(weight, texel_estimate(px, py, level, sampling.interpolation));
        }
    return mixture.result();
}

}  // namespace stochtex
