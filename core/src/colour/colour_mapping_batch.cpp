// The batch form of ColourMapping::to_rgb and MonotoneCubic, vectorised with Highway (compiled
// once per instruction set, dispatched at run time). Each kernel performs, lane by lane, the
// scalar code's IEEE operations in the scalar code's order (only Mul, Add, Sub, Div: no fused
// multiply-add), so the values are bit-identical to to_rgb() and operator() on every target.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "colour/colour_mapping_batch.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include "colour/colour_mapping.h"
#include "colour/gaussian.h"
#include "colour/histogram_map.h"
#include "numerics/small_integers-inl.h"
#include "numerics/small_table-inl.h"

#include <algorithm>

#ifndef STOCHTEX_COLOUR_MAPPING_BATCH_ONCE
#define STOCHTEX_COLOUR_MAPPING_BATCH_ONCE
namespace stochtex::colour_batch {
/// A monotone cubic as flat arrays (MonotoneCubic's evaluation form).
struct CubicTable {
    const double *x, *y, *inverse_width, *c1, *c2, *c3;
    std::size_t knots;
    double inverse_step;
    bool uniform;  // false: the segment is found by counting knots (the scalar binary search)
};
}  // namespace stochtex::colour_batch
#endif

HWY_BEFORE_NAMESPACE();
namespace stochtex::colour_batch::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using small_integers::HWY_NAMESPACE::SmallToInt64;
using small_table::HWY_NAMESPACE::SmallTable;  // the knot arrays are short

/// out[i] = f(t[i]): MonotoneCubic::operator(), lane-wise. Lanes outside
/// (x₀, x_n) take an end value; their segment is clamped too, so every read stays inside.
/// `at(index)` locates the lanes' entries once; its result's `(array)` reads one of the arrays
/// there (0 … 5: x, inverse_width, y, c1, c2, c3), so the segment's six reads share the work
/// that depends on the index alone.
template <class At>
void EvalCubicWith(const CubicTable& f, const double* t, double* out, std::size_t count, const At& at)
{
    const hn::ScalableTag<double> d;
    const hn::RebindToSigned<decltype(d)> di;
    const std::size_t lanes = hn::Lanes(d);
    const std::int64_t last_segment = std::int64_t(f.knots) - 2;
    const auto x_front = hn::Set(d, f.x[0]), x_back = hn::Set(d, f.x[f.knots - 1]);
    const auto y_front = hn::Set(d, f.y[0]), y_back = hn::Set(d, f.y[f.knots - 1]);
    const auto inverse_step = hn::Set(d, f.inverse_step), zero = hn::Zero(d);
    const auto top = hn::Set(d, double(last_segment));
    const auto one = hn::Set(di, 1), segment_limit = hn::Set(di, last_segment);
    std::size_t i = 0;
    for (; i + lanes <= count; i += lanes) {
        const auto v = hn::LoadU(d, t + i);
        hn::Vec<decltype(di)> k;
        if (f.uniform) {
            // size_t((t − x₀)·inverse_step), at most the last segment (min and truncation commute).
            const auto position = hn::Min(hn::Max(hn::Mul(hn::Sub(v, x_front), inverse_step), zero), top);
            const auto segment = SmallToInt64(d, position);  // position ∈ [0, knots)
            const auto x_at = at(segment)(0);
            const auto x_next = at(hn::Add(segment, one))(0);
            // Rounding at a knot may pick the neighbouring segment: step back into the right one.
            const auto back = hn::RebindMask(di, hn::Lt(v, x_at));
            const auto forward =
                hn::AndNot(back, hn::And(hn::RebindMask(di, hn::Ge(v, x_next)), hn::Lt(segment, segment_limit)));
            k = hn::IfThenElse(back, hn::Sub(segment, one), hn::IfThenElse(forward, hn::Add(segment, one), segment));
        } else {
            // upper_bound(x, t) − 1: the number of knots ≤ t, less one (exact: no adjustment).
            k = hn::Set(di, -1);
            for (std::size_t knot = 0; knot < f.knots; ++knot)
                k = hn::Sub(k, hn::VecFromMask(di, hn::RebindMask(di, hn::Le(hn::Set(d, f.x[knot]), v))));
            k = hn::Min(k, segment_limit);
        }
        const auto read = at(hn::Max(k, hn::Zero(di)));
        const auto s = hn::Mul(hn::Sub(v, read(0)), read(1));
        const auto inner = hn::Add(read(4), hn::Mul(s, read(5)));
        const auto middle = hn::Add(read(3), hn::Mul(s, inner));
        auto value = hn::Add(read(2), hn::Mul(s, middle));
        value = hn::IfThenElse(hn::Ge(v, x_back), y_back, value);
        value = hn::IfThenElse(hn::Le(v, x_front), y_front, value);
        hn::StoreU(value, d, out + i);
    }
    for (; i < count; ++i) {
        const double v = t[i];
        if (v <= f.x[0]) {
            out[i] = f.y[0];
            continue;
        }
        if (v >= f.x[f.knots - 1]) {
            out[i] = f.y[f.knots - 1];
            continue;
        }
        std::size_t k = f.uniform ? std::size_t((v - f.x[0]) * f.inverse_step)
                                  : std::size_t(std::upper_bound(f.x, f.x + f.knots, v) - f.x) - 1;
        if (k > f.knots - 2) k = f.knots - 2;
        if (v < f.x[k]) --k;
        else if (v >= f.x[k + 1] && k + 2 < f.knots) ++k;
        const double s = (v - f.x[k]) * f.inverse_width[k];
        out[i] = f.y[k] + s * (f.c1[k] + s * (f.c2[k] + s * f.c3[k]));
    }
}

