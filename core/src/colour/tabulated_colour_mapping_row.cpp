// Highway compiles this file once per instruction set (foreach_target.h). Lane-wise Mul, Add,
// Sub, Min, Max, Floor, gathers and conversions only: the same rounding on every target.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "colour/tabulated_colour_mapping_row.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include "colour/tabulated_colour_mapping_row.h"

#include <algorithm>
#include <cstdint>

HWY_BEFORE_NAMESPACE();
namespace stochtex::tabulated_row::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

void Interpolate(const ChannelTable& table, const double* z, const double* sigma, std::size_t count, double* y)
{
    const hn::ScalableTag<double> dd;
    const hn::Rebind<float, decltype(dd)> df;
    const hn::Rebind<std::int32_t, decltype(dd)> di;
    const std::size_t lanes = hn::Lanes(dd);
    const auto zero = hn::Zero(dd), one = hn::Set(dd, 1.0), inverse_step = hn::Set(dd, table.inverse_step);
    const auto z0 = hn::Set(dd, table.z0), last_row = hn::Set(dd, double(table.rows - 2));
    const auto last_q = hn::Set(dd, double(table.columns - 1)), last_column = hn::Set(dd, double(table.columns - 2));
    const auto columns = hn::Set(dd, double(table.columns));
    const auto next_row = hn::Set(di, table.columns), next = hn::Set(di, 1);
    auto lookup = [&](hn::Vec<decltype(dd)> zv, hn::Vec<decltype(dd)> sv) {
        // interpolate(): s = σ / step, row = min(int(s), rows − 2) (s ≥ 0: int() is floor),
        // q = clamp((z − z0) / step, 0, columns − 1), column = min(int(q), columns − 2).
        const auto s = hn::Mul(sv, inverse_step);
        const auto row = hn::Min(hn::Floor(s), last_row);
        const auto fs = hn::Sub(s, row);
        const auto q = hn::Min(hn::Max(hn::Mul(hn::Sub(zv, z0), inverse_step), zero), last_q);
        const auto column = hn::Min(hn::Floor(q), last_column);
        const auto fq = hn::Sub(q, column);
        const auto low = hn::DemoteTo(di, hn::Add(hn::Mul(row, columns), column));
        const auto high = hn::Add(low, next_row);
        auto read = [&](hn::Vec<decltype(di)> index) { return hn::PromoteTo(dd, hn::GatherIndex(df, table.values, index)); };
        const auto gq = hn::Sub(one, fq), gs = hn::Sub(one, fs);
        const auto a = hn::Add(hn::Mul(read(low), gq), hn::Mul(read(hn::Add(low, next)), fq));
        const auto b = hn::Add(hn::Mul(read(high), gq), hn::Mul(read(hn::Add(high, next)), fq));
        return hn::Add(hn::Mul(a, gs), hn::Mul(b, fs));
    };
    std::size_t i = 0;
    for (; i + lanes <= count; i += lanes) hn::StoreU(lookup(hn::LoadU(dd, z + i), hn::LoadU(dd, sigma + i)), dd, y + i);
    if (i < count) {  // the tail through a whole vector, padded with its last value
        double zt[hn::MaxLanes(decltype(dd)())], st[hn::MaxLanes(decltype(dd)())], yt[hn::MaxLanes(decltype(dd)())];
        for (std::size_t k = 0; k < lanes; ++k) zt[k] = z[std::min(i + k, count - 1)], st[k] = sigma[std::min(i + k, count - 1)];
        hn::StoreU(lookup(hn::LoadU(dd, zt), hn::LoadU(dd, st)), dd, yt);
        for (std::size_t k = 0; i + k < count; ++k) y[i + k] = yt[k];
    }
}

}  // namespace stochtex::tabulated_row::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace stochtex::tabulated_row {

HWY_EXPORT(Interpolate);

void interpolate(const ChannelTable& table, const double* z, const double* sigma, std::size_t count, double* y)
{
    HWY_DYNAMIC_DISPATCH(Interpolate)(table, z, sigma, count, y);
}

}  // namespace stochtex::tabulated_row
#endif
