// Highway compiles this file once per instruction set (foreach_target.h); plan_tap_row picks the
// best one the CPU has. Only Mul, Add, Sub, Div, Sqrt and Floor (never MulAdd), lane-wise: the
// same rounding on every target.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "models/tiling/tiling_raster_kernels.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include "numerics/small_integers-inl.h"
#include "numerics/small_table-inl.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "models/tiling/tiling_raster_kernels.h"

HWY_BEFORE_NAMESPACE();
namespace stochtex::tiling_raster::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Whole-number doubles (|v| < 2^31) as int32 and int64 lanes, cheaply.
using small_integers::HWY_NAMESPACE::SmallToInt32;
using small_integers::HWY_NAMESPACE::SmallToInt64;

/// The size of a level's side (a power of two) as doubles and the mask size − 1.
template <class DD>
struct Side {
    hn::Vec<DD> size, inverse;
    hn::Vec<hn::Rebind<std::int32_t, DD>> mask;
    Side(DD dd, double side)
        : size(hn::Set(dd, side)), inverse(hn::Set(dd, 1 / side)), mask(hn::Set(hn::Rebind<std::int32_t, DD>(), std::int32_t(side) - 1))
    {
    }
};

/// One axis of a bilinear lookup at p (TapRow): the fraction float(l − l0), l = p · scale − ½,
/// l0 = floor(l), and the texel l0 mod size as int32: l0 − size · floor(l0 · (1 / size)) (exact
/// for any l0, in [0, size)); on AVX-512 int64(l0) & (size − 1), the same for |l0| < 2^63, in
/// three instructions instead of five (elsewhere the int64 conversion is emulated).
template <class DD>
struct Axis {
    hn::Vec<hn::Rebind<float, DD>> fraction;
    hn::Vec<hn::Rebind<std::int32_t, DD>> texel;
};
template <class DD>
HWY_INLINE Axis<DD> AxisAt(DD dd, hn::Vec<DD> p, hn::Vec<DD> scale, const Side<DD>& side)
{
    const auto l = hn::Sub(hn::Mul(p, scale), hn::Set(dd, 0.5));
    const auto l0 = hn::Floor(l);
    const auto fraction = hn::DemoteTo(hn::Rebind<float, DD>(), hn::Sub(l, l0));
#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX3
    if constexpr (hn::MaxLanes(DD()) == 8) {
        const hn::Vec<hn::RebindToUnsigned<DD>> whole{_mm512_cvttpd_epi64(l0.raw)};
        const hn::Rebind<std::int32_t, DD> d32;
        return {fraction, hn::And(hn::BitCast(d32, hn::TruncateTo(hn::Rebind<std::uint32_t, DD>(), whole)), side.mask)};
    }
#endif
    return {fraction, SmallToInt32(dd, hn::Sub(l0, hn::Mul(side.size, hn::Floor(hn::Mul(l0, side.inverse)))))};
}

/// The y side of every vertex entry's lookups (TapRow): fy at vertex_fy + level · entries, the
/// offsets of rows iy and iy + 1 at vertex_rows + (2 · level + r) · entries.
void VertexRows(const TapRow& row)
{
    const hn::ScalableTag<double> dd;
    const hn::Rebind<float, decltype(dd)> df;
    const hn::Rebind<std::int32_t, decltype(dd)> d32;
    const std::size_t lanes = hn::Lanes(dd), entries = vertex_entries(row.columns);
    const auto y = hn::Set(dd, row.y);
    const auto one = hn::Set(d32, 1);
    for (int level = 0; level < (row.has_upper ? 2 : 1); ++level) {
        const LevelGeometry& g = level == 0 ? row.lower : row.upper;
        const Side<hn::ScalableTag<double>> side(dd, g.height);
        const auto records = hn::Set(d32, 8 * g.row);
        const auto scale = hn::Set(dd, g.scale_y);
        for (std::size_t e = 0; e < entries; e += lanes) {
            const auto axis = AxisAt(dd, hn::Add(y, hn::LoadU(dd, row.translation_y + e)), scale, side);
            hn::StoreU(axis.fraction, df, row.vertex_fy + std::size_t(level) * entries + e);
            hn::StoreU(hn::Mul(axis.texel, records), d32, row.vertex_rows + std::size_t(2 * level) * entries + e);
            hn::StoreU(hn::Mul(hn::And(hn::Add(axis.texel, one), side.mask), records), d32,
                       row.vertex_rows + std::size_t(2 * level + 1) * entries + e);
        }
    }
}