/// EvalCubicWith reading the six arrays as SmallTables of `Vectors` vectors (the x array's
/// count: the others are one entry shorter, their extra vector zero and never selected).
template <std::size_t Vectors, class D>
void EvalCubicFromTables(D d, const CubicTable& f, const small_table::HWY_NAMESPACE::SmallTable<D> (&tables)[6],
                         const double* t, double* out, std::size_t count)
{
    using Located = small_table::HWY_NAMESPACE::SmallTableIndex<D, Vectors>;
    EvalCubicWith(f, t, out, count, [&](hn::Vec<hn::RebindToSigned<D>> index) {
        return [&tables, d, where = Located(d, index)](int array) { return tables[array](d, where); };
    });
}

void EvalCubic(const CubicTable& f, const double* t, double* out, std::size_t count)
{
    // Arrays by number: x, inverse_width, y, c1, c2, c3.
    using D = hn::ScalableTag<double>;
    const D d;
    const double* arrays[6] = {f.x, f.inverse_width, f.y, f.c1, f.c2, f.c3};
    const std::size_t sizes[6] = {f.knots, f.knots - 1, f.knots, f.knots - 1, f.knots - 1, f.knots - 1};
    if (SmallTable<D>::fits(d, f.knots)) {
        const SmallTable<D> tables[6] = {{d, arrays[0], sizes[0]}, {d, arrays[1], sizes[1]},
                                                   {d, arrays[2], sizes[2]}, {d, arrays[3], sizes[3]},
                                                   {d, arrays[4], sizes[4]}, {d, arrays[5], sizes[5]}};
        // The vector count as a constant: no per-read loop or branch over it.
        switch (tables[0].vectors()) {
            case 1: return EvalCubicFromTables<1>(d, f, tables, t, out, count);
            case 2: return EvalCubicFromTables<2>(d, f, tables, t, out, count);
            case 3: return EvalCubicFromTables<3>(d, f, tables, t, out, count);
            default: return EvalCubicFromTables<4>(d, f, tables, t, out, count);
        }
    }
    EvalCubicWith(f, t, out, count, [&](hn::Vec<hn::RebindToSigned<D>> index) {
        return [&arrays, d, index](int array) { return hn::GatherIndex(d, arrays[array], index); };
    });
}

/// z[i] = gain · kept[i] / sigma.
void Normalise(const double* kept, double gain, double sigma, double* z, std::size_t count)
{
    const hn::ScalableTag<double> d;
    const std::size_t lanes = hn::Lanes(d);
    const auto vgain = hn::Set(d, gain), vsigma = hn::Set(d, sigma);
    std::size_t i = 0;
    for (; i + lanes <= count; i += lanes) hn::StoreU(hn::Div(hn::Mul(vgain, hn::LoadU(d, kept + i)), vsigma), d, z + i);
    for (; i < count; ++i) z[i] = gain * kept[i] / sigma;
}

/// out[i] = a[i] · s (s_first false) or a[i] + s (add true).
void Scale(const double* a, double s, double* out, std::size_t count)
{
    const hn::ScalableTag<double> d;
    const std::size_t lanes = hn::Lanes(d);
    const auto vs = hn::Set(d, s);
    std::size_t i = 0;
    for (; i + lanes <= count; i += lanes) hn::StoreU(hn::Mul(hn::LoadU(d, a + i), vs), d, out + i);
    for (; i < count; ++i) out[i] = a[i] * s;
}

