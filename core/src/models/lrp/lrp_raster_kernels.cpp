// Highway compiles this file once per instruction set (foreach_target.h); the entry points at the
// end pick the best one the CPU has. Only Mul, Add and Sub (never MulAdd), lane-wise: the same
// rounding as the scalar code on every target (lrp_raster_kernels.h).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "models/lrp/lrp_raster_kernels.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include <cstdint>

#include "models/lrp/lrp_noise.h"
#include "models/lrp/lrp_raster_kernels.h"
#include "models/lrp/lrp_window.h"
#include "numerics/fast_math-inl.h"

HWY_BEFORE_NAMESPACE();
namespace stochtex::lrp_raster::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

/// fast_sincos_turns (numerics/fast_math.h), lane by lane, operation for operation.
using fast_math::HWY_NAMESPACE::FastSinCosTurns;

/// Runs `body(d)` with the narrowest float vector of at most 4, 8 or the target's lanes that
/// covers `count` in one go where it can: a window a few pixels wide costs a few lanes, not 16.
/// Every lane performs the same operations whatever the width, so the values do not depend on it.
template <class Body>
HWY_INLINE void WithWidthFor(std::size_t count, const Body& body)
{
    const hn::ScalableTag<float> full;
    if (count <= 4 && hn::Lanes(full) > 4) return body(hn::CappedTag<float, 4>());
    if (count <= 8 && hn::Lanes(full) > 8) return body(hn::CappedTag<float, 8>());
    body(full);
}

void SinCosOfProducts(float a, const float* b, std::size_t count, float* sine, float* cosine)
{
    WithWidthFor(count, [&](auto d) {
        const std::size_t lanes = hn::Lanes(d);
        const auto va = hn::Set(d, a);
        for (std::size_t k = 0; k < count; k += lanes) {
            hn::Vec<decltype(d)> s, c;
            FastSinCosTurns(d, hn::Mul(va, hn::LoadU(d, b + k)), s, c);
            hn::StoreU(s, d, sine + k);
            hn::StoreU(c, d, cosine + k);
        }
    });
}

void RowFactors(float dy, const float* fy, const float* const re[3], const float* const im[3], int terms, float* p,
                float* q)
{
    WithWidthFor(std::size_t(terms), [&](auto d) {
        const std::size_t lanes = hn::Lanes(d);
        const auto vdy = hn::Set(d, dy);
        const std::size_t plane = factor_plane(terms);
        for (std::size_t t = 0; t < std::size_t(terms); t += lanes) {
            hn::Vec<decltype(d)> sb, cb;
            FastSinCosTurns(d, hn::Mul(hn::LoadU(d, fy + t), vdy), sb, cb);
            for (int c = 0; c < 3; ++c) {
                const auto vre = hn::LoadU(d, re[c] + t), vim = hn::LoadU(d, im[c] + t);
                hn::StoreU(hn::Sub(hn::Mul(vre, cb), hn::Mul(vim, sb)), d, p + std::size_t(c) * plane + t);
                hn::StoreU(hn::Add(hn::Mul(vre, sb), hn::Mul(vim, cb)), d, q + std::size_t(c) * plane + t);
            }
        }
    });
}

/// Whether y2 = rx² + ry² lies inside the window (LrpWindowTable::operator()'s test). Where no
/// lane is, every weight is 0: the kernels branch on this rather than on w > 0, which comes
/// after the table's gathers (a branch on that waited for them, and mispredicted there).
template <class D>
HWY_INLINE hn::Mask<D> InsideWindow(D d, hn::Vec<D> y2)
{
    return hn::Lt(y2, hn::Set(d, float(lrp_window_radius * lrp_window_radius)));
}

/// LrpWindowTable::operator() at y2 = rx² + ry², lane by lane (the clamp keeps the gathers in
/// the table; those lanes are 0). The table and its scale are fetched once per kernel call, not
/// per vector: LrpWindowTable::shared() is a call into another file, and each call cost a
/// vzeroupper and the live vectors spilled around it.
template <class D>
struct WindowWeights {
    const float* table;
    hn::Vec<D> scale;

