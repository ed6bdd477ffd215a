// Highway compiles this file once per instruction set (foreach_target.h); sum_row picks the best
// one the CPU has. Only Mul, Add and Sub (never MulAdd) and bit operations, lane-wise: the same
// IEEE results on every target, so values do not depend on the CPU.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "models/gabor/gabor_raster_kernels.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include <algorithm>
#include <cmath>

#include "models/gabor/gabor_raster_kernels.h"
#include "numerics/fast_math-inl.h"

HWY_BEFORE_NAMESPACE();
namespace stochtex::gabor_raster::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using fast_math::HWY_NAMESPACE::FastExp;
using fast_math::HWY_NAMESPACE::FastSinCosTurns;

template <class DF>
struct KernelAt {
    hn::Vec<DF> q, turns;
    hn::Mask<DF> keep;
};

template <bool Solid, int Channels>
void SumRowOf(const RowInput& in, const double* x, std::size_t count, float* const out[3])
{
    // One double lane per point (positions are doubles: d = p − c must not lose the point's
    // precision far from the origin), the kernel itself in float on as many lanes.
    const hn::ScalableTag<double> dd;
    const hn::Rebind<float, decltype(dd)> df;
#if HWY_TARGET != HWY_SCALAR
    const hn::Twice<decltype(df)> df2;
#endif
    using Kernel = KernelAt<decltype(df)>;
    const std::size_t lanes = hn::Lanes(dd);
    const CellImpulses& cells = *in.cells;
    const Envelope& envelope = in.envelope;
    const auto limit = hn::Set(df, envelope.limit), exp_floor = hn::Set(df, -87.0f);
    const auto e0x = hn::Set(df, envelope.e[0][0]), e1x = hn::Set(df, envelope.e[1][0]), e2x = hn::Set(df, envelope.e[2][0]);
    const double inverse_cell = 1 / in.cell_x;
    HWY_ALIGN double lane_x[HWY_MAX_BYTES / sizeof(double)];
    HWY_ALIGN float result[HWY_MAX_BYTES / sizeof(float)];

    for (std::size_t start = 0; start < count; start += lanes) {
        const std::size_t n = std::min(lanes, count - start);
        // Unused lanes repeat the last point (evaluated, not stored).
        for (std::size_t k = 0; k < lanes; ++k) lane_x[k] = x[start + std::min(k, n - 1)];
        const double x_min = *std::min_element(lane_x, lane_x + n), x_max = *std::max_element(lane_x, lane_x + n);
        const auto px = hn::Load(dd, lane_x);
        auto sum0 = hn::Zero(dd), sum1 = hn::Zero(dd), sum2 = hn::Zero(dd);
        // Cell m's q, turns and support mask at the lanes' points.
        auto kernel = [&](std::size_t m) {
            Kernel k;
            const auto dx = hn::DemoteTo(df, hn::Sub(px, hn::Set(dd, cells.x[m])));
            const float dy = float(in.y - cells.y[m]);
            // q and the turns: the lane's x part plus the cell's (y, z) part.
            if constexpr (Solid) {
                const float dz = float(in.z - cells.z[m]);
                const auto u0 = hn::Add(hn::Mul(e0x, dx), hn::Set(df, envelope.e[0][1] * dy + envelope.e[0][2] * dz));
                const auto u1 = hn::Add(hn::Mul(e1x, dx), hn::Set(df, envelope.e[1][1] * dy + envelope.e[1][2] * dz));
                const auto u2 = hn::Add(hn::Mul(e2x, dx), hn::Set(df, envelope.e[2][1] * dy + envelope.e[2][2] * dz));
                k.q = hn::Add(hn::Add(hn::Mul(u0, u0), hn::Mul(u1, u1)), hn::Mul(u2, u2));
                k.turns = hn::Add(hn::Mul(hn::Set(df, cells.wx[m]), dx), hn::Set(df, cells.wy[m] * dy + cells.wz[m] * dz));
            } else {
                const auto u = hn::Add(hn::Mul(e1x, dx), hn::Set(df, envelope.e[1][1] * dy));
                const float v = envelope.e[2][1] * dy;
                k.q = hn::Add(hn::Mul(u, u), hn::Set(df, v * v));
                k.turns = hn::Add(hn::Mul(hn::Set(df, cells.wx[m]), dx), hn::Set(df, cells.wy[m] * dy));
            }
            k.keep = hn::Le(k.q, limit);
            return k;
        };
        // Cell m's kernel added to the sums, from its envelope (zero where the lane is outside
        // the support) and sin/cos.
        auto add = [&](std::size_t m, const Kernel& k, hn::Vec<decltype(df)> envelope_value, hn::Vec<decltype(df)> s,
                       hn::Vec<decltype(df)> c) {
            envelope_value = hn::IfThenElseZero(k.keep, envelope_value);
            // cos(2πT + φ) = cos 2πT cos φ − sin 2πT sin φ: one sin/cos for every channel.
            const auto es = hn::Mul(envelope_value, s), ec = hn::Mul(envelope_value, c);
            sum0 = hn::Add(sum0, hn::PromoteTo(dd, hn::Sub(hn::Mul(ec, hn::Set(df, cells.cos_phase[0][m])),
                                                           hn::Mul(es, hn::Set(df, cells.sin_phase[0][m])))));
            if constexpr (Channels == 3) {
                sum1 = hn::Add(sum1, hn::PromoteTo(dd, hn::Sub(hn::Mul(ec, hn::Set(df, cells.cos_phase[1][m])),
                                                               hn::Mul(es, hn::Set(df, cells.sin_phase[1][m])))));
                sum2 = hn::Add(sum2, hn::PromoteTo(dd, hn::Sub(hn::Mul(ec, hn::Set(df, cells.cos_phase[2][m])),
                                                               hn::Mul(es, hn::Set(df, cells.sin_phase[2][m])))));
            }
        };
        auto exponent_of = [&](std::size_t m, const Kernel& k) {
            return hn::Max(hn::Sub(hn::Set(df, cells.log_amplitude[m]), k.q), exp_floor);
        };
        for (std::size_t r = 0; r < in.row_count; ++r) {
            const CellRow& row = in.rows[r];
            const std::int64_t first = row.every_cell ? 0 : std::max<std::int64_t>(std::int64_t(std::floor((x_min + row.lo) * inverse_cell)) - row.i_first, 0);
            const std::int64_t last = row.every_cell ? std::int64_t(row.count) - 1
                                                     : std::min<std::int64_t>(std::int64_t(std::floor((x_max + row.hi) * inverse_cell)) - row.i_first,
                                                                              std::int64_t(row.count) - 1);
            // Two cells at a time: their kernels are independent chains of arithmetic that the
            // core overlaps; their values still enter the sums one after the other, in order.
            for (std::int64_t i = first; i <= last; i += 2) {
                const std::size_t m = row.first + std::size_t(i);
                const bool pair = i + 1 <= last;
                Kernel k0 = kernel(m), k1 = pair ? kernel(m + 1) : k0;
                const bool any0 = !hn::AllFalse(df, k0.keep), any1 = pair && !hn::AllFalse(df, k1.keep);
                if (!any0 && !any1) continue;
#if HWY_TARGET == HWY_SCALAR
                // One lane: no wider vector to pair the cells in.
                for (int half = 0; half < 2; ++half) {
                    if (!(half ? any1 : any0)) continue;
                    const Kernel& k = half ? k1 : k0;
                    hn::Vec<decltype(df)> s, c;
                    FastSinCosTurns(df, k.turns, s, c);
                    add(m + std::size_t(half), k, FastExp(df, exponent_of(m + std::size_t(half), k)), s, c);
                }
#else
                // The two cells' exp and sin/cos on one vector of twice the lanes (half the
                // instructions: the polynomials' latency is what bounds this loop).
                const auto envelope_values = FastExp(df2, hn::Combine(df2, exponent_of(m + pair, k1), exponent_of(m, k0)));
                hn::Vec<decltype(df2)> s, c;
                FastSinCosTurns(df2, hn::Combine(df2, k1.turns, k0.turns), s, c);
                if (any0) add(m, k0, hn::LowerHalf(df, envelope_values), hn::LowerHalf(df, s), hn::LowerHalf(df, c));
                if (any1) add(m + 1, k1, hn::UpperHalf(df, envelope_values), hn::UpperHalf(df, s), hn::UpperHalf(df, c));
#endif
            }
        }
        const auto gain = hn::Set(dd, in.gain);
        const hn::Vec<decltype(dd)> sums[3] = {sum0, sum1, sum2};
        for (int ch = 0; ch < Channels; ++ch) {
            hn::Store(hn::DemoteTo(df, hn::Mul(sums[ch], gain)), df, result);
            std::copy(result, result + n, out[ch] + start);
        }
    }
}

