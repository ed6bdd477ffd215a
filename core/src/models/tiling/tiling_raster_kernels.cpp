// Highway compiles this file once per instruction set (foreach_target.h); plan_tap_row picks the
// best one the CPU has. Only Mul, Add, Sub, Div, Sqrt and Floor (never MulAdd), lane-wise: the
// same rounding on every target.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "models/tiling/tiling_raster_kernels.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include "numerics/small_table-inl.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "models/tiling/tiling_raster_kernels.h"

HWY_BEFORE_NAMESPACE();
namespace stochtex::tiling_raster::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

/// PlanTapRow's loop, the row tables' entries read by `read(table, column)` (table 0–3: row0_x,
/// row0_y, row1_x, row1_y).
template <class Read>
void PlanTapRowWith(const TapRow& row, const TileReads& out, const Read& read)
{
    const hn::ScalableTag<double> dd;
    const hn::RebindToSigned<decltype(dd)> di;
    const hn::Rebind<float, decltype(dd)> df;
    const hn::Rebind<std::int32_t, decltype(dd)> d32;
    const std::size_t lanes = hn::Lanes(dd);
    const auto one = hn::Set(dd, 1.0), half = hn::Set(dd, 0.5), zero = hn::Zero(dd);
    const auto fy = hn::Set(dd, row.fy), y = hn::Set(dd, row.y), i_min = hn::Set(dd, row.i_min);
    const auto shift = hn::Mul(half, hn::Set(dd, row.sy)), inverse_edge = hn::Set(dd, row.inverse_edge_x);
    const auto eight = hn::Set(dd, 8.0), a = hn::Set(dd, row.a), b = hn::Set(dd, row.b);
    const auto one_f = hn::Set(df, 1.0f);
    // One level's lookup of tile k at p, q: the two record offsets, the fractions and their complements.
    auto lookup = [&](const LevelGeometry& g, hn::Vec<decltype(dd)> p, hn::Vec<decltype(dd)> q, std::int32_t* o0, std::int32_t* o1,
                      float* fx, float* fyo, float* gx, float* gy, std::size_t i) {
        const auto lx = hn::Sub(hn::Mul(p, hn::Set(dd, g.scale_x)), half), ly = hn::Sub(hn::Mul(q, hn::Set(dd, g.scale_y)), half);
        const auto x0 = hn::Floor(lx), y0 = hn::Floor(ly);
        const auto tx = hn::DemoteTo(df, hn::Sub(lx, x0)), ty = hn::DemoteTo(df, hn::Sub(ly, y0));
        hn::StoreU(tx, df, fx + i);
        hn::StoreU(ty, df, fyo + i);
        hn::StoreU(hn::Sub(one_f, tx), df, gx + i);
        hn::StoreU(hn::Sub(one_f, ty), df, gy + i);
        const auto width = hn::Set(dd, g.width), height = hn::Set(dd, g.height);
        const auto ix = hn::Sub(x0, hn::Mul(width, hn::Floor(hn::Mul(x0, hn::Set(dd, g.inverse_width)))));
        const auto iy = hn::Sub(y0, hn::Mul(height, hn::Floor(hn::Mul(y0, hn::Set(dd, g.inverse_height)))));
        const auto next = hn::Add(iy, one);
        const auto jy = hn::IfThenElse(hn::Ge(next, height), zero, next);
        const auto records = hn::Set(dd, g.row);
        hn::StoreU(hn::DemoteTo(d32, hn::Mul(hn::Add(hn::Mul(iy, records), ix), eight)), d32, o0 + i);
        hn::StoreU(hn::DemoteTo(d32, hn::Mul(hn::Add(hn::Mul(jy, records), ix), eight)), d32, o1 + i);
    };
    for (std::size_t i = 0; i < row.n; i += lanes) {
        const auto x = hn::Add(hn::Add(hn::LoadU(dd, row.x + i), a), b);
        const auto sx = hn::Sub(hn::Mul(x, inverse_edge), shift);
        const auto cx = hn::Floor(sx);
        const auto fx = hn::Sub(sx, cx);
        const auto upper = hn::Ge(hn::Add(fx, fy), one);  // not (fx + fy < 1)
        const auto b0 = hn::IfThenElse(upper, hn::Sub(hn::Add(fx, fy), one), hn::Sub(hn::Sub(one, fx), fy));
        const auto b1 = hn::IfThenElse(upper, hn::Sub(one, fy), fx);
        const auto b2 = hn::IfThenElse(upper, hn::Sub(one, fx), fy);
        const auto inverse_norm =
            hn::Div(one, hn::Sqrt(hn::Add(hn::Add(hn::Mul(b0, b0), hn::Mul(b1, b1)), hn::Mul(b2, b2))));
        const hn::Vec<decltype(dd)> weights[3] = {hn::Mul(b0, inverse_norm), hn::Mul(b1, inverse_norm), hn::Mul(b2, inverse_norm)};
        // Translation columns c = cx − i_min and c + 1 in both vertex rows.
        const auto c = hn::ConvertTo(di, hn::Sub(cx, i_min));
        const auto c1 = hn::Add(c, hn::Set(di, 1));
        const auto t0x = hn::IfThenElse(upper, read(2, c1), read(0, c));
        const auto t0y = hn::IfThenElse(upper, read(3, c1), read(1, c));
        const hn::Vec<decltype(dd)> tx[3] = {t0x, read(0, c1), read(2, c)};
        const hn::Vec<decltype(dd)> ty[3] = {t0y, read(1, c1), read(3, c)};
        for (int k = 0; k < 3; ++k) {
            const auto w = hn::DemoteTo(df, weights[k]);
            hn::StoreU(w, df, out.weight[k] + i);
            hn::StoreU(hn::Mul(w, w), df, out.weight_squared[k] + i);
            const auto p = hn::Add(x, tx[k]), q = hn::Add(y, ty[k]);
            lookup(row.lower, p, q, out.offset0[k], out.offset1[k], out.fx[k], out.fy[k], out.gx[k], out.gy[k], i);
            if (row.has_upper)
                lookup(row.upper, p, q, out.upper_offset0[k], out.upper_offset1[k], out.upper_fx[k], out.upper_fy[k], out.upper_gx[k],
                       out.upper_gy[k], i);
        }
    }
}