    explicit WindowWeights(D d, const LrpWindowTable& window = LrpWindowTable::shared())
        : table(window.values()), scale(hn::Set(d, window.scale()))
    {
    }
    hn::Vec<D> operator()(D d, hn::Vec<D> y2) const
    {
        const hn::RebindToSigned<D> di;
        const auto extent = hn::Set(d, float(lrp_window_radius * lrp_window_radius));
        const auto inside = InsideWindow(d, y2);
        const auto t = hn::Mul(hn::Min(y2, extent), scale);
        // t ≥ 0 (a sum of squares, scaled): int(t) is floor(t), and floor(t) + 2²³ holds it in its
        // low mantissa bits, exactly; f = t − floor(t) as before. (ConvertTo also fixes up lanes
        // out of int32's range: four more operations per vector on AVX-512, for none here.)
        const auto whole = hn::Floor(t);
        const auto i = hn::Sub(hn::BitCast(di, hn::Add(whole, hn::Set(d, 8388608.0f))), hn::Set(di, 0x4B000000));
        const auto f = hn::Sub(t, whole);
        const auto v0 = hn::GatherIndex(d, table, i), v1 = hn::GatherIndex(d, table, hn::Add(i, hn::Set(di, 1)));
        return hn::IfThenElseZero(inside, hn::Add(v0, hn::Mul(f, hn::Sub(v1, v0))));
    }
};

// Where w = 0 (outside the window, or not among a pixel's 3×3), sum_windows skips the window;
// the kernels add w · local, w and w · w anyway, without a select: each is ±0 there (w ≥ 0: the
// table's values are, and so is their interpolation, rounding included), and a sum that starts
// at +0 and only ever has values added is never −0, so adding ±0 leaves its bits as they are.
template <std::size_t Channels, class D>
HWY_INLINE void AddWindowTerms(D d, const WindowTerms& layer, std::size_t k, hn::Vec<D> w)
{
    if (layer.terms == 0) return;
    // sum_terms_separable: one running sum per channel, term after term.
    const auto zero = hn::Zero(d);
    const std::size_t plane = factor_plane(layer.terms);
    hn::Vec<D> local[3] = {zero, zero, zero};
    for (std::size_t term = 0; term < std::size_t(layer.terms); ++term) {
        const auto ca = hn::LoadU(d, layer.cosine + term * layer.stride + k);
        const auto sa = hn::LoadU(d, layer.sine + term * layer.stride + k);
        for (std::size_t c = 0; c < Channels; ++c)
            local[c] = hn::Add(local[c], hn::Sub(hn::Mul(ca, hn::Set(d, layer.p[c * plane + term])),
                                                 hn::Mul(sa, hn::Set(d, layer.q[c * plane + term]))));
    }
    for (std::size_t c = 0; c < Channels; ++c) {
        const auto sum = hn::LoadU(d, layer.sum[c] + k);
        hn::StoreU(hn::Add(sum, hn::Mul(w, local[c])), d, layer.sum[c] + k);
    }
}

template <class D>
HWY_INLINE void AccumulateWindowRowOf(D d, const WindowRow& row)
{
    const std::size_t lanes = hn::Lanes(d);
    const auto ry2 = hn::Set(d, row.ry2);
    const WindowWeights<D> window(d);
    for (std::size_t k = 0; k < row.count; k += lanes) {
        const auto y2 = hn::Add(hn::LoadU(d, row.rx2 + k), ry2);
        if (hn::AllFalse(d, InsideWindow(d, y2))) continue;
        const auto w = window(d, y2);
        for (int l = 0; l < row.layers; ++l) {
            if (row.layer[l].channels == 1)
                AddWindowTerms<1>(d, row.layer[l], k, w);
            else
                AddWindowTerms<3>(d, row.layer[l], k, w);
        }
        const auto weight = hn::LoadU(d, row.weight + k);
        hn::StoreU(hn::Add(weight, w), d, row.weight + k);
        const auto squared = hn::LoadU(d, row.weight_squared + k);
        hn::StoreU(hn::Add(squared, hn::Mul(w, w)), d, row.weight_squared + k);
    }
}