void Offset(const double* a, double s, double* out, std::size_t count)
{
    const hn::ScalableTag<double> d;
    const std::size_t lanes = hn::Lanes(d);
    const auto vs = hn::Set(d, s);
    std::size_t i = 0;
    for (; i + lanes <= count; i += lanes) hn::StoreU(hn::Add(hn::LoadU(d, a + i), vs), d, out + i);
    for (; i < count; ++i) out[i] = a[i] + s;
}

/// out[i] = a[i] + s[i] · factor (map_channel's z + σ·node, σ per item).
void OffsetScaled(const double* a, const double* s, double factor, double* out, std::size_t count)
{
    const hn::ScalableTag<double> d;
    const std::size_t lanes = hn::Lanes(d);
    const auto vf = hn::Set(d, factor);
    std::size_t i = 0;
    for (; i + lanes <= count; i += lanes)
        hn::StoreU(hn::Add(hn::LoadU(d, a + i), hn::Mul(hn::LoadU(d, s + i), vf)), d, out + i);
    for (; i < count; ++i) out[i] = a[i] + s[i] * factor;
}

/// sum[i] += weight · f[i].
void AddWeighted(const double* f, double weight, double* sum, std::size_t count)
{
    const hn::ScalableTag<double> d;
    const std::size_t lanes = hn::Lanes(d);
    const auto vw = hn::Set(d, weight);
    std::size_t i = 0;
    for (; i + lanes <= count; i += lanes)
        hn::StoreU(hn::Add(hn::LoadU(d, sum + i), hn::Mul(vw, hn::LoadU(d, f + i))), d, sum + i);
    for (; i < count; ++i) sum[i] += weight * f[i];
}

/// rgb[r][i] = float(((mean[r] + basis[r][0]·y0) + basis[r][1]·y1) + basis[r][2]·y2), stored
/// into the output's channels (interleaved or planar).
void ToRgb(const double* mean, const double* basis, const double* const* y, float* const* channel, std::size_t stride,
           std::size_t count)
{
    const hn::ScalableTag<double> d;
    const hn::Rebind<float, decltype(d)> df;
    const std::size_t lanes = hn::Lanes(d);
    const bool interleaved = stride == 3 && channel[1] == channel[0] + 1 && channel[2] == channel[0] + 2;
    std::size_t i = 0;
    if (interleaved || stride == 1) {
        for (; i + lanes <= count; i += lanes) {
            const auto y0 = hn::LoadU(d, y[0] + i), y1 = hn::LoadU(d, y[1] + i), y2 = hn::LoadU(d, y[2] + i);
            hn::Vec<decltype(df)> rgb[3];
            for (int r = 0; r < 3; ++r) {
                const double* b = basis + 3 * r;
                const auto sum = hn::Add(hn::Add(hn::Add(hn::Set(d, mean[r]), hn::Mul(hn::Set(d, b[0]), y0)),
                                                 hn::Mul(hn::Set(d, b[1]), y1)),
                                         hn::Mul(hn::Set(d, b[2]), y2));
                rgb[r] = hn::DemoteTo(df, sum);
            }
            if (interleaved) {
                hn::StoreInterleaved3(rgb[0], rgb[1], rgb[2], df, channel[0] + 3 * i);
            } else {
                for (int r = 0; r < 3; ++r) hn::StoreU(rgb[r], df, channel[r] + i);
            }
        }
    }
    for (; i < count; ++i)
        for (int r = 0; r < 3; ++r) {
            const double* b = basis + 3 * r;
            channel[r][i * stride] = float(mean[r] + b[0] * y[0][i] + b[1] * y[1][i] + b[2] * y[2][i]);
        }
}

}  // namespace stochtex::colour_batch::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace stochtex {

namespace colour_batch {
HWY_EXPORT(EvalCubic);
HWY_EXPORT(Normalise);
HWY_EXPORT(Scale);
HWY_EXPORT(Offset);
HWY_EXPORT(OffsetScaled);
HWY_EXPORT(AddWeighted);
HWY_EXPORT(ToRgb);
}  // namespace colour_batch

void MonotoneCubic::eval(const double* t, double* out, std::size_t count) const
{
    const colour_batch::CubicTable f{x_.data(), y_.data(), inverse_width_.data(), c1_.data(), c2_.data(),
                                       c3_.data(), x_.size(), inverse_step_, uniform_};
    HWY_DYNAMIC_DISPATCH(colour_batch::EvalCubic)(f, t, out, count);
}

namespace {
// The batch to_rgb()s' block: small enough for the stack and the L1 cache.
constexpr std::size_t colour_block = 256;
}  // namespace