/// A vertex table read by gathers (Table's interface, for rows whose tables are too long to
/// hold in registers).
template <class D>
class Gathered {
public:
    Gathered(D, const hn::TFromD<D>* values, std::size_t, std::size_t) : values_(values) {}
    static bool fits(D, std::size_t) { return true; }
    hn::Vec<D> operator()(D d, hn::Vec<hn::RebindToSigned<D>> index) const { return hn::GatherIndex(d, values_, index); }

private:
    const hn::TFromD<D>* values_;
};

/// A tap row's vertex tables held as Table (PairTable, SmallTable, Gathered): the translations'
/// x, and per level fy and the two rows' offsets (VertexRows; the upper level's empty without one).
template <template <class> class Table>
struct VertexTables {
    using DD = hn::ScalableTag<double>;
    using DF = hn::Rebind<float, DD>;
    using D32 = hn::Rebind<std::int32_t, DD>;
    static bool fits(std::size_t columns) { return Table<DD>::fits(DD(), 2 * columns); }
    explicit VertexTables(const TapRow& row)
        : entries(vertex_entries(row.columns)), used(2 * row.columns), upper(row.has_upper ? used : 0),
          upper_entries(row.has_upper ? entries : 0), x(DD(), row.translation_x, used, entries),
          fy{{DF(), row.vertex_fy, used, entries}, {DF(), row.vertex_fy + entries, upper, upper_entries}},
          rows{{D32(), row.vertex_rows, used, entries},
               {D32(), row.vertex_rows + entries, used, entries},
               {D32(), row.vertex_rows + 2 * entries, upper, upper_entries},
               {D32(), row.vertex_rows + 3 * entries, upper, upper_entries}}
    {
    }
    std::size_t entries, used;               ///< per table: padded (vertex_entries), in use (2 · columns)
    std::size_t upper, upper_entries;        ///< the upper level's: 0 without one
    Table<DD> x;
    Table<DF> fy[2];
    Table<D32> rows[4];
};