void PlanTapRow(const TapRow& row, const TileReads& out)
{
    // A row's tables span a few vertex columns (a 64-pixel chunk at 4 exemplar pixels per pixel:
    // about 5): in registers, read by permutations, where they fit; else gathered.
    const hn::ScalableTag<double> dd;
    using Table = small_table::HWY_NAMESPACE::SmallTable<decltype(dd)>;
    const double* tables[4] = {row.row0_x, row.row0_y, row.row1_x, row.row1_y};
    if (Table::fits(dd, row.columns)) {
        const Table small[4] = {{dd, tables[0], row.columns}, {dd, tables[1], row.columns}, {dd, tables[2], row.columns},
                                {dd, tables[3], row.columns}};
        PlanTapRowWith(row, out, [&](int table, auto column) { return small[table](dd, column); });
    } else {
        PlanTapRowWith(row, out, [&](int table, auto column) { return hn::GatherIndex(dd, tables[table], column); });
    }
}

/// AccumulateTaps for a channel count, one or two levels and (Taps > 0) a tap count known at
/// compile time, so the loops unroll into registers and every field of a position is at a fixed
/// distance from its first (the same operations as with them at run time).
template <int Channels, bool Upper, int Taps>
void AccumulateTapsFor(const TapSums& s, std::size_t count, float* out)
{
    using P = RecordPairs<Channels>;
    constexpr int record = 8;
    const hn::CappedTag<float, record> df;
    const int step = int(hn::Lanes(df)), parts = record / step;
    const int taps = Taps > 0 ? Taps : s.taps;
    auto at_offsets = [&](std::size_t run, int field) { return s.offsets + (run * 4 + std::size_t(field)) * chunk; };
    auto at_fractions = [&](std::size_t run, int field) { return s.fractions + (run * 10 + std::size_t(field)) * chunk; };
    const auto level_t = hn::Set(df, s.t);
    // A record in one vector (AVX2, AVX-512): the mixture runs on vectors; else on scalars.
    constexpr bool one_vector = !HWY_HAVE_SCALABLE && HWY_MAX_BYTES >= 32;
    const auto mean_lanes = hn::FirstN(df, Channels), used_lanes = hn::FirstN(df, Channels + P::count);
    hn::Mask<decltype(df)> part_means[record];  // the mean lanes of each part of a record
    for (int h = 0; h < parts; ++h) part_means[h] = hn::FirstN(df, std::size_t(std::max(0, Channels - h * step)));
    const auto tap_weight = hn::Set(df, s.weight), inverse_total = hn::Set(df, s.inverse_total);
    std::int32_t first_index[hn::MaxLanes(decltype(df)())] = {}, second_index[hn::MaxLanes(decltype(df)())] = {};
    for (int p = 0; p < P::count && Channels + p < int(hn::MaxLanes(df)); ++p)
        first_index[Channels + p] = P::first[p], second_index[Channels + p] = P::second[p];
    const auto first_lanes = hn::SetTableIndices(df, first_index), second_lanes = hn::SetTableIndices(df, second_index);
    // No software prefetch of the records: an earlier version asked for the lines of the
    // position three ahead from a lambda, which GCC 12 took for a function without effects and
    // dropped (no prefetch instruction was ever emitted); written so that it is emitted, it made
    // Render/Raster/colour 16 % slower (12 % with one line per record) — the hardware keeps up.
    std::size_t first_single = 0;
    // Where a vector holds two records (AVX-512), two positions go through one vector,
    // interleaved (lane 2j + p: record lane j of position p), with the same operations lane by
    // lane as one position alone: the fields of positions l and l + 1 are adjacent, so each
    // factor comes as one 8-byte broadcast; each texel pair's two records are interleaved by a
    // lane permutation. Odd counts leave the last position to the loop below.
#if HWY_TARGET != HWY_SCALAR  // (no Combine there; it has one lane anyway)
    constexpr bool two_positions = !HWY_HAVE_SCALABLE && HWY_MAX_BYTES == 64;
    if constexpr (two_positions) {
        const hn::ScalableTag<float> dz;
        const hn::Half<decltype(dz)> dh;
        const hn::Repartition<std::uint64_t, decltype(dz)> du64;
        constexpr std::size_t lanes = hn::MaxLanes(dz);
        std::int32_t interleave[lanes], deinterleave[lanes], first2[lanes], second2[lanes];
        for (std::size_t k = 0; k < lanes; ++k) {
            const int j = int(k / 2), q = int(k % 2), pair = j - Channels;
            interleave[k] = std::int32_t(q * 8 + j);
            deinterleave[k] = std::int32_t((k % 8) * 2 + k / 8);
            const bool moment = pair >= 0 && pair < P::count;
            first2[k] = std::int32_t(moment ? 2 * P::first[std::max(pair, 0)] + q : q);
            second2[k] = std::int32_t(moment ? 2 * P::second[std::max(pair, 0)] + q : q);
        }
        const auto interleaved = hn::SetTableIndices(dz, interleave), deinterleaved = hn::SetTableIndices(dz, deinterleave);
#if HWY_TARGET == HWY_AVX3 || HWY_TARGET == HWY_AVX3_DL
        // vpermt2ps's indices: 0–15 the first table, 16–31 the second.
        std::int32_t left_index[lanes], right_index[lanes];
        for (std::size_t k = 0; k < lanes; ++k)
            left_index[k] = std::int32_t((k % 2) * 16 + k / 2), right_index[k] = left_index[k] + 8;
        const hn::RebindToSigned<decltype(dz)> di32;
        const auto left = hn::LoadU(di32, left_index), right = hn::LoadU(di32, right_index);
#endif
        const auto first_pairs = hn::SetTableIndices(dz, first2), second_pairs = hn::SetTableIndices(dz, second2);
        const auto means2 = hn::FirstN(dz, 2 * Channels), used2 = hn::FirstN(dz, 2 * (Channels + P::count));
        const auto level_t2 = hn::Set(dz, s.t), tap_weight2 = hn::Set(dz, s.weight), inverse_total2 = hn::Set(dz, s.inverse_total);
        auto factor = [&](const float* f) {  // [f[0], f[1]] in every lane pair
            std::uint64_t bits;
            std::memcpy(&bits, f, sizeof bits);
            return hn::BitCast(dz, hn::Set(du64, bits));
        };
        // A texel row's two records of positions a and b, interleaved: [left, right].
        auto texels = [&](const float* data, std::int32_t a, std::int32_t b, hn::Vec<decltype(dz)>* pair) {
#if HWY_TARGET == HWY_AVX3 || HWY_TARGET == HWY_AVX3_DL
            const auto va = hn::LoadU(dz, data + a), vb = hn::LoadU(dz, data + b);
            pair[0] = hn::Vec<decltype(dz)>{_mm512_permutex2var_ps(va.raw, left.raw, vb.raw)};
            pair[1] = hn::Vec<decltype(dz)>{_mm512_permutex2var_ps(va.raw, right.raw, vb.raw)};
#else
            for (int side = 0; side < 2; ++side)
                pair[side] = hn::TableLookupLanes(
                    hn::Combine(dz, hn::LoadU(dh, data + b + side * record), hn::LoadU(dh, data + a + side * record)), interleaved);
#endif
        };
        for (; first_single + 2 <= count; first_single += 2) {
            const std::size_t l = first_single;
            auto means = hn::Zero(dz), moments = hn::Zero(dz);
            for (int k = 0; k < taps; ++k) {
                auto sum = hn::Zero(dz);
                for (int tile = 0; tile < 3; ++tile) {
                    const std::size_t run = std::size_t(k) * 3 + std::size_t(tile);
                    auto bilinear = [&](const float* data, int field, int fraction) {
                        const std::int32_t* o0 = at_offsets(run, field) + l;
                        const std::int32_t* o1 = at_offsets(run, field + 1) + l;
                        const auto vx = factor(at_fractions(run, fraction) + l), vy = factor(at_fractions(run, fraction + 1) + l);
                        const auto sx = factor(at_fractions(run, fraction + 5) + l), sy = factor(at_fractions(run, fraction + 6) + l);
                        hn::Vec<decltype(dz)> row0[2], row1[2];
                        texels(data, o0[0], o0[1], row0);
                        texels(data, o1[0], o1[1], row1);
                        const auto low = hn::Add(hn::Mul(sx, row0[0]), hn::Mul(vx, row0[1]));
                        const auto high = hn::Add(hn::Mul(sx, row1[0]), hn::Mul(vx, row1[1]));
                        return hn::Add(hn::Mul(sy, low), hn::Mul(vy, high));
                    };
                    auto sample = bilinear(s.lower, 0, 0);
                    if (Upper) sample = hn::Add(sample, hn::Mul(level_t2, hn::Sub(bilinear(s.upper, 2, 2), sample)));
                    const auto weights = hn::IfThenElse(means2, factor(at_fractions(run, 4) + l), factor(at_fractions(run, 9) + l));
                    sum = hn::Add(sum, hn::Mul(weights, sample));
                }
                if (taps == 1) {
                    means = moments = sum;
                    break;
                }
                const auto delta = hn::Sub(sum, means);
                const auto products = hn::Mul(hn::TableLookupLanes(delta, first_pairs), hn::TableLookupLanes(delta, second_pairs));
                means = hn::Add(means, hn::Mul(hn::Set(dz, s.ratio[k]), delta));
                moments = hn::Add(moments, hn::Add(hn::Mul(tap_weight2, sum), hn::Mul(hn::Set(dz, s.scatter[k]), products)));
            }
            const auto scaled = hn::IfThenElse(means2, means, taps == 1 ? moments : hn::Mul(moments, inverse_total2));
            hn::StoreU(hn::TableLookupLanes(hn::IfThenElseZero(used2, scaled), deinterleaved), dz, out + l * record);
        }
    }
#endif
    for (std::size_t l = first_single; l < count; ++l) {
        float result[record] = {};
        // one_vector's result: the mean lanes of `means`, the moment lanes of `moments` (two
        // registers, so that the next tap's deltas wait on the means' chain alone).
        auto means = hn::Zero(df), moments = hn::Zero(df);
        for (int k = 0; k < taps; ++k) {
            hn::Vec<decltype(df)> sum[record] = {};
            for (int h = 0; h < parts; ++h) sum[h] = hn::Zero(df);
            for (int tile = 0; tile < 3; ++tile) {
                const std::size_t run = std::size_t(k) * 3 + std::size_t(tile);
                // The tile's weights on the record: w on the mean lanes, w² on the others (what
                // w · (1 + w · 0) and w · (0 + w · 1) are, exactly).
                const auto vw = hn::Set(df, at_fractions(run, 4)[l]), vw2 = hn::Set(df, at_fractions(run, 9)[l]);
                auto bilinear = [&](const float* data, int field, int fraction, int h) {
                    const float* r0 = data + at_offsets(run, field)[l] + h * step;
                    const float* r1 = data + at_offsets(run, field + 1)[l] + h * step;
                    const auto vx = hn::Set(df, at_fractions(run, fraction)[l]), vy = hn::Set(df, at_fractions(run, fraction + 1)[l]);
                    const auto sx = hn::Set(df, at_fractions(run, fraction + 5)[l]), sy = hn::Set(df, at_fractions(run, fraction + 6)[l]);
                    const auto low = hn::Add(hn::Mul(sx, hn::LoadU(df, r0)), hn::Mul(vx, hn::LoadU(df, r0 + record)));
                    const auto high = hn::Add(hn::Mul(sx, hn::LoadU(df, r1)), hn::Mul(vx, hn::LoadU(df, r1 + record)));
                    return hn::Add(hn::Mul(sy, low), hn::Mul(vy, high));
                };
                for (int h = 0; h < parts; ++h) {
                    auto sample = bilinear(s.lower, 0, 0, h);
                    if (Upper) sample = hn::Add(sample, hn::Mul(level_t, hn::Sub(bilinear(s.upper, 2, 2, h), sample)));
                    const auto weights = hn::IfThenElse(part_means[h], vw, vw2);
                    sum[h] = hn::Add(sum[h], hn::Mul(weights, sample));
                }
            }
            if constexpr (one_vector) {
                // The mixture below, lane-wise on the whole record: the mean lanes take
                // result + ratio · delta, moment lane C + p takes result + (weight · m + scatter ·
                // delta[first p] · delta[second p]), the deltas brought to it by a lane lookup.
                if (taps == 1) {
                    means = moments = sum[0];
                    break;
                }
                const auto delta = hn::Sub(sum[0], means);
                const auto products = hn::Mul(hn::TableLookupLanes(delta, first_lanes), hn::TableLookupLanes(delta, second_lanes));
                means = hn::Add(means, hn::Mul(hn::Set(df, s.ratio[k]), delta));
                moments = hn::Add(moments, hn::Add(hn::Mul(tap_weight, sum[0]), hn::Mul(hn::Set(df, s.scatter[k]), products)));
                continue;
            }
            float m[record];
            for (int h = 0; h < parts; ++h) hn::StoreU(sum[h], df, m + h * step);
            if (taps == 1) {
                for (int r = 0; r < record; ++r) result[r] = m[r];
                break;
            }
            // MomentMixture::add term for term (TilingNoise::planned_estimate), in single precision.
            float delta[record];
            for (int a = 0; a < Channels; ++a) delta[a] = m[a] - result[a];
            const float ratio = s.ratio[k], scatter = s.scatter[k];
            for (int a = 0; a < Channels; ++a) result[a] += ratio * delta[a];
            for (int p = 0; p < P::count; ++p)
                result[Channels + p] += s.weight * m[Channels + p] + scatter * (delta[P::first[p]] * delta[P::second[p]]);
        }
        float* o = out + l * record;
        if constexpr (one_vector) {
            // Lanes past the kept moments stay 0, as in the scalar form.
            const auto scaled = hn::IfThenElse(mean_lanes, means, taps == 1 ? moments : hn::Mul(moments, inverse_total));
            hn::StoreU(hn::IfThenElseZero(used_lanes, scaled), df, o);
            continue;
        }
        for (int r = 0; r < record; ++r) o[r] = taps == 1 || r < Channels ? result[r] : result[r] * s.inverse_total;
    }
}

