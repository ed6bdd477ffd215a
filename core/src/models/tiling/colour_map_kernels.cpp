// Highway compiles this file once per instruction set (foreach_target.h); line_sum picks the
// best one the CPU has. Lane-wise Mul, Add, Sub, Min, Max, Floor and conversions only (never
// MulAdd): the same rounding on every target (colour_map_kernels.h).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "models/tiling/colour_map_kernels.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/cache_control.h>
#include <hwy/highway.h>

#include "models/tiling/colour_map_kernels.h"

#include <algorithm>
#include <cstdint>

HWY_BEFORE_NAMESPACE();
namespace stochtex::colour_map_kernels::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

void LineSum(const LineNodes& line, float* rgb)
{
    const hn::ScalableTag<double> dd;
    const hn::Rebind<float, decltype(dd)> df;
    const hn::Rebind<std::int32_t, decltype(dd)> di;
    const std::size_t lanes = hn::Lanes(dd);
    // The nodes padded to whole vectors (the padding repeats the last node: valid addresses,
    // never summed), their colours stored planar.
    constexpr std::size_t padded = max_nodes + hn::MaxLanes(decltype(dd)());
    double t[padded];
    float colour[3][padded];
    const std::size_t count = std::size_t(line.count), rounded = (count + lanes - 1) / lanes * lanes;
    for (std::size_t k = 0; k < rounded; ++k) t[k] = line.node[std::min(k, count - 1)];
    const auto zero = hn::Zero(dd), one = hn::Set(dd, 1.0), half = hn::Set(dd, 0.5);
    const auto a = hn::Set(dd, line.a), b = hn::Set(dd, line.b), step_a = hn::Set(dd, line.step_a), step_b = hn::Set(dd, line.step_b);
    const auto fone = hn::Set(df, 1.0f);
    // Pass 1: every node's texel offsets and fractions in each table, and a prefetch of the two
    // rows each reads — the nodes walk ~one new map row each through a table of up to 0.8 MB,
    // so their loads are requested together rather than as the nodes come.
    std::int32_t offsets[4][2][padded];
    float fractions[4][2][padded];
    std::int32_t steps[4][padded];  // x1 − x0 in floats: 3, or 0 at the edge
    const int tables = std::min(line.table_count, 4);
    for (std::size_t k = 0; k < rounded; k += lanes) {
        const auto tk = hn::LoadU(dd, t + k);
        // std::clamp(a + t · step, 0, 1).
        const auto pa = hn::Min(hn::Max(hn::Add(a, hn::Mul(tk, step_a)), zero), one);
        const auto pb = hn::Min(hn::Max(hn::Add(b, hn::Mul(tk, step_b)), zero), one);
        for (int m = 0; m < tables; ++m) {
            const Table& table = line.tables[m];
            // Packed::fetch: clamped texel coordinates, the lower texel (at most the last but
            // one), its neighbour clamped to the edge, the fractions in float.
            const auto x = hn::Min(hn::Max(hn::Sub(hn::Mul(pa, hn::Set(dd, double(table.width))), half), zero),
                                   hn::Set(dd, double(table.width - 1)));
            const auto y = hn::Min(hn::Max(hn::Sub(hn::Mul(pb, hn::Set(dd, double(table.height))), half), zero),
                                   hn::Set(dd, double(table.height - 1)));
            const auto x0 = hn::Min(hn::Floor(x), hn::Set(dd, double(table.last_x0)));
            const auto y0 = hn::Min(hn::Floor(y), hn::Set(dd, double(table.last_y0)));
            const auto x1 = hn::Min(hn::Add(x0, one), hn::Set(dd, double(table.width - 1)));
            const auto y1 = hn::Min(hn::Add(y0, one), hn::Set(dd, double(table.height - 1)));
            hn::StoreU(hn::DemoteTo(df, hn::Sub(x, x0)), df, fractions[m][0] + k);
            hn::StoreU(hn::DemoteTo(df, hn::Sub(y, y0)), df, fractions[m][1] + k);
            const auto stride = hn::Set(dd, double(table.stride)), three = hn::Set(dd, 3.0);
            const auto c0 = hn::Mul(x0, three);
            hn::StoreU(hn::DemoteTo(di, hn::Add(hn::Mul(y0, stride), c0)), di, offsets[m][0] + k);
            hn::StoreU(hn::DemoteTo(di, hn::Add(hn::Mul(y1, stride), c0)), di, offsets[m][1] + k);
            hn::StoreU(hn::DemoteTo(di, hn::Sub(hn::Mul(x1, three), c0)), di, steps[m] + k);
        }
    }
    for (int m = 0; m < tables; ++m)
        for (std::size_t k = 0; k < count; ++k) {
            hwy::Prefetch(line.tables[m].rgb + offsets[m][0][k]);
            hwy::Prefetch(line.tables[m].rgb + offsets[m][1][k]);
        }
    // Pass 2: the nodes' colours (Packed::fetch's arithmetic), then their sum in node order.
    for (std::size_t k = 0; k < rounded; k += lanes) {
        hn::Vec<decltype(df)> out[3] = {hn::Zero(df), hn::Zero(df), hn::Zero(df)};
        for (int m = 0; m < tables; ++m) {
            const auto fx = hn::LoadU(df, fractions[m][0] + k), fy = hn::LoadU(df, fractions[m][1] + k);
            const auto hx = hn::Sub(fone, fx), hy = hn::Sub(fone, fy);
            const auto i00 = hn::LoadU(di, offsets[m][0] + k), i10 = hn::LoadU(di, offsets[m][1] + k);
            const auto step = hn::LoadU(di, steps[m] + k);
            const auto i01 = hn::Add(i00, step), i11 = hn::Add(i10, step);
            const auto weight = hn::Set(df, line.tables[m].weight);
            for (int c = 0; c < 3; ++c) {
                const float* base = line.tables[m].rgb + c;
                const auto low = hn::Add(hn::Mul(hx, hn::GatherIndex(df, base, i00)), hn::Mul(fx, hn::GatherIndex(df, base, i01)));
                const auto high = hn::Add(hn::Mul(hx, hn::GatherIndex(df, base, i10)), hn::Mul(fx, hn::GatherIndex(df, base, i11)));
                out[c] = hn::Add(out[c], hn::Mul(weight, hn::Add(hn::Mul(hy, low), hn::Mul(fy, high))));
            }
        }
        for (int c = 0; c < 3; ++c) hn::StoreU(out[c], df, colour[c] + k);
    }
    float sum[3] = {0, 0, 0};
    for (std::size_t k = 0; k < count; ++k) {
        const float w = float(line.weight[k]);
        for (int c = 0; c < 3; ++c) sum[c] += w * colour[c][k];
    }
    for (int c = 0; c < 3; ++c) rgb[c] = sum[c];
}

}  // namespace stochtex::colour_map_kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace stochtex::colour_map_kernels {

HWY_EXPORT(LineSum);

void line_sum(const LineNodes& line, float* rgb) { HWY_DYNAMIC_DISPATCH(LineSum)(line, rgb); }

}  // namespace stochtex::colour_map_kernels
#endif