/// PlanTapRow's loop for one level or two, the vertex tables read through `tables` (VertexTables).
template <bool Upper, class Tables>
void PlanTapRowWith(const TapRow& row, const TileReads& reads, const Tables& tables)
{
    const hn::ScalableTag<double> dd;
    const hn::RebindToSigned<decltype(dd)> di;
    const hn::RebindToUnsigned<decltype(dd)> du;
    const hn::Rebind<float, decltype(dd)> df;
    const hn::Rebind<std::int32_t, decltype(dd)> d32;
    const hn::Rebind<std::uint32_t, decltype(dd)> du32;
    const std::size_t lanes = hn::Lanes(dd);
    const auto one = hn::Set(dd, 1.0), half = hn::Set(dd, 0.5);
    const auto fy = hn::Set(dd, row.fy), i_min = hn::Set(dd, row.i_min);
    const auto shift = hn::Mul(half, hn::Set(dd, row.sy)), inverse_edge = hn::Set(dd, row.inverse_edge_x);
    const auto a = hn::Set(dd, row.a), b = hn::Set(dd, row.b);
    const auto one_f = hn::Set(df, 1.0f);
    const auto one_64 = hn::Set(di, 1), columns = hn::Set(di, std::int64_t(row.columns));
    // The tables and the levels' constants as locals, so that they stay in registers (the
    // compiler cannot tell the stores from them otherwise).
    const Tables t = tables;
    const TileReads out = reads;
    const hn::Vec<decltype(dd)> scale[2] = {hn::Set(dd, row.lower.scale_x), hn::Set(dd, row.upper.scale_x)};
    const Side<hn::ScalableTag<double>> width[2] = {{dd, row.lower.width}, {dd, row.upper.width}};
    // One level's lookup at p (vertex entry e) into tile k's fields: the two record offsets,
    // the fractions and their complements.
    auto lookup = [&](int level, hn::Vec<decltype(dd)> p, hn::Vec<decltype(d32)> e, std::int32_t* offsets, float* fractions) {
        const auto axis = AxisAt(dd, p, scale[level], width[level]);
        const auto ty = t.fy[level](df, e);
        auto store = [&](int field, hn::Vec<decltype(df)> v) { hn::StoreU(v, df, fractions + std::size_t(field) * chunk); };
        store(level == 0 ? lower_fx : upper_fx, axis.fraction);
        store(level == 0 ? lower_gx : upper_gx, hn::Sub(one_f, axis.fraction));
        store(level == 0 ? lower_fy : upper_fy, ty);
        store(level == 0 ? lower_gy : upper_gy, hn::Sub(one_f, ty));
        const auto column = hn::ShiftLeft<3>(axis.texel);
        const int row0 = level == 0 ? lower_row0 : upper_row0;
        hn::StoreU(hn::Add(t.rows[2 * level](d32, e), column), d32, offsets + std::size_t(row0) * chunk);
        hn::StoreU(hn::Add(t.rows[2 * level + 1](d32, e), column), d32, offsets + std::size_t(row0 + 1) * chunk);
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
        // The tiles' vertex entries: column c = cx − i_min (exact: a small integer) and c + 1,
        // row j or j + 1; as int64 for the translations, as int32 for the other tables.
        const auto c = SmallToInt64(dd, hn::Sub(cx, i_min));
        const auto below = hn::Add(c, columns);
        const hn::Vec<decltype(di)> entry[3] = {hn::IfThenElse(hn::RebindMask(di, upper), hn::Add(below, one_64), c), hn::Add(c, one_64),
                                                below};
        HWY_UNROLL(3)
        for (int k = 0; k < 3; ++k) {
            std::int32_t* offsets = out.offsets + std::size_t(k * offset_fields) * chunk + i;
            float* fractions = out.fractions + std::size_t(k * fraction_fields) * chunk + i;
            const auto w = hn::DemoteTo(df, weights[k]);
            hn::StoreU(w, df, fractions + std::size_t(weight) * chunk);
            hn::StoreU(hn::Mul(w, w), df, fractions + std::size_t(weight_squared) * chunk);
            const auto p = hn::Add(x, t.x(dd, entry[k]));
            const auto e = hn::BitCast(d32, hn::TruncateTo(du32, hn::BitCast(du, entry[k])));
            lookup(0, p, e, offsets, fractions);
            if (Upper) lookup(1, p, e, offsets, fractions);
        }
    }
}

/// PlanTapRowWith for the row's level count.
template <class Tables>
void PlanTapRowOf(const TapRow& row, const TileReads& out, const Tables& tables)
{
    if (row.has_upper)
        PlanTapRowWith<true>(row, out, tables);
    else
        PlanTapRowWith<false>(row, out, tables);
}

void PlanTapRow(const TapRow& row, const TileReads& out)
{
    // A row's tables span a few vertex columns (a 64-pixel chunk at 4 exemplar pixels per pixel:
    // about 5, 10 entries): in registers, read by permutations, where they fit; else gathered.
    using small_table::HWY_NAMESPACE::PairTable;
    using small_table::HWY_NAMESPACE::SmallTable;
    VertexRows(row);
    if (VertexTables<PairTable>::fits(row.columns))
        PlanTapRowOf(row, out, VertexTables<PairTable>(row));
    else if (VertexTables<SmallTable>::fits(row.columns))
        PlanTapRowOf(row, out, VertexTables<SmallTable>(row));
    else
        PlanTapRowOf(row, out, VertexTables<Gathered>(row));
}

