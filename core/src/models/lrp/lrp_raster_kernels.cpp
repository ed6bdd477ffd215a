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

template <class D>
HWY_INLINE void AccumulateWindowRowOf(D d, const WindowRow& row)
{
    const hn::RebindToSigned<D> di;
    const std::size_t lanes = hn::Lanes(d);
    const LrpWindowTable& window = LrpWindowTable::shared();
    const float* table = window.values();
    const auto scale = hn::Set(d, window.scale());
    const auto extent = hn::Set(d, float(lrp_window_radius * lrp_window_radius));
    const auto ry2 = hn::Set(d, row.ry2);
    const auto zero = hn::Zero(d);
    const std::size_t terms = std::size_t(row.terms), plane = factor_plane(row.terms);
    for (std::size_t k = 0; k < row.count; k += lanes) {
        // LrpWindowTable::operator() (the clamp keeps the gathers in the table; those lanes are 0).
        const auto y2 = hn::Add(hn::LoadU(d, row.rx2 + k), ry2);
        const auto inside = hn::Lt(y2, extent);
        const auto t = hn::Mul(hn::Min(y2, extent), scale);
        const auto i = hn::ConvertTo(di, t);
        const auto f = hn::Sub(t, hn::ConvertTo(d, i));
        const auto v0 = hn::GatherIndex(d, table, i), v1 = hn::GatherIndex(d, table, hn::Add(i, hn::Set(di, 1)));
        const auto w = hn::IfThenElseZero(inside, hn::Add(v0, hn::Mul(f, hn::Sub(v1, v0))));
        const auto live = hn::Gt(w, zero);
        if (hn::AllFalse(d, live)) continue;
        if (terms > 0) {
            // sum_terms_separable: one running sum per channel, term after term.
            hn::Vec<D> local[3] = {zero, zero, zero};
            for (std::size_t term = 0; term < terms; ++term) {
                const auto ca = hn::LoadU(d, row.cosine + term * row.stride + k);
                const auto sa = hn::LoadU(d, row.sine + term * row.stride + k);
                for (std::size_t c = 0; c < 3; ++c)
                    local[c] = hn::Add(local[c], hn::Sub(hn::Mul(ca, hn::Set(d, row.p[c * plane + term])),
                                                         hn::Mul(sa, hn::Set(d, row.q[c * plane + term]))));
            }
            for (int c = 0; c < 3; ++c) {
                const auto sum = hn::LoadU(d, row.sum[c] + k);
                hn::StoreU(hn::IfThenElse(live, hn::Add(sum, hn::Mul(w, local[c])), sum), d, row.sum[c] + k);
            }
        }
        const auto weight = hn::LoadU(d, row.weight + k);
        hn::StoreU(hn::IfThenElse(live, hn::Add(weight, w), weight), d, row.weight + k);
        const auto squared = hn::LoadU(d, row.weight_squared + k);
        hn::StoreU(hn::IfThenElse(live, hn::Add(squared, hn::Mul(w, w)), squared), d, row.weight_squared + k);
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

}  // namespace stochtex::lrp_raster
#endif