/// sum_windows' last step, value = sum[c] · scale with scale = 1/√weight_squared, 1/weight or 1,
/// for the first `left` lanes: out[c][at…] = value, or with `add` out[c][at…] + value (the sum
/// over strata eval_region makes, in its order).
template <class D>
HWY_INLINE void StoreNormalised(D d, const hn::Vec<D> sum[3], hn::Vec<D> weight, hn::Vec<D> weight_squared,
                                Normalisation normalisation, bool add, std::size_t left, float* const out[3], std::size_t at)
{
    const auto one = hn::Set(d, 1.0f);
    const auto scale = normalisation == Normalisation::variance    ? hn::Div(one, hn::Sqrt(weight_squared))
                       : normalisation == Normalisation::partition ? hn::Div(one, weight)
                                                                   : one;
    for (int c = 0; c < 3; ++c) {
        if (!out[c]) continue;
        const auto value = hn::Mul(sum[c], scale);
        if (left >= hn::Lanes(d)) {
            hn::StoreU(add ? hn::Add(hn::LoadU(d, out[c] + at), value) : value, d, out[c] + at);
        } else {
            // The row's last lanes: no vector load past its end (it may be the buffer's).
            float lanes[hn::MaxLanes(D())];
            hn::StoreU(value, d, lanes);
            for (std::size_t i = 0; i < left; ++i) out[c][at + i] = add ? out[c][at + i] + lanes[i] : lanes[i];
        }
    }
}

void Normalise(const float* const sum[3], const float* weight, const float* weight_squared, std::size_t stride,
               std::size_t width, int rows, Normalisation normalisation, bool add, float* const out[3])
{
    const hn::ScalableTag<float> d;
    const std::size_t lanes = hn::Lanes(d);
    for (std::size_t r = 0; r < std::size_t(rows); ++r)
        for (std::size_t k = 0; k < width; k += lanes) {
            const std::size_t at = r * stride + k;
            const hn::Vec<decltype(d)> sums[3] = {hn::LoadU(d, sum[0] + at), hn::LoadU(d, sum[1] + at),
                                                  hn::LoadU(d, sum[2] + at)};
            StoreNormalised(d, sums, hn::LoadU(d, weight + at), hn::LoadU(d, weight_squared + at), normalisation, add,
                            width - k, out, r * width + k);
        }
}

/// The windows of a vector of pixels, window[k …] (never decreasing along it): factors[window +
/// offset] per lane, by one load of consecutive windows from the first lane's and a lane
/// permutation (`Permute`: the vector spans fewer windows than lanes), else by a gather.
template <class D>
struct LaneWindows {
    using VI = hn::Vec<hn::RebindToSigned<D>>;
    std::int32_t base;
    VI window;
    decltype(hn::IndicesFromVec(D(), VI())) lane;

    LaneWindows(D d, const std::int32_t* first)
        : base(*first),
          window(hn::LoadU(hn::RebindToSigned<D>(), first)),
          // (Masked to the lane count so that the gathering form makes valid indices too.)
          lane(hn::IndicesFromVec(d, hn::And(hn::Sub(window, hn::Set(hn::RebindToSigned<D>(), base)),
                                             hn::Set(hn::RebindToSigned<D>(), std::int32_t(hn::Lanes(d)) - 1))))
    {
    }
    /// Whether the vector from `first` spans fewer windows than lanes (reads a vector of it).
    static bool permutable(D d, const std::int32_t* first)
    {
        return std::size_t(first[hn::Lanes(d) - 1] - first[0]) < hn::Lanes(d);
    }
    template <bool Permute>
    hn::Vec<D> of(D d, const float* factors, std::int32_t offset) const
    {
        if constexpr (Permute)
            return hn::TableLookupLanes(hn::LoadU(d, factors + base + offset), lane);
        else
            return hn::GatherIndex(d, factors, hn::Add(window, hn::Set(hn::RebindToSigned<D>(), offset)));
    }
};

