#include "models/lrp/lrp_noise.h"
#include "models/lrp/lrp_raster_draw.h"
#include <stochtex/models/lrp_parameters.h>

#include "numerics/fast_math.h"
#include "numerics/random.h"
#include "numerics/constants.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace stochtex {

namespace {

/// Share of the window's spectral energy whose radius stands for its spread in the fades.
constexpr double spread_energy = 0.75;
/// Responses below this are dropped (the rest rescaled so the response stays continuous).
constexpr double response_floor = 1.0 / 256;

}  // namespace

LrpFilter LrpFilter::from_footprint(const Footprint2D& footprint, double pixels_per_unit)
{
    LrpFilter filter;
    const Symmetric2 pixel = filter_covariance(footprint, pixels_per_unit);
    filter.covariance = without_isotropic_blur(pixel, pixel_filter_sigma * pixel_filter_sigma);
    filter.major_sd = std::sqrt(std::max(0.0, filter.covariance.largest_eigenvalue()));
    filter.identity = !(filter.major_sd > 0);
    return filter;
}

float LrpFilter::response(double fx, double fy, double spread) const
{
    if (identity) return 1.0f;
    const double q = std::sqrt(std::max(0.0, covariance.quadratic_form(fx, fy))) + spread * major_sd;
    const double g = std::exp(-2 * kPi * kPi * q * q);
    return g <= response_floor ? 0.0f : float((g - response_floor) / (1 - response_floor));
}

void LrpTerms::pad()
{
    const float zero[3] = {0, 0, 0};
    const int real = count;
    while (count % lanes) push(0, 0, zero, zero);
    live = real;
}

void sum_terms(const LrpTermView& terms, float dx, float dy, float out[3])
{
    // lrp_raster::sum_terms_at repeats these operations lane by lane: change both or neither.
    constexpr int lanes = LrpTerms::lanes;
    float sum[3][lanes] = {};
    const float* fx = terms.fx();
    const float* fy = terms.fy();
    const float* re[3] = {terms.re(0), terms.re(1), terms.re(2)};
    const float* im[3] = {terms.im(0), terms.im(1), terms.im(2)};
    for (int t = 0; t < terms.count; t += lanes)
        for (int l = 0; l < lanes; ++l) {
            float sine, cosine;
            fast_sincos_turns(fx[t + l] * dx + fy[t + l] * dy, sine, cosine);
            for (int c = 0; c < 3; ++c) sum[c][l] += re[c][t + l] * cosine - im[c][t + l] * sine;
        }
    for (int c = 0; c < 3; ++c) out[c] = (sum[c][0] + sum[c][1]) + (sum[c][2] + sum[c][3]);
}

void sum_terms_separable(const LrpTermView& terms, float dx, float dy, float out[3])
{
    // lrp_raster_kernels.cpp repeats these operations lane by lane (pixels are its lanes, so one
    // running sum per channel keeps its registers free): change both or neither.
    float sum[3] = {0, 0, 0};
    const float* fx = terms.fx();
    const float* fy = terms.fy();
    const float* re[3] = {terms.re(0), terms.re(1), terms.re(2)};
    const float* im[3] = {terms.im(0), terms.im(1), terms.im(2)};
    for (int t = 0; t < terms.live; ++t) {
        float sa, ca, sb, cb;
        fast_sincos_turns(fx[t] * dx, sa, ca);
        fast_sincos_turns(fy[t] * dy, sb, cb);
        for (int c = 0; c < 3; ++c) {
            const float p = re[c][t] * cb - im[c][t] * sb;
            const float q = re[c][t] * sb + im[c][t] * cb;
            sum[c] += ca * p - sa * q;
        }
    }
    for (int c = 0; c < 3; ++c) out[c] = sum[c];
}

LrpLattice::LrpLattice(double spacing_x, double spacing_y, double origin_x, double origin_y)
    : origin{origin_x, origin_y},
      spacing{spacing_x, spacing_y},
      inverse_spacing{float(1 / spacing_x), float(1 / spacing_y)}
{
}

const PhaseTable& PhaseTable::shared()
{
    static const PhaseTable table = [] {
        PhaseTable t;
        for (int i = 0; i < (1 << bits); ++i) {
            const double phase = 2 * kPi * (i + 0.5) / (1 << bits);
            t.cosine[std::size_t(i)] = float(std::cos(phase));
            t.sine[std::size_t(i)] = float(std::sin(phase));
            std::uint32_t cosine, sine;
            std::memcpy(&cosine, &t.cosine[std::size_t(i)], 4), std::memcpy(&sine, &t.sine[std::size_t(i)], 4);
            t.packed[std::size_t(i)] = cosine | std::uint64_t(sine) << 32;
        }
        return t;
    }();
    return table;
}