template <class MapBlock, class Sigma0>
void ColourMapping::to_rgb_blocks(const std::array<const double*, 3>& kept, double gain, const MapBlock& map_block,
                                  const Sigma0& sigma0, const RgbOutput& out, std::size_t first, std::size_t count) const
{
    double z[colour_block], y[3][colour_block], z0[colour_block];
    for (std::size_t start = 0; start < count; start += colour_block) {
        const std::size_t n = std::min(colour_block, count - start);
        for (int c = 0; c < 3; ++c) {
            // z as the wavelet's finish() makes it, then map_channel()'s three cases.
            if (sigma_m_[c] > 0) HWY_DYNAMIC_DISPATCH(colour_batch::Normalise)(kept[c] + start, gain, sigma_m_[c], z, n);
            else std::fill(z, z + n, 0.0);
            if (maps_[c].empty()) HWY_DYNAMIC_DISPATCH(colour_batch::Scale)(z, sigma_m_[c], y[c], n);
            else map_block(c, z, y[c], start, n);
            if (c == 0) std::copy(z, z + n, z0);
        }
        if (chroma_.enabled())
            for (std::size_t i = 0; i < n; ++i) {
                // condition()'s arithmetic, item by item: bit-identical to to_rgb().
                std::array<double, 3> item{y[0][i], y[1][i], y[2][i]};
                condition(z0[i], sigma0(start + i), item);
                y[1][i] = item[1], y[2][i] = item[2];
            }
        combine({y[0], y[1], y[2]}, out, first + start, n);
    }
}

void ColourMapping::combine(const std::array<const double*, 3>& y, const RgbOutput& out, std::size_t first, std::size_t count) const
{
    const double flat_basis[9] = {basis_[0][0], basis_[0][1], basis_[0][2], basis_[1][0], basis_[1][1],
                                  basis_[1][2], basis_[2][0], basis_[2][1], basis_[2][2]};
    float* channel[3];
    for (int c = 0; c < 3; ++c) channel[c] = out.channel[c] + first * out.stride;
    HWY_DYNAMIC_DISPATCH(colour_batch::ToRgb)(mean_.data(), flat_basis, y.data(), channel, out.stride, count);
}

void ColourMapping::to_rgb(const std::array<const double*, 3>& kept, double gain,
                           const std::array<double, 3>& dropped_sigma, const RgbOutput& out, std::size_t first,
                           std::size_t count) const
{
    const GaussHermite& rule = GaussHermite::standard_normal();
    const auto map_block = [&](int c, const double* z, double* y, std::size_t, std::size_t n) {
        if (dropped_sigma[c] < 1e-4) return maps_[c].eval(z, y, n);
        double t[colour_block], f[colour_block];
        std::fill(y, y + n, 0.0);
        for (int i = 0; i < GaussHermite::count; ++i) {
            HWY_DYNAMIC_DISPATCH(colour_batch::Offset)(z, dropped_sigma[c] * rule.node[i], t, n);
            maps_[c].eval(t, f, n);
            HWY_DYNAMIC_DISPATCH(colour_batch::AddWeighted)(f, rule.weight[i], y, n);
        }
    };
    to_rgb_blocks(kept, gain, map_block, [&](std::size_t) { return dropped_sigma[0]; }, out, first, count);
}

void ColourMapping::to_rgb(const std::array<const double*, 3>& kept, double gain,
                           const std::array<const double*, 3>& dropped_sigma, const RgbOutput& out, std::size_t first,
                           std::size_t count) const
{
    // map_channel() per item: the quadrature where the item's σ asks for it (every item of the
    // block runs it, those below the threshold then take the plain map's value instead).
    const GaussHermite& rule = GaussHermite::standard_normal();
    const auto map_block = [&](int c, const double* z, double* y, std::size_t start, std::size_t n) {
        const double* sigma = dropped_sigma[c] + start;
        double t[colour_block], f[colour_block];
        std::fill(y, y + n, 0.0);
        for (int i = 0; i < GaussHermite::count; ++i) {
            HWY_DYNAMIC_DISPATCH(colour_batch::OffsetScaled)(z, sigma, rule.node[i], t, n);
            maps_[c].eval(t, f, n);
            HWY_DYNAMIC_DISPATCH(colour_batch::AddWeighted)(f, rule.weight[i], y, n);
        }
        bool any_sharp = false;
        for (std::size_t k = 0; k < n && !any_sharp; ++k) any_sharp = sigma[k] < 1e-4;
        if (!any_sharp) return;
        maps_[c].eval(z, f, n);
        for (std::size_t k = 0; k < n; ++k)
            if (sigma[k] < 1e-4) y[k] = f[k];
    };
    to_rgb_blocks(kept, gain, map_block, [&](std::size_t i) { return dropped_sigma[0][i]; }, out, first, count);
}

}  // namespace stochtex
#endif
