// Highway compiles this file once per instruction set (foreach_target.h); line_sum picks the
// best one the CPU has. Lane-wise Mul, Add, Sub, Min, Max, Floor and conversions only (never
// MulAdd), and GCC vector arithmetic (lane-wise too) in the second pass: the same rounding on
// every target (colour_map_kernels.h).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "models/tiling/colour_map_kernels.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/cache_control.h>
#include <hwy/highway.h>

#include "models/tiling/colour_map_kernels.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

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
    const std::size_t count = std::size_t(line.count), rounded = (count + lanes - 1) / lanes * lanes;
    for (std::size_t k = 0; k < rounded; ++k) t[k] = line.node[std::min(k, count - 1)];
    const auto zero = hn::Zero(dd), one = hn::Set(dd, 1.0), half = hn::Set(dd, 0.5);
    const auto a = hn::Set(dd, line.a), b = hn::Set(dd, line.b), step_a = hn::Set(dd, line.step_a), step_b = hn::Set(dd, line.step_b);
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
    // Pass 2: node by node, Packed::fetch's arithmetic on each texel's RGB as one vector of four
    // floats (one load, where a gather per channel would take three), summed in node order.
    typedef float Colour4 __attribute__((vector_size(4 * sizeof(float))));
    auto load = [](const float* p) {
        Colour4 c;
        std::memcpy(&c, p, sizeof c);
        return c;
    };
    auto splat = [](float v) { return Colour4{v, v, v, v}; };
    Colour4 sum{};
    for (std::size_t k = 0; k < count; ++k) {
        Colour4 out{};
        for (int m = 0; m < tables; ++m) {
            const float fx = fractions[m][0][k], fy = fractions[m][1][k];
            const float* r0 = line.tables[m].rgb + offsets[m][0][k];
            const float* r1 = line.tables[m].rgb + offsets[m][1][k];
            const std::int32_t step = steps[m][k];
            const Colour4 gx = splat(fx), hx = splat(1 - fx);
            const Colour4 low = hx * load(r0) + gx * load(r0 + step);
            const Colour4 high = hx * load(r1) + gx * load(r1 + step);
            out += splat(line.tables[m].weight) * (splat(1 - fy) * low + splat(fy) * high);
        }
        sum += splat(float(line.weight[k])) * out;
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