/// SetTableIndices' result for tag D (Highway 1.0 names no such type).
template <class D>
using IndicesOf = decltype(hn::SetTableIndices(D(), static_cast<const std::int32_t*>(nullptr)));

/// Record lanes of one position per vector (AVX2, AVX-512): lane j is record lane j.
template <int Channels>
struct OneRecord {
    using P = RecordPairs<Channels>;
    using D = hn::CappedTag<float, 8>;
    static constexpr std::size_t positions = 1;
    D d;
    hn::Mask<D> means = hn::FirstN(d, Channels), used = hn::FirstN(d, Channels + P::count);
    IndicesOf<D> first, second;  ///< moment lane C + p reads delta[first p] · delta[second p]
    OneRecord()
    {
        std::int32_t a[hn::MaxLanes(D())] = {}, b[hn::MaxLanes(D())] = {};
        for (int p = 0; p < P::count; ++p) a[Channels + p] = P::first[p], b[Channels + p] = P::second[p];
        first = hn::SetTableIndices(d, a), second = hn::SetTableIndices(d, b);
    }
    /// A field's value of the position at f.
    hn::Vec<D> factor(const float* f) const { return hn::Set(d, f[0]); }
    /// The texel row's two records (left, right) at the position's offset.
    void texels(const float* data, const std::int32_t* offset, hn::Vec<D>* pair) const
    {
        pair[0] = hn::LoadU(d, data + offset[0]), pair[1] = hn::LoadU(d, data + offset[0] + 8);
    }
    void store(hn::Vec<D> v, float* out) const { hn::StoreU(v, d, out); }
};

#if HWY_TARGET != HWY_SCALAR  // (no Combine there; it holds one lane anyway)
/// Two positions per vector where a vector holds two records (AVX-512), interleaved: lane
/// 2j + q is record lane j of position q. The fields of positions l and l + 1 are adjacent, so
/// a factor is one 8-byte broadcast; a texel row's records of both are interleaved by lane
/// permutations (two-table ones on AVX-512: vpermt2ps), and de-interleaved by the store.
template <int Channels>
struct TwoRecords {
    using P = RecordPairs<Channels>;
    using D = hn::ScalableTag<float>;
    static constexpr std::size_t positions = 2, lanes = hn::MaxLanes(D());
    D d;
    hn::Mask<D> means = hn::FirstN(d, 2 * Channels), used = hn::FirstN(d, 2 * (Channels + P::count));
    IndicesOf<D> first, second, interleaved, deinterleaved;
    hn::Vec<hn::RebindToSigned<D>> left, right;  ///< vpermt2ps's: 0–15 the first table, 16–31 the second
    TwoRecords()
    {
        std::int32_t a[lanes], b[lanes], in[lanes], back[lanes], l[lanes], r[lanes];
        for (std::size_t k = 0; k < lanes; ++k) {
            const int j = int(k / 2), q = int(k % 2), pair = j - Channels;
            const bool moment = pair >= 0 && pair < P::count;
            a[k] = std::int32_t(moment ? 2 * P::first[std::max(pair, 0)] + q : q);
            b[k] = std::int32_t(moment ? 2 * P::second[std::max(pair, 0)] + q : q);
            in[k] = std::int32_t(q * 8 + j), back[k] = std::int32_t((k % 8) * 2 + k / 8);
            l[k] = std::int32_t(q * 16 + j), r[k] = l[k] + 8;
        }
        first = hn::SetTableIndices(d, a), second = hn::SetTableIndices(d, b);
        interleaved = hn::SetTableIndices(d, in), deinterleaved = hn::SetTableIndices(d, back);
        const hn::RebindToSigned<D> di;
        left = hn::LoadU(di, l), right = hn::LoadU(di, r);
    }
    hn::Vec<D> factor(const float* f) const
    {
        const hn::Repartition<std::uint64_t, D> du64;
        std::uint64_t bits;
        std::memcpy(&bits, f, sizeof bits);
        return hn::BitCast(d, hn::Set(du64, bits));
    }
    void texels(const float* data, const std::int32_t* offset, hn::Vec<D>* pair) const
    {
#if HWY_TARGET == HWY_AVX3 || HWY_TARGET == HWY_AVX3_DL
        const auto a = hn::LoadU(d, data + offset[0]), b = hn::LoadU(d, data + offset[1]);
        pair[0] = hn::Vec<D>{_mm512_permutex2var_ps(a.raw, left.raw, b.raw)};
        pair[1] = hn::Vec<D>{_mm512_permutex2var_ps(a.raw, right.raw, b.raw)};
#else
        const hn::Half<D> dh;
        for (int side = 0; side < 2; ++side)
            pair[side] = hn::TableLookupLanes(
                hn::Combine(d, hn::LoadU(dh, data + offset[1] + side * 8), hn::LoadU(dh, data + offset[0] + side * 8)), interleaved);
#endif
    }
    void store(hn::Vec<D> v, float* out) const { hn::StoreU(hn::TableLookupLanes(v, deinterleaved), d, out); }
};
#endif

