// Highway compiles this file once per instruction set (foreach_target.h); the entry points at the
// end pick the best one the CPU has. Only Mul and Add (never MulAdd), lane-wise: the same
// rounding as the scalar code on every target.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "models/wavelet/wavelet_raster_kernels.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include <cmath>

#include "models/wavelet/wavelet_raster_kernels.h"

HWY_BEFORE_NAMESPACE();
namespace stochtex::wavelet_raster::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

void CombineRows(const float* w, const float* at, std::size_t stride, std::size_t count, float* out)
{
    const hn::ScalableTag<float> d;
    const std::size_t lanes = hn::Lanes(d);
    const auto w0 = hn::Set(d, w[0]), w1 = hn::Set(d, w[1]), w2 = hn::Set(d, w[2]);
    std::size_t k = 0;
    for (; k + lanes <= count; k += lanes) {
        const auto a0 = hn::LoadU(d, at + k), a1 = hn::LoadU(d, at + k + stride), a2 = hn::LoadU(d, at + k + 2 * stride);
        hn::StoreU(hn::Add(hn::Add(hn::Mul(w0, a0), hn::Mul(w1, a1)), hn::Mul(w2, a2)), d, out + k);
    }
    for (; k < count; ++k) out[k] = w[0] * at[k] + w[1] * at[k + stride] + w[2] * at[k + 2 * stride];
}

void CombinePlanes(const float* wz, const float* wy, const float* const* rows, std::size_t count, float* out)
{
    const hn::ScalableTag<float> d;
    const std::size_t lanes = hn::Lanes(d);
    const auto y0 = hn::Set(d, wy[0]), y1 = hn::Set(d, wy[1]), y2 = hn::Set(d, wy[2]);
    const auto z0 = hn::Set(d, wz[0]), z1 = hn::Set(d, wz[1]), z2 = hn::Set(d, wz[2]);
    std::size_t x = 0;
    for (; x + lanes <= count; x += lanes) {
        hn::Vec<decltype(d)> plane[3];
        for (int k = 0; k < 3; ++k) {
            const float* const* r = rows + 3 * k;
            plane[k] = hn::Add(hn::Add(hn::Mul(y0, hn::LoadU(d, r[0] + x)), hn::Mul(y1, hn::LoadU(d, r[1] + x))),
                               hn::Mul(y2, hn::LoadU(d, r[2] + x)));
        }
        hn::StoreU(hn::Add(hn::Add(hn::Mul(z0, plane[0]), hn::Mul(z1, plane[1])), hn::Mul(z2, plane[2])), d, out + x);
    }
    for (; x < count; ++x) {
        float plane[3];
        for (int k = 0; k < 3; ++k) {
            const float* const* r = rows + 3 * k;
            plane[k] = wy[0] * r[0][x] + wy[1] * r[1][x] + wy[2] * r[2][x];
        }
        out[x] = wz[0] * plane[0] + wz[1] * plane[1] + wz[2] * plane[2];
    }
}