/// SplitMix64's output function (gabor_noise.cpp's mix64), lane-wise.
template <class D, class V>
V Mix64(D d, V z)
{
    z = hn::Mul(hn::Xor(z, hn::ShiftRight<30>(z)), hn::Set(d, 0xbf58476d1ce4e5b9ull));
    z = hn::Mul(hn::Xor(z, hn::ShiftRight<27>(z)), hn::Set(d, 0x94d049bb133111ebull));
    return hn::Xor(z, hn::ShiftRight<31>(z));
}

std::size_t TestCandidates(const CandidateTest& in, const CandidateRow* rows, std::size_t row_count, std::uint64_t* key_out,
                           double* x_out, double* y_out, double* z_out)
{
    const hn::ScalableTag<double> dd;
    const hn::RebindToUnsigned<decltype(dd)> du;
    const hn::RebindToSigned<decltype(dd)> di;
    const std::size_t lanes = hn::Lanes(dd);
    const auto cell = hn::Set(dd, in.cell), half = hn::Set(dd, 0.5), scale = hn::Set(dd, 0x1.0p-21);
    const auto field = hn::Set(du, 0x1fffffull);
    const auto px = hn::Set(dd, in.p[0]), py = hn::Set(dd, in.p[1]), pz = hn::Set(dd, in.p[2]);
    const auto m00 = hn::Set(dd, in.m[0][0]), m11 = hn::Set(dd, in.m[1][1]), m22 = hn::Set(dd, in.m[2][2]);
    const auto m01 = hn::Set(dd, in.m[0][1]), m02 = hn::Set(dd, in.m[0][2]), m12 = hn::Set(dd, in.m[1][2]);
    const auto two = hn::Set(dd, 2.0), limit = hn::Set(dd, in.limit);
    const auto lane_steps = hn::Mul(hn::Iota(du, 0), hn::Set(du, in.step_i));
    // (int32(bits & 0x1fffff) + ½)·2^-21 · cell, plus the index times the cell, as position_fraction.
    auto coordinate = [&](hn::Vec<decltype(dd)> index, hn::Vec<decltype(du)> bits) {
        const auto fraction = hn::Mul(hn::Add(hn::ConvertTo(dd, hn::BitCast(di, hn::And(bits, field))), half), scale);
        return hn::Add(hn::Mul(index, cell), hn::Mul(fraction, cell));
    };
    std::size_t kept = 0;
    for (std::size_t r = 0; r < row_count; ++r) {
        const CandidateRow& row = rows[r];
        const std::uint64_t base = in.key0 + std::uint64_t(row.j) * in.step_j + std::uint64_t(row.k) * in.step_k;
        const auto j = hn::Set(dd, double(row.j)), k = hn::Set(dd, double(row.k));
        for (std::int64_t i0 = row.i0; i0 <= row.i1; i0 += std::int64_t(lanes)) {
            const std::size_t n = std::min<std::size_t>(lanes, std::size_t(row.i1 - i0 + 1));
            const auto key = hn::Add(hn::Set(du, base + std::uint64_t(i0) * in.step_i), lane_steps);
            const auto bits = Mix64(du, key);
            const auto i = hn::ConvertTo(dd, hn::Add(hn::Set(di, i0), hn::Iota(di, 0)));
            const auto cx = coordinate(i, bits), cy = coordinate(j, hn::ShiftRight<21>(bits)),
                       cz = coordinate(k, hn::ShiftRight<42>(bits));
            const auto d0 = hn::Sub(px, cx), d1 = hn::Sub(py, cy), d2 = hn::Sub(pz, cz);
            // dᵀMd by the same IEEE operations in every lane (no fused multiply-add), so every
            // instruction set keeps the same cells.
            const auto diagonal = hn::Add(hn::Add(hn::Mul(hn::Mul(m00, d0), d0), hn::Mul(hn::Mul(m11, d1), d1)),
                                          hn::Mul(hn::Mul(m22, d2), d2));
            const auto cross = hn::Add(hn::Add(hn::Mul(hn::Mul(m01, d0), d1), hn::Mul(hn::Mul(m02, d0), d2)),
                                       hn::Mul(hn::Mul(m12, d1), d2));
            const auto q = hn::Add(diagonal, hn::Mul(two, cross));
            const auto keep = hn::And(hn::Le(q, limit), hn::FirstN(dd, n));
            hn::CompressStore(key, hn::RebindMask(du, keep), du, key_out + kept);
            hn::CompressStore(cx, keep, dd, x_out + kept);
            hn::CompressStore(cy, keep, dd, y_out + kept);
            kept += hn::CompressStore(cz, keep, dd, z_out + kept);
        }
    }
    return kept;
}