/// AccumulateTaps' lookups and mixture on whole-record vectors laid out by L (OneRecord,
/// TwoRecords), for the positions from `first` on in steps of L::positions while a step fits;
/// returns the first position left. Per tap, the three tiles' bilinear records weighted by w on
/// the mean lanes and w² on the others (what w · (1 + w · 0) and w · (0 + w · 1) are, exactly);
/// then the mixture, lane-wise: the mean lanes take result + ratio · delta, moment lane C + p
/// takes result + (weight · m + scatter · delta[first p] · delta[second p]), the deltas brought to
/// it by a lane lookup. The running means and moments are two registers, so that the next tap's
/// deltas wait on the means' chain alone.
template <bool Upper, int Taps, class L>
std::size_t AccumulateVectors(const TapSums& s, std::size_t first, std::size_t count, float* out, const L& layout)
{
    const typename L::D d;
    const int taps = Taps > 0 ? Taps : s.taps;
    const auto level_t = hn::Set(d, s.t), tap_weight = hn::Set(d, s.weight), inverse_total = hn::Set(d, s.inverse_total);
    std::size_t l = first;
    for (; l + L::positions <= count; l += L::positions) {
        auto means = hn::Zero(d), moments = hn::Zero(d);
        for (int k = 0; k < taps; ++k) {
            auto sum = hn::Zero(d);
            for (int tile = 0; tile < 3; ++tile) {
                const std::size_t run = std::size_t(k) * 3 + std::size_t(tile);
                const std::int32_t* offsets = s.offsets + run * offset_fields * chunk + l;
                const float* fractions = s.fractions + run * fraction_fields * chunk + l;
                auto field = [&](int f) { return layout.factor(fractions + std::size_t(f) * chunk); };
                auto bilinear = [&](const float* data, int row, int fraction) {
                    hn::Vec<typename L::D> row0[2], row1[2];
                    layout.texels(data, offsets + std::size_t(row) * chunk, row0);
                    layout.texels(data, offsets + std::size_t(row + 1) * chunk, row1);
                    const auto vx = field(fraction), vy = field(fraction + 1), sx = field(fraction + 5), sy = field(fraction + 6);
                    const auto low = hn::Add(hn::Mul(sx, row0[0]), hn::Mul(vx, row0[1]));
                    const auto high = hn::Add(hn::Mul(sx, row1[0]), hn::Mul(vx, row1[1]));
                    return hn::Add(hn::Mul(sy, low), hn::Mul(vy, high));
                };
                auto sample = bilinear(s.lower, 0, 0);
                if (Upper) sample = hn::Add(sample, hn::Mul(level_t, hn::Sub(bilinear(s.upper, 2, 2), sample)));
                sum = hn::Add(sum, hn::Mul(hn::IfThenElse(layout.means, field(4), field(9)), sample));
            }
            if (taps == 1) {
                means = moments = sum;
                break;
            }
            const auto delta = hn::Sub(sum, means);
            const auto products = hn::Mul(hn::TableLookupLanes(delta, layout.first), hn::TableLookupLanes(delta, layout.second));
            means = hn::Add(means, hn::Mul(hn::Set(d, s.ratio[k]), delta));
            moments = hn::Add(moments, hn::Add(hn::Mul(tap_weight, sum), hn::Mul(hn::Set(d, s.scatter[k]), products)));
        }
        // Lanes past the kept moments stay 0, as in the scalar form.
        const auto scaled = hn::IfThenElse(layout.means, means, taps == 1 ? moments : hn::Mul(moments, inverse_total));
        layout.store(hn::IfThenElseZero(layout.used, scaled), out + l * 8);
    }
    return l;
}

