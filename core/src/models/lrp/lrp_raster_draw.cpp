// Highway compiles this file once per instruction set (foreach_target.h); the entry points at the
// end pick the best one the CPU has. Every operation is one that draw() performs, lane by lane
// (lrp_raster_draw.h): change both or neither.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "models/lrp/lrp_raster_draw.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include "models/lrp/lrp_raster_draw.h"

HWY_BEFORE_NAMESPACE();
namespace stochtex::lrp_raster::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

/// SplitMix64's increment (numerics/random.h): output n of a stream is Mix(seed + n·γ).
constexpr std::uint64_t golden_gamma = 0x9e3779b97f4a7c15ull;

/// SplitMix64::next's output function, lane-wise.
template <class D, class V>
HWY_INLINE V Mix(D d, V z)
{
    z = hn::Mul(hn::Xor(z, hn::ShiftRight<30>(z)), hn::Set(d, 0xbf58476d1ce4e5b9ull));
    z = hn::Mul(hn::Xor(z, hn::ShiftRight<27>(z)), hn::Set(d, 0x94d049bb133111ebull));
    return hn::Xor(z, hn::ShiftRight<31>(z));
}

/// Output n (from 1) of each lane's stream.
template <class D>
HWY_INLINE hn::Vec<D> Output(D d, hn::Vec<D> seed, std::uint64_t n)
{
    return Mix(d, hn::Add(seed, hn::Set(d, n * golden_gamma)));
}

/// std::round (half away from zero), exactly: v − trunc v is exact, and trunc keeps the sign of 0.
template <class D>
HWY_INLINE hn::Vec<D> RoundHalfAway(D d, hn::Vec<D> v)
{
    const auto whole = hn::Trunc(v);
    const auto away = hn::Ge(hn::Abs(hn::Sub(v, whole)), hn::Set(d, 0.5));
    return hn::IfThenElse(away, hn::Add(whole, hn::CopySign(hn::Set(d, 1.0), v)), whole);
}

/// (bin + jitter) · inverse_size, the 16 jitter bits at `shift` of `bits`, snapped where periodic.
template <int shift, class D, class VU>
HWY_INLINE hn::Vec<D> Frequency(D d, hn::Vec<D> bin, VU bits, double inverse_size, double period)
{
    const hn::RebindToSigned<D> di;
    const auto field = hn::ConvertTo(d, hn::BitCast(di, hn::And(hn::ShiftRight<shift>(bits), hn::Set(hn::RebindToUnsigned<D>(), 0xffff))));
    const auto jitter = hn::Add(hn::Sub(hn::Div(field, hn::Set(d, 65536.0)), hn::Set(d, 0.5)), hn::Set(d, 1.0 / 131072));
    auto f = hn::Mul(hn::Add(bin, jitter), hn::Set(d, inverse_size));
    if (period > 0) f = hn::Div(RoundHalfAway(d, hn::Mul(f, hn::Set(d, period))), hn::Set(d, period));
    return f;
}

/// The low and high 32 bits of each lane, as float or int32 lanes of half the width.
template <class D32, class VU>
HWY_INLINE hn::Vec<D32> LowHalf(D32 d, VU v)
{
    return hn::BitCast(d, hn::TruncateTo(hn::RebindToUnsigned<D32>(), v));
}
template <class D32, class VU>
HWY_INLINE hn::Vec<D32> HighHalf(D32 d, VU v)
{
    return LowHalf(d, hn::ShiftRight<32>(v));
}

void DrawFrequencies(const TermRow& row)
{
    const hn::ScalableTag<double> dd;
    const hn::RebindToUnsigned<decltype(dd)> du;
    const hn::RebindToSigned<decltype(dd)> di;
    const hn::Rebind<float, decltype(dd)> df;
    const hn::Rebind<std::int32_t, decltype(dd)> di32;
    const std::size_t lanes = hn::Lanes(dd);
    for (int t = 0; t < row.terms; ++t) {
        const std::uint32_t first = row.first[t], count = row.first[t + 1] - first;
        for (std::size_t w = 0; w < row.count; w += lanes) {
            const auto bits = Output(du, hn::LoadU(du, row.seed + w), 2 * std::uint64_t(t) + 1);
            // A bin of the sub-stratum (top 32 bits, multiply-shift): its kx, ky by one gather.
            const auto b = hn::Add(hn::Set(du, first), hn::ShiftRight<32>(hn::Mul(hn::ShiftRight<32>(bits), hn::Set(du, count))));
            const auto bin = hn::GatherIndex(du, row.bins, hn::BitCast(di, b));
            const auto fx = Frequency<16>(dd, hn::PromoteTo(dd, LowHalf(di32, bin)), bits, row.inverse_size, row.period[0]);
            const auto fy = Frequency<0>(dd, hn::PromoteTo(dd, HighHalf(di32, bin)), bits, row.inverse_size, row.period[1]);
            const std::size_t out = std::size_t(t) * row.stride + w;
            hn::StoreU(hn::DemoteTo(df, fx), df, row.fx + out);
            hn::StoreU(hn::DemoteTo(df, fy), df, row.fy + out);
            if (row.fx_exact) hn::StoreU(fx, dd, row.fx_exact + out), hn::StoreU(fy, dd, row.fy_exact + out);
        }
    }
}

void DrawCoefficients(const TermRow& row)
{
    const hn::ScalableTag<std::uint64_t> du;
    const hn::RebindToSigned<decltype(du)> di;
    const hn::Rebind<float, decltype(du)> df;
    const std::size_t lanes = hn::Lanes(du);
    const auto mask = hn::Set(du, (std::uint64_t(1) << row.phase_bits) - 1);
    for (int t = 0; t < row.terms; ++t)
        for (std::size_t w = 0; w < row.count; w += lanes) {
            const auto bits = Output(du, hn::LoadU(du, row.seed + w), 2 * std::uint64_t(t) + 2);
            const std::size_t out = std::size_t(t) * row.stride + w;
            for (int c = 0; c < 3; ++c) {
                const auto phase = hn::BitCast(di, hn::And(hn::ShiftRightSame(bits, row.shared_phase ? 0 : row.phase_bits * c), mask));
                const auto amplitude = row.response ? hn::Mul(hn::Set(df, row.amplitude[c]), hn::LoadU(df, row.response + out))
                                                    : hn::Set(df, row.amplitude[c]);  // draw(): amplitude · 1
                const auto cosine_sine = hn::GatherIndex(du, row.phases, phase);
                hn::StoreU(hn::Mul(amplitude, LowHalf(df, cosine_sine)), df, row.re[c] + out);
                hn::StoreU(hn::Mul(amplitude, HighHalf(df, cosine_sine)), df, row.im[c] + out);
            }
        }
}

}  // namespace stochtex::lrp_raster::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace stochtex::lrp_raster {

HWY_EXPORT(DrawFrequencies);
HWY_EXPORT(DrawCoefficients);

void draw_frequencies(const TermRow& row) { HWY_DYNAMIC_DISPATCH(DrawFrequencies)(row); }

void draw_coefficients(const TermRow& row) { HWY_DYNAMIC_DISPATCH(DrawCoefficients)(row); }

}  // namespace stochtex::lrp_raster
#endif
