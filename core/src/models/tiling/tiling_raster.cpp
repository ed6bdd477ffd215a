#include "models/tiling/tiling_raster.h"

#include "numerics/exact_rounding.h"

#include <algorithm>
#include <cstring>

namespace stochtex {

namespace {

constexpr int record = PackedMomentPyramid::record;

/// One texel record as a vector (GCC/Clang vector extension: two SSE registers on the x86-64
/// baseline, one AVX register where the build targets it). Lane-wise products and sums only, so
/// every target computes the same bits.
typedef float Record __attribute__((vector_size(record * sizeof(float))));

inline Record load(const float* p)
{
    Record r;
    std::memcpy(&r, p, sizeof r);
    return r;
}

inline void store(const Record& r, float* p) { std::memcpy(p, &r, sizeof r); }

inline Record splat(float v) { return Record{v, v, v, v, v, v, v, v}; }

/// packed_pairs() at compile time.
template <int Channels>
struct Pairs;
template <>
struct Pairs<1> {
    static constexpr int count = 1;
    static constexpr int first[1] = {0}, second[1] = {0};
};
template <>
struct Pairs<2> {
    static constexpr int count = 3;
    static constexpr int first[3] = {0, 0, 1}, second[3] = {0, 1, 1};
};
template <>
struct Pairs<3> {  // the variances only: what the colour output reads
    static constexpr int count = 3;
    static constexpr int first[3] = {0, 1, 2}, second[3] = {0, 1, 2};
};

/// The bilinear lookup of a level at (x, y) level-0 pixels (MomentPyramid::sample_level_linear's
/// texel centres and wrap), all 8 lanes: branch-free, the two texels along x read as one block.
inline Record bilinear(const PackedMomentPyramid::Level& l, double x, double y)
{
    const double lx = x * l.scale_x - 0.5, ly = y * l.scale_y - 0.5;
    const double x0 = floor_exact(lx), y0 = floor_exact(ly);
    const float tx = float(lx - x0), ty = float(ly - y0);
    const std::int64_t ix = std::int64_t(x0) & l.mask_x, iy = std::int64_t(y0) & l.mask_y;
    const std::int64_t jy = (iy + 1) & l.mask_y;
    const float* r0 = l.data + (std::size_t(iy) * l.row + std::size_t(ix)) * record;
    const float* r1 = l.data + (std::size_t(jy) * l.row + std::size_t(ix)) * record;
    const Record vx = splat(tx), vy = splat(ty), sx = splat(1 - tx), sy = splat(1 - ty);
    const Record low = sx * load(r0) + vx * load(r0 + record), high = sx * load(r1) + vx * load(r1 + record);
    return sy * low + vy * high;
}

}  // namespace

PackedPairs packed_pairs(int channels)
{
    PackedPairs p{};
    auto fill = [&](auto pairs) {
        p.count = pairs.count;
        for (int k = 0; k < pairs.count; ++k) p.first[std::size_t(k)] = pairs.first[k], p.second[std::size_t(k)] = pairs.second[k];
    };
    switch (channels) {
    case 1: fill(Pairs<1>{}); break;
    case 2: fill(Pairs<2>{}); break;
    default: fill(Pairs<3>{}); break;
    }
    return p;
}

PackedMomentPyramid::PackedMomentPyramid(const MomentPyramid& pyramid) : channels_(pyramid.channels())
{
    const PackedPairs pairs = packed_pairs(channels_);
    used_ = channels_ + pairs.count;
    const Moments global = pyramid.global();
    std::vector<std::size_t> offsets;
    std::size_t total = 0;
    for (int l = 0; l < pyramid.level_count(); ++l) {
        const int width = std::max(1, pyramid.width() >> l), height = std::max(1, pyramid.height() >> l);
        offsets.push_back(total);
        total += std::size_t(width + 1) * height * record;
    }
    data_.assign(total, 0.0f);
    for (int l = 0; l < pyramid.level_count(); ++l) {
        const int width = std::max(1, pyramid.width() >> l), height = std::max(1, pyramid.height() >> l);
        float* base = data_.data() + offsets[std::size_t(l)];
        const std::size_t row = std::size_t(width) + 1;
        for (int y = 0; y < height; ++y)
            for (int x = 0; x <= width; ++x) {
                const Moments m = pyramid.texel(l, x, y);  // x = width wraps to the first texel
                float* out = base + (std::size_t(y) * row + std::size_t(x)) * record;
                for (int c = 0; c < channels_; ++c) out[c] = float(m.mean[std::size_t(c)] - global.mean[std::size_t(c)]);
                for (int p = 0; p < pairs.count; ++p) out[channels_ + p] = float(m.moment(pairs.first[std::size_t(p)], pairs.second[std::size_t(p)]));
            }
        levels_.push_back({base, row, width - 1, height - 1, double(width) / pyramid.width(), double(height) / pyramid.height()});
    }
}

TilingRaster::VertexCache::VertexCache(int bits_i, int bits_j)
    : slots_(std::size_t(1) << (bits_i + bits_j), Slot{INT64_MIN, INT64_MIN, 0, 0}),
      mask_i_((std::uint64_t(1) << bits_i) - 1), mask_j_((std::uint64_t(1) << bits_j) - 1), shift_j_(bits_i)
{
}

TilingRaster::TilingRaster(const TilingNoise& noise, const PackedMomentPyramid& pyramid)
    : noise_(noise), pyramid_(pyramid), pairs_(packed_pairs(pyramid.channels()))
{
}

TilingRaster::Plan TilingRaster::plan(const Footprint2D& footprint_px, const FootprintSampling& sampling) const
{
    Plan plan;
    plan.taps = noise_.plan(footprint_px, sampling);
    plan.lower = &pyramid_.level(plan.taps.choice.lower);
    plan.upper = plan.taps.choice.t > 0 ? &pyramid_.level(plan.taps.choice.lower + 1) : nullptr;
    plan.t = float(plan.taps.choice.t);
    const int taps = std::min(plan.taps.na * plan.taps.nb, TapPlan::max_planned_taps);
    for (int k = 0; k < taps; ++k) {
        plan.ratio[std::size_t(k)] = float(plan.taps.ratio[std::size_t(k)]);
        plan.scatter[std::size_t(k)] = float(plan.taps.scatter[std::size_t(k)]);
    }
    plan.weight = float(plan.taps.weight);
    plan.inverse_total = float(1 / plan.taps.total);
    return plan;
}

const double* TilingRaster::translation(std::int64_t i, std::int64_t j, VertexCache& cache) const
{
    VertexCache::Slot& slot =
        cache.slots_[std::size_t((std::uint64_t(i) & cache.mask_i_) | ((std::uint64_t(j) & cache.mask_j_) << cache.shift_j_))];
    if (slot.i != i || slot.j != j) {
        const std::array<double, 2> t = tile_position(noise_.grid().vertex(i, j), 0, 0, noise_.width(), noise_.height());
        slot = {i, j, t[0], t[1]};
    }
    return &slot.dx;
}

const std::array<std::array<double, 2>, 3>& TilingRaster::translations(const TilingGrid::Triangle& triangle, VertexCache& cache) const
{
    if (triangle.i[0] != cache.last_i0_ || triangle.j[0] != cache.last_j0_ || triangle.i[1] != cache.last_i1_) {
        for (int k = 0; k < 3; ++k) {
            const double* t = translation(triangle.i[std::size_t(k)], triangle.j[std::size_t(k)], cache);
            cache.last_[std::size_t(k)] = {t[0], t[1]};
        }
        cache.last_i0_ = triangle.i[0], cache.last_j0_ = triangle.j[0], cache.last_i1_ = triangle.i[1];
    }
    return cache.last_;
}

template <int Channels>
inline void TilingRaster::tap(double x, double y, const TilingGrid::Triangle& triangle, const Plan& plan, VertexCache& cache,
                              float* out) const
{
    // Lanes of the means (1) and of the second moments (0).
    const Record means = Channels == 1 ? Record{1, 0, 0, 0, 0, 0, 0, 0}
                         : Channels == 2 ? Record{1, 1, 0, 0, 0, 0, 0, 0}
                                         : Record{1, 1, 1, 0, 0, 0, 0, 0};
    const Record moments = splat(1) - means;
    Record sum{};
    const std::array<std::array<double, 2>, 3>& shifts = translations(triangle, cache);
    for (int k = 0; k < 3; ++k) {
        const double w = triangle.weight[std::size_t(k)];
        if (w == 0) continue;
        const std::array<double, 2>& shift = shifts[std::size_t(k)];
        const double px = x + shift[0], py = y + shift[1];
        Record sample = bilinear(*plan.lower, px, py);
        if (plan.upper) sample += splat(plan.t) * (bilinear(*plan.upper, px, py) - sample);
        // Means (centred) by w, second moments by w².
        const Record wf = splat(float(w));
        sum += (wf * (means + wf * moments)) * sample;
    }
    store(sum, out);
}

template <int Channels>
void TilingRaster::estimate_for(double x, double y, const Plan& plan, VertexCache& cache, float* out) const
{
    using P = Pairs<Channels>;
    const TapPlan& taps = plan.taps;
    if (taps.na == 1 && taps.nb == 1) return tap<Channels>(x, y, noise_.grid().triangle(x, y), plan, cache, out);
    // The taps' triangles first, all independent (their square roots and divisions overlap),
    // then their lookups.
    const int n = taps.na * taps.nb;
    std::array<double, TapPlan::max_planned_taps> tx, ty;
    std::array<TilingGrid::Triangle, TapPlan::max_planned_taps> triangles;
    for (int j = 0, k = 0; j < taps.nb; ++j)
        for (int i = 0; i < taps.na; ++i, ++k) {
            tx[std::size_t(k)] = x + taps.along_a[std::size_t(i)][0] + taps.along_b[std::size_t(j)][0];
            ty[std::size_t(k)] = y + taps.along_a[std::size_t(i)][1] + taps.along_b[std::size_t(j)][1];
        }
    for (int k = 0; k < n; ++k) triangles[std::size_t(k)] = noise_.grid().triangle(tx[std::size_t(k)], ty[std::size_t(k)]);
    // MomentMixture::add term for term (TilingNoise::planned_estimate), in single precision.
    float result[record] = {};
    for (int k = 0; k < n; ++k) {
        float m[record];
        tap<Channels>(tx[std::size_t(k)], ty[std::size_t(k)], triangles[std::size_t(k)], plan, cache, m);
        float delta[Channels];
        for (int a = 0; a < Channels; ++a) delta[a] = m[a] - result[a];
        const float ratio = plan.ratio[std::size_t(k)], scatter = plan.scatter[std::size_t(k)];
        for (int a = 0; a < Channels; ++a) result[a] += ratio * delta[a];
        for (int p = 0; p < P::count; ++p)
            result[Channels + p] += plan.weight * m[Channels + p] + scatter * (delta[P::first[p]] * delta[P::second[p]]);
    }
    for (int r = 0; r < record; ++r) out[r] = r < Channels ? result[r] : result[r] * plan.inverse_total;
}

void TilingRaster::estimate(double x, double y, const Plan& plan, VertexCache& cache, float* out) const
{
    switch (pyramid_.channels()) {
    case 1: return estimate_for<1>(x, y, plan, cache, out);
    case 2: return estimate_for<2>(x, y, plan, cache, out);
    default: return estimate_for<3>(x, y, plan, cache, out);
    }
}

Moments TilingRaster::unpack(const float* packed) const
{
    const Moments& global = noise_.global();
    Moments m;
    m.channels = global.channels;
    m.mean = global.mean;
    for (int c = 0; c < m.channels; ++c) m.mean[std::size_t(c)] += double(packed[c]);
    for (int p = 0; p < pairs_.count; ++p) {
        const double v = packed[m.channels + p];
        m.moment(pairs_.first[std::size_t(p)], pairs_.second[std::size_t(p)]) = v;
        m.moment(pairs_.second[std::size_t(p)], pairs_.first[std::size_t(p)]) = v;
    }
    return m;
}

}  // namespace stochtex