/// AccumulateTapsFor with the tap count of an isotropic footprint's default plan (2 × 2) or of
/// a point (1) fixed, any other at run time.
template <int Channels, bool Upper>
void AccumulateTapsOf(const TapSums& s, std::size_t count, float* out)
{
    switch (s.taps) {
    case 1: return AccumulateTapsFor<Channels, Upper, 1>(s, count, out);
    case 4: return AccumulateTapsFor<Channels, Upper, 4>(s, count, out);
    default: return AccumulateTapsFor<Channels, Upper, 0>(s, count, out);
    }
}

void AccumulateTaps(const TapSums& s, std::size_t count, float* out)
{
    const bool upper = s.upper != nullptr;
    switch (s.channels) {
    case 1: return upper ? AccumulateTapsOf<1, true>(s, count, out) : AccumulateTapsOf<1, false>(s, count, out);
    case 2: return upper ? AccumulateTapsOf<2, true>(s, count, out) : AccumulateTapsOf<2, false>(s, count, out);
    default: return upper ? AccumulateTapsOf<3, true>(s, count, out) : AccumulateTapsOf<3, false>(s, count, out);
    }
}

void ColourInputs(const float* packed, std::size_t count, const double* mean, double* const* z, double* const* spread)
{
    const hn::ScalableTag<double> dd;
    const hn::Rebind<float, decltype(dd)> df;
    const hn::Rebind<std::int32_t, decltype(dd)> d32;
    const std::size_t lanes = hn::Lanes(dd);
    const auto zero = hn::Zero(dd);
    for (std::size_t i = 0; i < count; i += lanes) {
        // Lane k reads record i + k (the last one past count): its lanes gathered, planar.
        std::int32_t first[hn::MaxLanes(decltype(dd)())];
        for (std::size_t k = 0; k < lanes; ++k) first[k] = std::int32_t(std::min(i + k, count - 1) * 8);
        const auto records = hn::LoadU(d32, first);
        double zt[3][hn::MaxLanes(decltype(dd)())], st[3][hn::MaxLanes(decltype(dd)())];
        const bool whole = i + lanes <= count;
        for (int c = 0; c < 3; ++c) {
            const auto m = hn::PromoteTo(dd, hn::GatherIndex(df, packed + c, records));
            const auto v = hn::PromoteTo(dd, hn::GatherIndex(df, packed + 3 + c, records));
            // std::max(0.0, v): v where 0 < v, else 0 (NaN and −0 included).
            hn::StoreU(hn::Add(hn::Set(dd, mean[c]), m), dd, whole ? z[c] + i : zt[c]);
            hn::StoreU(hn::Sqrt(hn::IfThenElse(hn::Gt(v, zero), v, zero)), dd, whole ? spread[c] + i : st[c]);
        }
        if (!whole)
            for (int c = 0; c < 3; ++c)
                for (std::size_t k = 0; i + k < count; ++k) z[c][i + k] = zt[c][k], spread[c][i + k] = st[c][k];
    }
}

}  // namespace stochtex::tiling_raster::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace stochtex::tiling_raster {

HWY_EXPORT(PlanTapRow);
HWY_EXPORT(AccumulateTaps);
HWY_EXPORT(ColourInputs);

void colour_inputs(const float* packed, std::size_t count, const double* mean, double* const* z, double* const* spread)
{
    HWY_DYNAMIC_DISPATCH(ColourInputs)(packed, count, mean, z, spread);
}

void accumulate_taps(const TapSums& sums, std::size_t count, float* out) { HWY_DYNAMIC_DISPATCH(AccumulateTaps)(sums, count, out); }

void plan_tap_row(const TapRow& row, const TileReads& out) { HWY_DYNAMIC_DISPATCH(PlanTapRow)(row, out); }

}  // namespace stochtex::tiling_raster
#endif