void SplinesOfColumns(const ColumnPositions& p, std::size_t count, std::int32_t* index, float* w0, float* w1, float* w2)
{
    const hn::ScalableTag<double> dd;
    const hn::Rebind<float, decltype(dd)> df;
    const hn::Rebind<std::int32_t, decltype(dd)> di;
    const std::size_t lanes = hn::Lanes(dd);
    const auto origin = hn::Set(dd, p.origin_u), du = hn::Set(dd, p.du), scale = hn::Set(dd, p.scale);
    const auto offset = hn::Set(dd, p.offset), half = hn::Set(dd, 0.5), period = hn::Set(dd, double(p.period));
    const auto inverse_period = hn::Set(dd, p.inverse_period);
    const auto one = hn::Set(df, 1.0f), halff = hn::Set(df, 0.5f);
    std::size_t i = 0;
    for (; i + lanes <= count; i += lanes) {
        const auto pixel = hn::Iota(dd, double(p.x0 + std::int64_t(i)));
        const auto x = hn::Add(hn::Mul(hn::Add(origin, hn::Mul(hn::Add(pixel, half), du)), scale), offset);
        const auto shifted = hn::Sub(x, half);
        const auto base = hn::Floor(shifted);
        const auto t = hn::DemoteTo(df, hn::Sub(shifted, base));
        const auto wrapped = hn::Sub(base, hn::Mul(period, hn::Floor(hn::Mul(base, inverse_period))));
        hn::StoreU(hn::DemoteTo(di, wrapped), di, index + i);
        const auto rest = hn::Sub(one, t);
        const auto a = hn::Mul(hn::Mul(halff, rest), rest), c = hn::Mul(hn::Mul(halff, t), t);
        hn::StoreU(a, df, w0 + i);
        hn::StoreU(hn::Sub(hn::Sub(one, a), c), df, w1 + i);
        hn::StoreU(c, df, w2 + i);
    }
    for (; i < count; ++i) {
        const double u = p.origin_u + (double(p.x0 + std::int64_t(i)) + 0.5) * p.du;
        const double shifted = (u * p.scale + p.offset) - 0.5;
        const double base = std::floor(shifted);
        const float t = float(shifted - base);
        index[i] = std::int32_t(base - double(p.period) * std::floor(base * p.inverse_period));
        w0[i] = 0.5f * (1 - t) * (1 - t);
        w2[i] = 0.5f * t * t;
        w1[i] = 1 - w0[i] - w2[i];
    }
}

// Vectors of columns: as many as there are double lanes. The permuted reads take their three
// values from one float vector of the target's full width ("table"), twice as many lanes.
template <class DD>
constexpr bool can_permute(DD dd)
{
    return hn::MaxLanes(hn::ScalableTag<float>()) >= 2 * hn::MaxLanes(dd);
}

void PlanColumns(const std::int32_t* index, std::size_t count, std::int32_t* group)
{
    const hn::ScalableTag<double> dd;
    const std::size_t lanes = hn::Lanes(dd);
    const std::int32_t table = std::int32_t(hn::Lanes(hn::ScalableTag<float>()));
    for (std::size_t g = 0, i = 0; i + lanes <= count; ++g, i += lanes) {
        const std::int32_t base = index[i];
        bool fits = can_permute(dd);
        for (std::size_t k = 0; k < lanes && fits; ++k) fits = index[i + k] >= base && index[i + k] - base + 2 < table;
        group[g] = fits ? base : -1;
    }
}

void AccumulateBand(const ColumnSplines& columns, const float* combined, double gain, double fade_weight,
                    double* kept, std::size_t count)
{
    // One double lane per pixel; the float part runs on a float vector of as many lanes.
    const hn::ScalableTag<double> dd;
    const hn::Rebind<float, decltype(dd)> df;
    const hn::Rebind<std::int32_t, decltype(dd)> di;
    const hn::ScalableTag<float> dt;
    const hn::RebindToSigned<decltype(dt)> dti;
    (void)dt, (void)dti;
    const std::size_t lanes = hn::Lanes(dd);
    const auto vgain = hn::Set(dd, gain), vfade = hn::Set(dd, fade_weight);
    const auto one = hn::Set(di, 1), two = hn::Set(di, 2);
    std::size_t i = 0;
    for (std::size_t g = 0; i + lanes <= count; ++g, i += lanes) {
        const auto index = hn::LoadU(di, columns.index + i);
        hn::Vec<decltype(df)> c0, c1, c2;
        const std::int32_t base = columns.group[g];
#if HWY_TARGET != HWY_SCALAR
        if constexpr (can_permute(decltype(dd)())) {
            if (base >= 0) {
                const auto table = hn::LoadU(dt, combined + base);
                const auto offset = hn::Sub(index, hn::Set(di, base));
                const auto at = [&](hn::Vec<decltype(di)> lane) {
                    const auto wide = hn::ZeroExtendVector(dti, lane);
                    return hn::LowerHalf(df, hn::TableLookupLanes(table, hn::IndicesFromVec(dt, wide)));
                };
                c0 = at(offset), c1 = at(hn::Add(offset, one)), c2 = at(hn::Add(offset, two));
            }
        }
#endif
        if (base < 0 || !can_permute(dd)) {
            c0 = hn::GatherIndex(df, combined, index);
            c1 = hn::GatherIndex(df, combined, hn::Add(index, one));
            c2 = hn::GatherIndex(df, combined, hn::Add(index, two));
        }
        const auto value = hn::Add(hn::Add(hn::Mul(hn::LoadU(df, columns.w0 + i), c0), hn::Mul(hn::LoadU(df, columns.w1 + i), c1)),
                                   hn::Mul(hn::LoadU(df, columns.w2 + i), c2));
        const auto contribution = hn::Mul(vfade, hn::Mul(vgain, hn::PromoteTo(dd, value)));
        hn::StoreU(hn::Add(hn::LoadU(dd, kept + i), contribution), dd, kept + i);
    }
    for (; i < count; ++i) {
        const float* at = combined + columns.index[i];
        const float value = columns.w0[i] * at[0] + columns.w1[i] * at[1] + columns.w2[i] * at[2];
        kept[i] += fade_weight * (gain * double(value));
    }
}

