#include "models/tiling/tiling_noise.h"

#include <algorithm>
#include <cmath>
#include <utility>

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
    TileCache cache;
    return footprint_estimate(x, y, plan(footprint_px, sampling), cache);
}

TapPlan TilingNoise::plan(const Footprint2D& footprint_px, const FootprintSampling& sampling) const
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
    TapPlan plan;
    plan.na = std::min(taps_along(length_a), TapPlan::max_taps_per_axis);
    plan.nb = std::min(taps_along(length_b), TapPlan::max_taps_per_axis);
    // Each tap stands for a (length/n)-sized piece: its level is that size's log2.
    const double piece = std::max(length_a / plan.na, length_b / plan.nb);
    plan.level = piece > 1 ? std::log2(piece) : 0.0;
    plan.choice = pyramid_->choose_level(plan.level);
    plan.interpolation = sampling.interpolation;
    for (int i = 0; i < plan.na; ++i) {
        const double s = (i + 0.5) / plan.na - 0.5;
        plan.along_a[i] = {s * a[0], s * a[1]};
    }
    for (int j = 0; j < plan.nb; ++j) {
        const double t = (j + 0.5) / plan.nb - 0.5;
        plan.along_b[j] = {t * b[0], t * b[1]};
    }
    // MomentMixture::add's coefficients, which depend on the (equal) weights alone.
    plan.weight = 1.0 / (plan.na * plan.nb);
    double total = 0;
    for (int k = 0; k < std::min(plan.na * plan.nb, TapPlan::max_planned_taps); ++k) {
        const double next = total + plan.weight;
        plan.ratio[k] = plan.weight / next;
        plan.scatter[k] = total * plan.weight / next;
        total = next;
    }
    plan.total = total;
    return plan;
}

template <int Channels>
void TilingNoise::tap_moments(double x, double y, const TapPlan& plan, TileCache& cache, double* mean, double* pairs) const
{
    // estimate() with the packed linear lookup: per channel pair the same sums in the same order.
    constexpr int n_pairs = Channels * (Channels + 1) / 2;
    const TileBlend blend = grid_.blend(x, y, cache);
    for (int a = 0; a < Channels; ++a) mean[a] = global_.mean[a];
    for (int p = 0; p < n_pairs; ++p) pairs[p] = 0;
    for (const TileVertex& vertex : blend) {
        if (vertex.weight == 0) continue;
        const std::array<double, 2> t = tile_position(vertex, x, y, width(), height());
        double tile_mean[Channels], tile_pairs[n_pairs];
        pyramid_->sample_linear<Channels>(plan.choice, t[0], t[1], tile_mean, tile_pairs);
        const double w = vertex.weight, w2 = w * w;
        for (int a = 0; a < Channels; ++a) mean[a] += w * (tile_mean[a] - global_.mean[a]);
        for (int p = 0; p < n_pairs; ++p) pairs[p] += w2 * tile_pairs[p];
    }
}

namespace {
/// The index of moment (a, b) in the packed upper triangle of `Channels` channels.
template <int Channels>
constexpr int pair_index(int a, int b)
{
    if (a > b) std::swap(a, b);
    return a * Channels - a * (a - 1) / 2 + (b - a);
}
}  // namespace

template <int Channels>
Moments TilingNoise::planned_estimate(double x, double y, const TapPlan& plan, TileCache& cache) const
{
    constexpr int n_pairs = Channels * (Channels + 1) / 2;
    Moments result;
    result.channels = Channels;
    double mean[Channels], pairs[n_pairs];
    if (plan.na == 1 && plan.nb == 1) {
        tap_moments<Channels>(x, y, plan, cache, mean, pairs);
        result.mean = global_.mean;
        for (int a = 0; a < Channels; ++a) result.mean[a] = mean[a];
        for (int a = 0; a < Channels; ++a)
            for (int b = 0; b < Channels; ++b) result.moment(a, b) = pairs[pair_index<Channels>(a, b)];
        return result;
    }
    // MomentMixture::add term for term, its weight ratios from the plan (result: zero-initialised).
    int k = 0;
    for (int j = 0; j < plan.nb; ++j)
        for (int i = 0; i < plan.na; ++i, ++k) {
            const double px = x + plan.along_a[i][0] + plan.along_b[j][0];
            const double py = y + plan.along_a[i][1] + plan.along_b[j][1];
            tap_moments<Channels>(px, py, plan, cache, mean, pairs);
            double delta[Channels];
            for (int a = 0; a < Channels; ++a) delta[a] = mean[a] - result.mean[a];
            for (int a = 0; a < Channels; ++a) {
                result.mean[a] += plan.ratio[k] * delta[a];
                for (int b = 0; b < Channels; ++b)
                    result.moment(a, b) += plan.weight * pairs[pair_index<Channels>(a, b)] + plan.scatter[k] * delta[a] * delta[b];
            }
        }
    for (double& s : result.second) s /= plan.total;
    return result;
}

Moments TilingNoise::tap_estimate(double x, double y, const TapPlan& plan, TileCache& cache) const
{
    const TileBlend blend = grid_.blend(x, y, cache);
    if (plan.interpolation != TexelInterpolation::linear) return estimate(x, y, plan.level, plan.interpolation, blend);
    // estimate() with the packed linear lookup: per channel pair the same sums in the same order.
    const int n = channels(), pairs = pyramid_->pairs();
    double mean[max_moment_channels], second[max_moment_channels * (max_moment_channels + 1) / 2] = {};
    for (int a = 0; a < n; ++a) mean[a] = global_.mean[a];
    for (const TileVertex& vertex : blend) {
        if (vertex.weight == 0) continue;
        const std::array<double, 2> t = tile_position(vertex, x, y, width(), height());
        double tile_mean[max_moment_channels], tile_pairs[max_moment_channels * (max_moment_channels + 1) / 2];
        pyramid_->sample_linear(plan.choice, t[0], t[1], tile_mean, tile_pairs);
        const double w = vertex.weight, w2 = w * w;
        for (int a = 0; a < n; ++a) mean[a] += w * (tile_mean[a] - global_.mean[a]);
        for (int p = 0; p < pairs; ++p) second[p] += w2 * tile_pairs[p];
    }
    Moments result;
    result.channels = n;
    result.mean = global_.mean;
    for (int a = 0; a < n; ++a) result.mean[a] = mean[a];
    for (int a = 0, p = 0; a < n; ++a)
        for (int b = a; b < n; ++b, ++p) result.moment(a, b) = result.moment(b, a) = second[p];
    return result;
}

Moments TilingNoise::footprint_estimate(double x, double y, const TapPlan& plan, TileCache& cache) const
{
    if (plan.interpolation == TexelInterpolation::linear && plan.na * plan.nb <= TapPlan::max_planned_taps) {
        switch (channels()) {
        case 1: return planned_estimate<1>(x, y, plan, cache);
        case 2: return planned_estimate<2>(x, y, plan, cache);
        default: return planned_estimate<3>(x, y, plan, cache);
        }
    }
    if (plan.na == 1 && plan.nb == 1) return tap_estimate(x, y, plan, cache);
    MomentMixture mixture(channels());
    const double weight = 1.0 / (plan.na * plan.nb);
    for (int j = 0; j < plan.nb; ++j)
        for (int i = 0; i < plan.na; ++i) {
            const double px = x + plan.along_a[i][0] + plan.along_b[j][0];
            const double py = y + plan.along_a[i][1] + plan.along_b[j][1];
            mixture.add(weight, tap_estimate(px, py, plan, cache));
        }
    return mixture.result();
}

}  // namespace stochtex