LrpStratumNoise::LrpStratumNoise(const LrpStratum& stratum, int spectrum_size, const Options& options)
    : normalisation_(options.normalisation),
      key_(options.seed),
      shared_phase_(options.shared_phase),
      period_{options.period[0], options.period[1]},
      inverse_size_(1.0 / spectrum_size),
      term_count_(int(stratum.substrata.size()))
{
    double spacing[2] = {stratum.spacing, stratum.spacing};
    if (period_[0] > 0 && period_[1] > 0) {
        // A whole number of cells per period (at least 3, so a window never meets itself).
        for (int axis = 0; axis < 2; ++axis) {
            const double cells = std::max(3.0, std::round(period_[axis] / stratum.spacing));
            spacing[axis] = period_[axis] / cells;
        }
    }
    lattice_ = LrpLattice(spacing[0], spacing[1]);
    if (period_[0] > 0 && period_[1] > 0)
        for (int axis = 0; axis < 2; ++axis) lattice_.wrap[axis] = std::int64_t(std::llround(period_[axis] / spacing[axis]));
    spread_ = lrp_window_spread_2d(spread_energy) / std::max(spacing[0], spacing[1]);
    min_frequency_ = std::numeric_limits<double>::max();
    for (const std::vector<int>& substratum : stratum.substrata) {
        first_.push_back(std::uint32_t(bins_.size() / 2));
        for (std::size_t b = 0; b + 1 < substratum.size(); b += 2) {
            bins_.push_back(substratum[b]);
            bins_.push_back(substratum[b + 1]);
            // Jitter moves a draw by up to half a bin along each axis.
            const double fx = std::max(0.0, std::abs(substratum[b]) - 0.5), fy = std::max(0.0, std::abs(substratum[b + 1]) - 0.5);
            min_frequency_ = std::min(min_frequency_, std::hypot(fx, fy) * inverse_size_);
        }
    }
    first_.push_back(std::uint32_t(bins_.size() / 2));
    for (std::size_t b = 0; b + 1 < bins_.size(); b += 2)
        bin_pairs_.push_back(std::uint32_t(bins_[b]) | std::uint64_t(std::uint32_t(bins_[b + 1])) << 32);
    for (int c = 0; c < 3; ++c) {
        variance_[c] = stratum.sigma[c] * stratum.sigma[c];
        // Normalised windows: the variance is J A²/2 at every point.
        amplitude_[c] = term_count_ > 0 ? float(stratum.sigma[c] * std::sqrt(2.0 / term_count_)) : 0.0f;
    }
    if (normalisation_ == LrpNormalisation::none) {
        // The paper's eq. 3 with E_S = σ_S² (Parseval-normalised PSD): A_S = σ_S (Δ_S² J_S π ∫r w²)^-½.
        const double constant = std::sqrt(spacing[0] * spacing[1] * term_count_ * kPi * lrp_window_radial_energy());
        for (int c = 0; c < 3; ++c) amplitude_[c] = float(stratum.sigma[c] / constant);
    }
}

void LrpStratumNoise::draw(std::int64_t i, std::int64_t j, const LrpFilter& filter, LrpTerms& terms) const
{
    const PhaseTable& phases = PhaseTable::shared();
    SplitMix64 rng(mix_seed(key_, std::uint64_t(lattice_.wrapped(0, i)), std::uint64_t(lattice_.wrapped(1, j))));
    constexpr std::uint64_t phase_mask = (1u << PhaseTable::bits) - 1;
    for (int t = 0; t < term_count_; ++t) {
        const std::uint64_t bits = rng.next(), phase_bits = rng.next();
        // A bin of the sub-stratum (top 32 bits, multiply-shift), jittered uniformly in its cell.
        const std::uint32_t first = first_[std::size_t(t)], count = first_[std::size_t(t) + 1] - first;
        const std::uint32_t b = first + std::uint32_t(((bits >> 32) * count) >> 32);
        const double jitter_x = double((bits >> 16) & 0xffff) / 65536.0 - 0.5 + 1.0 / 131072;
        const double jitter_y = double(bits & 0xffff) / 65536.0 - 0.5 + 1.0 / 131072;
        double fx = (bins_[2 * std::size_t(b)] + jitter_x) * inverse_size_;
        double fy = (bins_[2 * std::size_t(b) + 1] + jitter_y) * inverse_size_;
        if (period_[0] > 0) {
            fx = std::round(fx * period_[0]) / period_[0];
            fy = std::round(fy * period_[1]) / period_[1];
        }
        // (response() is 1 without a filter: not called then, once per term of every window.)
        const float response = filter.identity ? 1.0f : filter.response(fx, fy, spread_);
        if (!(response > 0)) continue;
        float re[3], im[3];
        for (int c = 0; c < 3; ++c) {
            const std::size_t phase = std::size_t((phase_bits >> (shared_phase_ ? 0 : PhaseTable::bits * c)) & phase_mask);
            const float amplitude = amplitude_[c] * response;
            re[c] = amplitude * phases.cosine[phase];
            im[c] = amplitude * phases.sine[phase];
        }
        terms.push(float(fx), float(fy), re, im);
    }
    terms.pad();
}