void SumRow(const RowInput& in, const double* x, std::size_t count, float* const out[3])
{
    if (in.solid) {
        if (in.channels == 3) SumRowOf<true, 3>(in, x, count, out);
        else SumRowOf<true, 1>(in, x, count, out);
    } else {
        if (in.channels == 3) SumRowOf<false, 3>(in, x, count, out);
        else SumRowOf<false, 1>(in, x, count, out);
    }
}

}  // namespace stochtex::gabor_raster::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace stochtex::gabor_raster {

HWY_EXPORT(SumRow);
HWY_EXPORT(TestCandidates);

std::size_t test_candidates(const CandidateTest& test, const CandidateRow* rows, std::size_t row_count, std::uint64_t* key,
                            double* x, double* y, double* z)
{
    return HWY_DYNAMIC_DISPATCH(TestCandidates)(test, rows, row_count, key, x, y, z);
}

void CellImpulses::clear()
{
    for (std::vector<double>* v : {&x, &y, &z}) v->clear();
    for (std::vector<float>* v : {&wx, &wy, &wz, &log_amplitude}) v->clear();
    for (int c = 0; c < 3; ++c) cos_phase[c].clear(), sin_phase[c].clear();
}

void CellImpulses::resize(std::size_t n)
{
    for (std::vector<double>* v : {&x, &y, &z}) v->resize(n);
    for (std::vector<float>* v : {&wx, &wy, &wz, &log_amplitude}) v->resize(n);
    for (int c = 0; c < 3; ++c) cos_phase[c].resize(n), sin_phase[c].resize(n);
}

void sum_row(const RowInput& input, const double* x, std::size_t count, float* const out[3])
{
    HWY_DYNAMIC_DISPATCH(SumRow)(input, x, count, out);
}

}  // namespace stochtex::gabor_raster
#endif
