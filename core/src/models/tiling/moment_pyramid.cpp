#include "models/tiling/moment_pyramid.h"

#include "numerics/exact_rounding.h"

#include <stochtex/error.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace stochtex {

namespace {
bool power_of_two(int n) { return n > 0 && (n & (n - 1)) == 0; }
int wrap(int i, int n) { return ((i % n) + n) % n; }
constexpr int stride = max_moment_channels;
}  // namespace

void MomentMixture::add(double weight, const Moments& part)
{
    // Weighted Welford update: stable, and exactly the law of total variance once all parts are in.
    if (!(weight > 0)) return;
    const double total = weight_ + weight;
    std::array<double, max_moment_channels> delta{};
    for (int a = 0; a < total_.channels; ++a) delta[a] = part.mean[a] - total_.mean[a];
    const double scatter = weight_ * weight / total;
    for (int a = 0; a < total_.channels; ++a) {
        total_.mean[a] += weight / total * delta[a];
        for (int b = 0; b < total_.channels; ++b)
            total_.moment(a, b) += weight * part.moment(a, b) + scatter * delta[a] * delta[b];
    }
    weight_ = total;
}

Moments MomentMixture::result() const
{
    Moments m = total_;
    if (weight_ > 0)
        for (double& s : m.second) s /= weight_;
    return m;
}

Moments MomentPyramid::unpack(const Level& level, std::size_t texel) const
{
    Moments m;
    m.channels = channels_;
    std::copy_n(&level.data[texel * record_], channels_, m.mean.begin());
    const double* second = &level.data[texel * record_ + channels_];
    for (int a = 0; a < channels_; ++a)
        for (int b = a; b < channels_; ++b) m.moment(a, b) = m.moment(b, a) = *second++;
    return m;
}

void MomentPyramid::pack(const Moments& moments, Level& level, std::size_t texel) const
{
    std::copy_n(moments.mean.begin(), channels_, &level.data[texel * record_]);
    double* second = &level.data[texel * record_ + channels_];
    for (int a = 0; a < channels_; ++a)
        for (int b = a; b < channels_; ++b) *second++ = moments.moment(a, b);
}

MomentPyramid::MomentPyramid(const std::vector<std::vector<double>>& planes, int width, int height)
    : channels_(int(planes.size())), pairs_(channels_ * (channels_ + 1) / 2), record_(channels_ + pairs_)
{
    if (channels_ < 1 || channels_ > max_moment_channels) throw Error("moment pyramid: 1 to 3 channels");
    if (!power_of_two(width) || !power_of_two(height))
        throw Error("moment pyramid: sides must be powers of two, got " + std::to_string(width) + "x" +
                    std::to_string(height));
    const std::size_t texels = std::size_t(width) * height;
    Level base{width, height, std::vector<double>(texels * record_, 0.0)};
    for (int c = 0; c < channels_; ++c) {
        if (planes[c].size() != texels) throw Error("moment pyramid: plane size does not match");
        for (std::size_t i = 0; i < texels; ++i) base.data[i * record_ + c] = planes[c][i];
    }
    levels_.push_back(std::move(base));
    while (levels_.back().width > 1 || levels_.back().height > 1) {
        const Level& fine = levels_.back();
        const int fx = fine.width > 1 ? 2 : 1, fy = fine.height > 1 ? 2 : 1;
        Level coarse{fine.width / fx, fine.height / fy, {}};
        const std::size_t count = std::size_t(coarse.width) * coarse.height;
        coarse.data.assign(count * record_, 0.0);
        for (int y = 0; y < coarse.height; ++y)
            for (int x = 0; x < coarse.width; ++x) {
                MomentMixture mixture(channels_);
                for (int dy = 0; dy < fy; ++dy)
                    for (int dx = 0; dx < fx; ++dx)
                        mixture.add(1.0 / (fx * fy), unpack(fine, std::size_t(y * fy + dy) * fine.width + std::size_t(x * fx + dx)));
                pack(mixture.result(), coarse, std::size_t(y) * coarse.width + x);
            }
        levels_.push_back(std::move(coarse));
    }
    for (Level& level : levels_) {
        level.scale_x = double(level.width) / width;
        level.scale_y = double(level.height) / height;
    }
}

Moments MomentPyramid::texel(int level, int x, int y) const
{
    const Level& l = levels_.at(std::size_t(level));
    return unpack(l, std::size_t(wrap(y, l.height)) * l.width + std::size_t(wrap(x, l.width)));
}