template <bool Permute, class D>
HWY_INLINE void WindowSinCosVector(D d, const float* a, const std::int32_t* index, std::int32_t offset, const float* b,
                                   float* sine, float* cosine)
{
    const LaneWindows<D> windows(d, index);
    hn::Vec<D> s, c;
    FastSinCosTurns(d, hn::Mul(windows.template of<Permute>(d, a, offset), hn::LoadU(d, b)), s, c);
    hn::StoreU(s, d, sine);
    hn::StoreU(c, d, cosine);
}

void GatheredSinCos(const float* a, const std::int32_t* index, std::int32_t offset, const float* b, std::size_t count,
                    float* sine, float* cosine)
{
    const hn::ScalableTag<float> d;
    const std::size_t lanes = hn::Lanes(d);
    for (std::size_t k = 0; k < count; k += lanes) {
        if (LaneWindows<decltype(d)>::permutable(d, index + k))
            WindowSinCosVector<true>(d, a, index + k, offset, b + k, sine + k, cosine + k);
        else
            WindowSinCosVector<false>(d, a, index + k, offset, b + k, sine + k, cosine + k);
    }
}

/// One vector of pixels of a PixelRow from k: the 3×3 windows in sum_windows' order, then the
/// normalisation; each lane's row factors by LaneWindows.
template <bool Permute, class D>
HWY_INLINE void PixelVector(D d, const PixelRow& row, const WindowWeights<D>& window, std::size_t k)
{
    const auto zero = hn::Zero(d);
    const LaneWindows<D> windows(d, row.window + k);
    hn::Vec<D> sum[3] = {zero, zero, zero};
    auto weight = zero, weight_squared = zero;
    for (int dj = 0; dj < 3; ++dj) {
        if (!row.reaches[dj]) continue;
        const auto ry2 = hn::Set(d, row.ry2[dj]);
        const std::size_t terms = std::size_t(row.terms[dj]);
        for (int dix = 0; dix < 3; ++dix) {
            const auto y2 = hn::Add(hn::LoadU(d, row.rx2 + std::size_t(dix) * row.stride + k), ry2);
            if (hn::AllFalse(d, InsideWindow(d, y2))) continue;
            const auto w = window(d, y2);
            // Slot dix's window of each lane is window + dix − 1.
            const auto expand = [&](const float* factors) { return windows.template of<Permute>(d, factors, dix - 1); };
            // sum_terms_separable's running sums, the window's zero terms past its live ones
            // included (they add ±0 to a sum that is never −0: no change).
            hn::Vec<D> local[3] = {zero, zero, zero};
            for (std::size_t t = 0; t < terms; ++t) {
                const std::size_t column = (std::size_t(dix) * terms + t) * row.stride + k;
                const auto ca = hn::LoadU(d, row.cosine[dj] + column);
                const auto sa = hn::LoadU(d, row.sine[dj] + column);
                for (std::size_t c = 0; c < 3; ++c) {
                    const std::size_t factor = c * row.plane[dj] + t * row.windows;
                    local[c] = hn::Add(local[c], hn::Sub(hn::Mul(ca, expand(row.p[dj] + factor)),
                                                         hn::Mul(sa, expand(row.q[dj] + factor))));
                }
            }
            // sum_windows: a window of no live terms adds w · 0 (the same: sum is never −0), and
            // lanes of w = 0 add ±0 (see AccumulateWindowRowOf).
            for (int c = 0; c < 3; ++c) sum[c] = hn::Add(sum[c], hn::Mul(w, local[c]));
            weight = hn::Add(weight, w);
            weight_squared = hn::Add(weight_squared, hn::Mul(w, w));
        }
    }
    StoreNormalised(d, sum, weight, weight_squared, row.normalisation, row.add, row.count - k, row.out, k);
}

void AccumulatePixelRow(const PixelRow& row)
{
    const hn::ScalableTag<float> d;
    const std::size_t lanes = hn::Lanes(d);
    const WindowWeights<hn::ScalableTag<float>> window(d);
    for (std::size_t k = 0; k < row.count; k += lanes) {
        // (The padding repeats the last window: a vector past the row reads its own padding.)
        if (LaneWindows<decltype(d)>::permutable(d, row.window + k))
            PixelVector<true>(d, row, window, k);
        else
            PixelVector<false>(d, row, window, k);
    }
}

