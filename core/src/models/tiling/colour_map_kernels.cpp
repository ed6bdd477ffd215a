// Highway compiles this file once per instruction set (foreach_target.h); line_sum picks the
// best one the CPU has. Lane-wise Mul, Add, Sub, Min, Max, Floor and conversions only (never
// MulAdd), and GCC vector arithmetic (lane-wise too) in the second pass: the same rounding on
// every target (colour_map_kernels.h).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "models/tiling/colour_map_kernels.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

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
    const hn::ScalableTag<float> df;
    const hn::RebindToSigned<decltype(df)> di;
    const std::size_t lanes = hn::Lanes(df);
    static_assert(hn::MaxLanes(decltype(df)()) <= node_padding, "the nodes are read in whole vectors");
    constexpr std::size_t padded = max_nodes + node_padding;
    const std::size_t count = std::size_t(line.count), rounded = (count + lanes - 1) / lanes * lanes;
    const auto zero = hn::Zero(df), one = hn::Set(df, 1.0f), half = hn::Set(df, 0.5f);
    const auto a = hn::Set(df, float(line.a)), b = hn::Set(df, float(line.b));
    const auto step_a = hn::Set(df, float(line.step_a)), step_b = hn::Set(df, float(line.step_b));
    // Pass 1: every node's texel offsets and corner weights in each table (the padding nodes
    // past `count` give valid addresses and are never summed). Single precision: a position is
    // then within ~1e-5 texel, and the offsets (< 2²⁴) are exact.
    std::int32_t offsets[4][2][padded];
    float corners[4][4][padded];  // (x0, y0), (x1, y0), (x0, y1), (x1, y1)
    std::int32_t steps[4][padded];  // x1 − x0 in floats: 3, or 0 at the edge
    const int tables = std::min(line.table_count, 4);
    for (std::size_t k = 0; k < rounded; k += lanes) {
        const auto tk = hn::LoadU(df, line.node + k), wk = hn::LoadU(df, line.weight + k);
        // std::clamp(a + t · step, 0, 1).
        const auto pa = hn::Min(hn::Max(hn::Add(a, hn::Mul(tk, step_a)), zero), one);
        const auto pb = hn::Min(hn::Max(hn::Add(b, hn::Mul(tk, step_b)), zero), one);
        for (int m = 0; m < tables; ++m) {
            const Table& table = line.tables[m];
            // ColourMapFilter::fetch: clamped texel coordinates, the lower texel (at most the
            // last but one), its neighbour clamped to the edge.
            const auto x = hn::Min(hn::Max(hn::Sub(hn::Mul(pa, hn::Set(df, float(table.width))), half), zero),
                                   hn::Set(df, float(table.width - 1)));
            const auto y = hn::Min(hn::Max(hn::Sub(hn::Mul(pb, hn::Set(df, float(table.height))), half), zero),
                                   hn::Set(df, float(table.height - 1)));
            const auto x0 = hn::Min(hn::Floor(x), hn::Set(df, float(table.last_x0)));
            const auto y0 = hn::Min(hn::Floor(y), hn::Set(df, float(table.last_y0)));
            const auto x1 = hn::Min(hn::Add(x0, one), hn::Set(df, float(table.width - 1)));
            const auto y1 = hn::Min(hn::Add(y0, one), hn::Set(df, float(table.height - 1)));
            const auto fx = hn::Sub(x, x0), fy = hn::Sub(y, y0);
            const auto weight = hn::Mul(wk, hn::Set(df, table.weight));
            const auto low = hn::Mul(weight, hn::Sub(one, fy)), high = hn::Mul(weight, fy);
            hn::StoreU(hn::Mul(low, hn::Sub(one, fx)), df, corners[m][0] + k);
            hn::StoreU(hn::Mul(low, fx), df, corners[m][1] + k);
            hn::StoreU(hn::Mul(high, hn::Sub(one, fx)), df, corners[m][2] + k);
            hn::StoreU(hn::Mul(high, fx), df, corners[m][3] + k);
            const auto stride = hn::Set(df, float(table.stride)), three = hn::Set(df, 3.0f);
            const auto c0 = hn::Mul(x0, three);
            hn::StoreU(hn::ConvertTo(di, hn::Add(hn::Mul(y0, stride), c0)), di, offsets[m][0] + k);
            hn::StoreU(hn::ConvertTo(di, hn::Add(hn::Mul(y1, stride), c0)), di, offsets[m][1] + k);
            hn::StoreU(hn::ConvertTo(di, hn::Sub(hn::Mul(x1, three), c0)), di, steps[m] + k);
        }
    }
    // Pass 2: node by node, each texel's RGB as one vector of four floats (one load, where a
    // gather per channel would take three) times its corner weight; a node's corners summed in
    // pairs, the nodes in order.
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
            const float* r0 = line.tables[m].rgb + offsets[m][0][k];
            const float* r1 = line.tables[m].rgb + offsets[m][1][k];
            const std::int32_t step = steps[m][k];
            const Colour4 low = splat(corners[m][0][k]) * load(r0) + splat(corners[m][1][k]) * load(r0 + step);
            const Colour4 high = splat(corners[m][2][k]) * load(r1) + splat(corners[m][3][k]) * load(r1 + step);
            out += low + high;
        }
        sum += out;
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