Moments MomentPyramid::sample_level(int level, double x, double y, TexelInterpolation interpolation) const
{
    const Level& l = levels_[std::size_t(level)];
    // Level coordinates with texel centres at integers + ½.
    const double lx = x * l.width / width() - 0.5, ly = y * l.height / height() - 0.5;
    const double x0 = std::floor(lx), y0 = std::floor(ly);
    const double tx = lx - x0, ty = ly - y0;
    const int ix = wrap(int(std::fmod(x0, l.width)), l.width), iy = wrap(int(std::fmod(y0, l.height)), l.height);
    const int jx = ix + 1 == l.width ? 0 : ix + 1, jy = iy + 1 == l.height ? 0 : iy + 1;
    const std::size_t texels[4] = {std::size_t(iy) * l.width + ix, std::size_t(iy) * l.width + jx,
                                   std::size_t(jy) * l.width + ix, std::size_t(jy) * l.width + jx};
    const double weights[4] = {(1 - tx) * (1 - ty), tx * (1 - ty), (1 - tx) * ty, tx * ty};
    if (interpolation == TexelInterpolation::mixture) {
        MomentMixture mixture(channels_);
        for (int k = 0; k < 4; ++k) mixture.add(weights[k], unpack(l, texels[k]));
        return mixture.result();
    }
    // Linear: interpolate the packed texels, unpack once (the hot path of every estimate).
    double mean[max_moment_channels] = {0, 0, 0}, second[max_moment_channels * (max_moment_channels + 1) / 2] = {0, 0, 0, 0, 0, 0};
    for (int k = 0; k < 4; ++k) {
        const double w = weights[k];
        if (w == 0) continue;
        const double* m = &l.data[texels[k] * record_];
        const double* c = m + channels_;
        for (int a = 0; a < channels_; ++a) mean[a] += w * m[a];
        for (int p = 0; p < pairs_; ++p) second[p] += w * c[p];
    }
    Moments result;
    result.channels = channels_;
    for (int a = 0; a < channels_; ++a) result.mean[a] = mean[a];
    for (int a = 0, p = 0; a < channels_; ++a)
        for (int b = a; b < channels_; ++b, ++p) result.moment(a, b) = result.moment(b, a) = second[p];
    return result;
}

template <int Channels>
void MomentPyramid::sample_level_linear(int level, double x, double y, double* mean, double* pairs) const
{
    // sample_level(linear) term for term, the channel count known at compile time; the wrap of
    // the (integral) texel index is a mask, the sides being powers of two (the same index fmod
    // and wrap give).
    constexpr int n_pairs = Channels * (Channels + 1) / 2, record = Channels + n_pairs;
    const Level& l = levels_[std::size_t(level)];
    // x · l.width / width() with the ratio (a power of two: exact, so the same double) taken once.
    const double lx = x * l.scale_x - 0.5, ly = y * l.scale_y - 0.5;
    const double x0 = floor_exact(lx), y0 = floor_exact(ly);
    const double tx = lx - x0, ty = ly - y0;
    const std::int64_t mask_x = l.width - 1, mask_y = l.height - 1;
    const std::int64_t ix = std::int64_t(x0) & mask_x, iy = std::int64_t(y0) & mask_y;
    const std::int64_t jx = (ix + 1) & mask_x, jy = (iy + 1) & mask_y;
    const std::size_t texels[4] = {std::size_t(iy * l.width + ix), std::size_t(iy * l.width + jx),
                                   std::size_t(jy * l.width + ix), std::size_t(jy * l.width + jx)};
    const double weights[4] = {(1 - tx) * (1 - ty), tx * (1 - ty), (1 - tx) * ty, tx * ty};
    double sum[record] = {};
    for (int k = 0; k < 4; ++k) {
        const double w = weights[k];
        if (w == 0) continue;
        const double* texel = &l.data[texels[k] * record];
        for (int r = 0; r < record; ++r) sum[r] += w * texel[r];
    }
    for (int a = 0; a < Channels; ++a) mean[a] = sum[a];
    for (int p = 0; p < n_pairs; ++p) pairs[p] = sum[Channels + p];
}

MomentPyramid::LevelChoice MomentPyramid::choose_level(double level) const
{
    level = std::clamp(level, 0.0, double(level_count() - 1));
    const int lower = std::min(int(level), level_count() - 1);
    return {lower, level - lower};
}

template <int Channels>
void MomentPyramid::sample_linear(const LevelChoice& level, double x, double y, double* mean, double* pairs) const
{
    constexpr int n_pairs = Channels * (Channels + 1) / 2;
    sample_level_linear<Channels>(level.lower, x, y, mean, pairs);
    if (level.t == 0) return;
    double upper_mean[Channels], upper_pairs[n_pairs];
    sample_level_linear<Channels>(level.lower + 1, x, y, upper_mean, upper_pairs);
    for (int a = 0; a < Channels; ++a) mean[a] += level.t * (upper_mean[a] - mean[a]);
    for (int p = 0; p < n_pairs; ++p) pairs[p] += level.t * (upper_pairs[p] - pairs[p]);
}

template void MomentPyramid::sample_linear<1>(const LevelChoice&, double, double, double*, double*) const;
template void MomentPyramid::sample_linear<2>(const LevelChoice&, double, double, double*, double*) const;
template void MomentPyramid::sample_linear<3>(const LevelChoice&, double, double, double*, double*) const;

void MomentPyramid::sample_linear(const LevelChoice& level, double x, double y, double* mean, double* pairs) const
{
    switch (channels_) {
    case 1: return sample_linear<1>(level, x, y, mean, pairs);
    case 2: return sample_linear<2>(level, x, y, mean, pairs);
    default: return sample_linear<3>(level, x, y, mean, pairs);
    }
}

Moments MomentPyramid::sample(double level, double x, double y, TexelInterpolation interpolation) const
{
    level = std::clamp(level, 0.0, double(level_count() - 1));
    const int lower = std::min(int(level), level_count() - 1);
    const double t = level - lower;
    const Moments a = sample_level(lower, x, y, interpolation);
    if (t == 0) return a;
    const Moments b = sample_level(lower + 1, x, y, interpolation);
    if (interpolation == TexelInterpolation::mixture) {
        MomentMixture mixture(channels_);
        mixture.add(1 - t, a);
        mixture.add(t, b);
        return mixture.result();
    }
    Moments result = a;
    for (int c = 0; c < stride; ++c) result.mean[c] += t * (b.mean[c] - a.mean[c]);
    for (int s = 0; s < stride * stride; ++s) result.second[s] += t * (b.second[s] - a.second[s]);
    return result;
}

}  // namespace stochtex