void SumTermsAt(const LrpTermView& terms, const float* dx, const float* dy, std::size_t count, float* const out[3])
{
    const hn::ScalableTag<float> d;
    const std::size_t lanes = hn::Lanes(d);
    const auto zero = hn::Zero(d);
    const float* fx = terms.fx();
    const float* fy = terms.fy();
    const float* re[3] = {terms.re(0), terms.re(1), terms.re(2)};
    const float* im[3] = {terms.im(0), terms.im(1), terms.im(2)};
    for (std::size_t k = 0; k < count; k += lanes) {
        const auto vdx = hn::LoadU(d, dx + k), vdy = hn::LoadU(d, dy + k);
        hn::Vec<decltype(d)> partial[4][3];
        for (auto& lane : partial)
            for (auto& channel : lane) channel = zero;
        for (int t = 0; t < terms.count; t += 4)
            for (int l = 0; l < 4; ++l) {
                const std::size_t term = std::size_t(t + l);
                const auto turns = hn::Add(hn::Mul(hn::Set(d, fx[term]), vdx), hn::Mul(hn::Set(d, fy[term]), vdy));
                hn::Vec<decltype(d)> sine, cosine;
                FastSinCosTurns(d, turns, sine, cosine);
                for (int c = 0; c < 3; ++c)
                    partial[l][c] = hn::Add(partial[l][c], hn::Sub(hn::Mul(hn::Set(d, re[c][term]), cosine),
                                                                   hn::Mul(hn::Set(d, im[c][term]), sine)));
            }
        for (int c = 0; c < 3; ++c)
            hn::StoreU(hn::Add(hn::Add(partial[0][c], partial[1][c]), hn::Add(partial[2][c], partial[3][c])), d, out[c] + k);
    }
}

void AccumulateWindowRow(const WindowRow& row)
{
    WithWidthFor(row.count, [&](auto d) { AccumulateWindowRowOf(d, row); });
}

}  // namespace stochtex::lrp_raster::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace stochtex::lrp_raster {

HWY_EXPORT(SinCosOfProducts);
HWY_EXPORT(AccumulateWindowRow);
HWY_EXPORT(RowFactors);
HWY_EXPORT(SumTermsAt);
HWY_EXPORT(GatheredSinCos);
HWY_EXPORT(AccumulatePixelRow);
HWY_EXPORT(Normalise);

void sincos_of_products(float a, const float* b, std::size_t count, float* sine, float* cosine)
{
    HWY_DYNAMIC_DISPATCH(SinCosOfProducts)(a, b, count, sine, cosine);
}

void row_factors(float dy, const float* fy, const float* const re[3], const float* const im[3], int terms, float* p,
                 float* q)
{
    HWY_DYNAMIC_DISPATCH(RowFactors)(dy, fy, re, im, terms, p, q);
}

void sum_terms_at(const LrpTermView& terms, const float* dx, const float* dy, std::size_t count, float* const out[3])
{
    HWY_DYNAMIC_DISPATCH(SumTermsAt)(terms, dx, dy, count, out);
}

void accumulate_window_row(const WindowRow& row)
{
    HWY_DYNAMIC_DISPATCH(AccumulateWindowRow)(row);
}

void gathered_sincos(const float* a, const std::int32_t* index, std::int32_t offset, const float* b, std::size_t count,
                     float* sine, float* cosine)
{
    HWY_DYNAMIC_DISPATCH(GatheredSinCos)(a, index, offset, b, count, sine, cosine);
}

void accumulate_pixel_row(const PixelRow& row)
{
    HWY_DYNAMIC_DISPATCH(AccumulatePixelRow)(row);
}

void normalise(const float* const sum[3], const float* weight, const float* weight_squared, std::size_t stride,
               std::size_t width, int rows, Normalisation normalisation, bool add, float* const out[3])
{
    HWY_DYNAMIC_DISPATCH(Normalise)(sum, weight, weight_squared, stride, width, rows, normalisation, add, out);
}

}  // namespace stochtex::lrp_raster
#endif