/// QuadraticBSplineWeights of lattice positions x (lanes): the first coefficient's index wrapped
/// into [0, size) and the three weights, as SplinesOfColumns computes them.
template <class DD, class DF, class DI>
HWY_INLINE void SplinesOf(DD dd, DF df, DI di, hn::Vec<DD> x, double size, double inverse_size, hn::Vec<DI>& first,
                          hn::Vec<DF> w[3])
{
    const auto shifted = hn::Sub(x, hn::Set(dd, 0.5));
    const auto base = hn::Floor(shifted);
    const auto t = hn::DemoteTo(df, hn::Sub(shifted, base));
    // base mod size, exactly (a power-of-two size: the scaling, floor and product are exact).
    const auto period = hn::Set(dd, size);
    first = hn::DemoteTo(di, hn::Sub(base, hn::Mul(period, hn::Floor(hn::Mul(base, hn::Set(dd, inverse_size))))));
    const auto one = hn::Set(df, 1.0f), half = hn::Set(df, 0.5f);
    const auto rest = hn::Sub(one, t);
    w[0] = hn::Mul(hn::Mul(half, rest), rest);
    w[2] = hn::Mul(hn::Mul(half, t), t);
    w[1] = hn::Sub(hn::Sub(one, w[0]), w[2]);
}