int LrpStratumNoise::draw_row(std::int64_t i_begin, std::size_t count, std::int64_t j, const LrpFilter& filter,
                              float* const planes[8], std::size_t stride) const
{
    // One thread's buffers, grown once.
    thread_local std::vector<std::uint64_t> seed;
    thread_local std::vector<double> fx, fy;
    thread_local std::vector<float> response;
    const std::size_t padded = (count + 15) / 16 * 16, cells = std::size_t(term_count_) * stride;
    seed.resize(std::max(seed.size(), padded));
    const std::uint64_t row = std::uint64_t(lattice_.wrapped(1, j));
    for (std::size_t w = 0; w < count; ++w)
        seed[w] = mix_seed(key_, std::uint64_t(lattice_.wrapped(0, i_begin + std::int64_t(w))), row);
    const PhaseTable& phases = PhaseTable::shared();
    lrp_raster::TermRow terms;
    terms.seed = seed.data(), terms.count = count, terms.terms = term_count_;
    terms.first = first_.data(), terms.bins = bin_pairs_.data(), terms.inverse_size = inverse_size_;
    if (period_[0] > 0) terms.period[0] = period_[0], terms.period[1] = period_[1];
    for (int c = 0; c < 3; ++c) terms.amplitude[c] = amplitude_[std::size_t(c)];
    terms.shared_phase = shared_phase_, terms.phase_bits = PhaseTable::bits;
    terms.phases = phases.packed.data();
    terms.stride = stride, terms.fx = planes[0], terms.fy = planes[1];
    for (int c = 0; c < 3; ++c) terms.re[c] = planes[2 + c], terms.im[c] = planes[5 + c];
    if (!filter.identity) {
        // The response in double from the unrounded frequencies, as draw() takes it.
        fx.resize(std::max(fx.size(), cells)), fy.resize(std::max(fy.size(), cells));
        response.resize(std::max(response.size(), cells));
        terms.fx_exact = fx.data(), terms.fy_exact = fy.data(), terms.response = response.data();
    }
    lrp_raster::draw_frequencies(terms);
    bool dropped = false;
    if (!filter.identity)
        for (std::size_t at = 0; at < cells; at += stride)
            for (std::size_t w = 0; w < count; ++w) {
                response[at + w] = filter.response(fx[at + w], fy[at + w], spread_);
                dropped = dropped || !(response[at + w] > 0);
            }
    lrp_raster::draw_coefficients(terms);
    for (int p = 0; p < 8; ++p)
        for (std::size_t at = 0; at < cells; at += stride) std::fill(planes[p] + at + count, planes[p] + at + stride, 0.0f);
    if (!dropped) return term_count_;
    // draw() skips the terms the filter drops: each point's kept terms move down, zeros after.
    int most = 0;
    for (std::size_t w = 0; w < count; ++w) {
        std::size_t kept = 0;
        for (std::size_t at = 0; at < cells; at += stride)
            if (response[at + w] > 0) {
                for (int p = 0; p < 8; ++p) planes[p][kept + w] = planes[p][at + w];
                kept += stride;
            }
        for (std::size_t at = kept; at < cells; at += stride)
            for (int p = 0; p < 8; ++p) planes[p][at + w] = 0.0f;
        most = std::max(most, int(kept / stride));
    }
    return most;
}

void LrpStratumNoise::eval(double x, double y, const LrpFilter& filter, float out[3]) const
{
    LrpTerms scratch;
    sum_windows<LrpTermSum::separable>(lattice_, normalisation_, x, y,
                [&](std::int64_t i, std::int64_t j) {
                    scratch.count = 0;
                    draw(i, j, filter, scratch);
                    return scratch.view();
                },
                out);
}

bool LrpStratumNoise::survives(const LrpFilter& filter) const
{
    if (amplitude_[0] == 0 && amplitude_[1] == 0 && amplitude_[2] == 0) return false;
    if (filter.identity) return true;
    // Every term's response is at most that of the slowest frequency along the footprint's minor axis.
    const double minor_sd = std::sqrt(std::max(0.0, filter.covariance.smallest_eigenvalue()));
    const double q = min_frequency_ * minor_sd + spread_ * filter.major_sd;
    return std::exp(-2 * kPi * kPi * q * q) > response_floor;
}

double LrpStratumNoise::kept_variance_fraction(const LrpFilter& filter) const
{
    if (filter.identity) return 1;
    double sum = 0;
    for (int t = 0; t < term_count_; ++t) {
        const std::uint32_t first = first_[std::size_t(t)], last = first_[std::size_t(t) + 1];
        double substratum = 0;
        for (std::uint32_t b = first; b < last; ++b) {
            const double r = filter.response(bins_[2 * std::size_t(b)] * inverse_size_, bins_[2 * std::size_t(b) + 1] * inverse_size_, spread_);
            substratum += r * r;
        }
        sum += substratum / double(last - first);
    }
    return term_count_ > 0 ? sum / term_count_ : 1;
}

}  // namespace stochtex