/// AccumulateTaps for a channel count, one or two levels and (Taps > 0) a tap count known at
/// compile time, so the loops unroll into registers and every field of a position is at a fixed
/// distance from its first (the same operations as with them at run time).
template <int Channels, bool Upper, int Taps>
void AccumulateTapsFor(const TapSums& s, std::size_t count, float* out)
{
    // No software prefetch of the records: an earlier version asked for the lines of the
    // position three ahead from a lambda, which GCC 12 took for a function without effects and
    // dropped (no prefetch instruction was ever emitted); written so that it is emitted, it made
    // Render/Raster/colour 16 % slower (12 % with one line per record) — the hardware keeps up.
    //
    // A record in one vector (AVX2, AVX-512): the lookups and mixture run on vectors, two
    // positions per vector where it holds two records; else on parts of a record and scalars.
    if constexpr (!HWY_HAVE_SCALABLE && HWY_MAX_BYTES >= 32) {
        std::size_t first = 0;
#if HWY_TARGET != HWY_SCALAR
        if constexpr (HWY_MAX_BYTES == 64) first = AccumulateVectors<Upper, Taps>(s, 0, count, out, TwoRecords<Channels>());
#endif
        AccumulateVectors<Upper, Taps>(s, first, count, out, OneRecord<Channels>());
        return;
    }
    using P = RecordPairs<Channels>;
    constexpr int record = 8;
    const hn::CappedTag<float, record> df;
    const int step = int(hn::Lanes(df)), parts = record / step;
    const int taps = Taps > 0 ? Taps : s.taps;
    auto at_offsets = [&](std::size_t run, int field) { return s.offsets + (run * offset_fields + std::size_t(field)) * chunk; };
    auto at_fractions = [&](std::size_t run, int field) { return s.fractions + (run * fraction_fields + std::size_t(field)) * chunk; };
    const auto level_t = hn::Set(df, s.t);
    hn::Mask<decltype(df)> part_means[record];  // the mean lanes of each part of a record
    for (int h = 0; h < parts; ++h) part_means[h] = hn::FirstN(df, std::size_t(std::max(0, Channels - h * step)));
    for (std::size_t l = 0; l < count; ++l) {
        float result[record] = {};
        for (int k = 0; k < taps; ++k) {
            hn::Vec<decltype(df)> sum[record] = {};
            for (int h = 0; h < parts; ++h) sum[h] = hn::Zero(df);
            for (int tile = 0; tile < 3; ++tile) {
                const std::size_t run = std::size_t(k) * 3 + std::size_t(tile);
                // The tile's weights on the record: w on the mean lanes, w² on the others.
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