/// SolidNoiseAtPoints for the Lanes(dd) points from k: eval()'s splines, gathers and sums.
template <class DD>
HWY_INLINE void SolidNoiseOfLanes(DD dd, const SolidBandPoints& p, std::size_t k, const float* coefficients, int size,
                                  float* out)
{
    const hn::Rebind<float, DD> df;
    const hn::Rebind<std::int32_t, DD> di;
    const double inverse_size = 1.0 / size;
    const auto scale = hn::Set(dd, p.scale);
    const auto mask = hn::Set(di, size - 1), vsize = hn::Set(di, size), plane = hn::Set(di, size * size);
    hn::Vec<decltype(di)> fx, fy, fz;
    hn::Vec<decltype(df)> wx[3], wy[3], wz[3];
    SplinesOf(dd, df, di, hn::Add(hn::Mul(hn::LoadU(dd, p.x + k), scale), hn::Set(dd, p.offset[0])), size, inverse_size, fx, wx);
    SplinesOf(dd, df, di, hn::Add(hn::Mul(hn::LoadU(dd, p.y + k), scale), hn::Set(dd, p.offset[1])), size, inverse_size, fy, wy);
    SplinesOf(dd, df, di, hn::Add(hn::Mul(hn::LoadU(dd, p.z + k), scale), hn::Set(dd, p.offset[2])), size, inverse_size, fz, wz);
    // Row starts of the nine (z, y) coefficient rows, slab-major as eval() walks them.
    hn::Vec<decltype(di)> row[9];
    for (int kz = 0; kz < 3; ++kz) {
        const auto slab = hn::Mul(hn::And(hn::Add(fz, hn::Set(di, kz)), mask), plane);
        for (int jy = 0; jy < 3; ++jy)
            row[3 * kz + jy] = hn::Add(slab, hn::Mul(hn::And(hn::Add(fy, hn::Set(di, jy)), mask), vsize));
    }
    hn::Vec<decltype(df)> column[3];
    for (int i = 0; i < 3; ++i) {
        const auto cx = hn::And(hn::Add(fx, hn::Set(di, i)), mask);
        hn::Vec<decltype(df)> planes[3];
        for (int kz = 0; kz < 3; ++kz) {
            const auto* r = row + 3 * kz;
            const auto c0 = hn::GatherIndex(df, coefficients, hn::Add(r[0], cx));
            const auto c1 = hn::GatherIndex(df, coefficients, hn::Add(r[1], cx));
            const auto c2 = hn::GatherIndex(df, coefficients, hn::Add(r[2], cx));
            planes[kz] = hn::Add(hn::Add(hn::Mul(wy[0], c0), hn::Mul(wy[1], c1)), hn::Mul(wy[2], c2));
        }
        column[i] = hn::Add(hn::Add(hn::Mul(wz[0], planes[0]), hn::Mul(wz[1], planes[1])), hn::Mul(wz[2], planes[2]));
    }
    hn::StoreU(hn::Add(hn::Add(hn::Mul(wx[0], column[0]), hn::Mul(wx[1], column[1])), hn::Mul(wx[2], column[2])), df,
               out + k);
}

void SolidNoiseAtPoints(const SolidBandPoints& p, std::size_t count, const float* coefficients, int size, float* out)
{
    const hn::ScalableTag<double> dd;
    const std::size_t lanes = hn::Lanes(dd);
    std::size_t k = 0;
    for (; k + lanes <= count; k += lanes) SolidNoiseOfLanes(dd, p, k, coefficients, size, out);
    // The rest one point at a time: the same operations on one-lane vectors.
    for (; k < count; ++k) SolidNoiseOfLanes(hn::CappedTag<double, 1>(), p, k, coefficients, size, out);
}

}  // namespace stochtex::wavelet_raster::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace stochtex::wavelet_raster {

HWY_EXPORT(CombineRows);
HWY_EXPORT(CombinePlanes);
HWY_EXPORT(AccumulateBand);
HWY_EXPORT(SplinesOfColumns);
HWY_EXPORT(PlanColumns);
HWY_EXPORT(SolidNoiseAtPoints);

void plan_columns(const std::int32_t* index, std::size_t count, std::int32_t* group)
{
    HWY_DYNAMIC_DISPATCH(PlanColumns)(index, count, group);
}

void column_splines(const ColumnPositions& positions, std::size_t count, std::int32_t* index, float* w0, float* w1,
                    float* w2)
{
    HWY_DYNAMIC_DISPATCH(SplinesOfColumns)(positions, count, index, w0, w1, w2);
}

void combine_planes(const float wz[3], const float wy[3], const float* const rows[9], std::size_t count, float* out)
{
    HWY_DYNAMIC_DISPATCH(CombinePlanes)(wz, wy, rows, count, out);
}

void combine_rows(const float w[3], const float* at, std::size_t stride, std::size_t count, float* out)
{
    HWY_DYNAMIC_DISPATCH(CombineRows)(w, at, stride, count, out);
}

void accumulate_band(const ColumnSplines& columns, const float* combined, double gain, double fade_weight,
                     double* kept, std::size_t count)
{
    HWY_DYNAMIC_DISPATCH(AccumulateBand)(columns, combined, gain, fade_weight, kept, count);
}

void solid_noise_at_points(const SolidBandPoints& points, std::size_t count, const float* coefficients, int size,
                           float* out)
{
    HWY_DYNAMIC_DISPATCH(SolidNoiseAtPoints)(points, count, coefficients, size, out);
}

}  // namespace stochtex::wavelet_raster
#endif
