// Local random-phase noise (paper 003, eqs. 1–2): windows on a regular lattice, each holding a
// local sum of cosines.
//
//   n_S(x) = Σ_i w(‖x − x_i‖/Δ_S) Σ_j A_j cos(2π f_ij·(x − x_i) + φ_ij)  /  √(Σ_i w_i(x)²)
//
// Evaluation. The 3×3 lattice points around x's *nearest* lattice point are exactly those whose
// window reaches x (a floor-centred block would miss some). Lattice point i seeds its own
// random stream from its integer coordinates, the stratum and the texture seed, and draws one
// frequency per sub-stratum (one stored bin, jittered within it) and a phase per channel.
// Cosines are taken relative to x_i: with random phases this is the same noise in distribution
// as the paper's global x, and it keeps the argument small enough for float.
//
// Normalisation (decided by measurement, docs/models/lrp.md). Local noises with independent
// phases are uncorrelated, so the variance at x is (J A²/2) Σ_i w_i(x)², which varies ×2.4
// across a lattice cell (the paper's "< 5 %" holds for Σ w_i, not for Σ w_i²). Dividing by
// √(Σ w_i²) makes it J A²/2 everywhere: each channel's per-term amplitude is σ_S √(2/J_S), so
// the stratum holds exactly its share σ_S² of the variance. The paper's eq. 3 is kept as an
// option for the measurement that rejected it.
//
// Colour. The three decorrelated channels share the lattice and the frequencies and have
// independent phases (uncorrelated, like the PCA channels they model; one phase in the
// rgb-shared mode): one sine/cosine per term serves the three channels.
//
// Filtering. A term of frequency f is multiplied by the Gaussian pixel filter's response
// exp(−2π² (√(fᵀΣf) + ρ_Δ √λ_max(Σ))²): Σ the footprint's covariance less one exemplar pixel's
// (the photo's pixels already blurred the spectrum the noise was fitted to), ρ_Δ the window's
// spectral spread (its 75 % radius, 0.41/Δ). Terms whose response falls below 1/256 are not
// evaluated at all, so minification is also cheaper.
//
// Periodic form: the lattice holds a whole number of cells per period (the key wraps) and each
// drawn frequency snaps to the nearest multiple of 1/period.
#pragma once

#include "numerics/exact_rounding.h"
#include "filtering/footprint_filter.h"
#include "models/lrp/lrp_window.h"

#include <stochtex/footprint.h>
#include <stochtex/texture_description.h>
#include <stochtex/models/lrp_parameters.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

namespace stochtex {

/// The pixel filter of one evaluation, in exemplar pixels.
struct LrpFilter {
    Symmetric2 covariance;   ///< what the footprint adds to the photo's own pixel blur, px²
    double major_sd = 0;     ///< √λ_max(covariance)
    bool identity = true;    ///< no blur: every term kept whole

    /// From a footprint in texture units, at `pixels_per_unit` exemplar pixels per unit.
    static LrpFilter from_footprint(const Footprint2D& footprint, double pixels_per_unit);
    /// The response to a term of frequency (fx, fy) cycles per pixel in windows of spectral
    /// spread `spread`; 0 below 1/256 (then rescaled so the response stays continuous).
    float response(double fx, double fy, double spread) const;
};

/// Sum-of-cosines terms of one window, in structure-of-arrays form: fx, fy (cycles per pixel,
/// relative to the window's lattice point), then per channel the coefficients re and im of
/// re·cos θ − im·sin θ. `count` is padded to a multiple of the lane count with zero terms.
struct LrpTermView {
    const float* data = nullptr;
    int count = 0;
    int stride = 0;
    int live = 0;  ///< the terms before the padding (the separable sums skip the zero terms)
    const float* fx() const { return data; }
    const float* fy() const { return data + stride; }
    const float* re(int c) const { return data + (2 + c) * stride; }
    const float* im(int c) const { return data + (5 + c) * stride; }
};

/// Room for the terms of one window (eval()'s scratch).
struct LrpTerms {
    static constexpr int capacity = 256;
    static constexpr int lanes = 4;
    int count = 0;
    int live = 0;  ///< count before pad()
    float data[8 * capacity];

    float* fx() { return data; }
    float* fy() { return data + capacity; }
    float* re(int c) { return data + (2 + c) * capacity; }
    float* im(int c) { return data + (5 + c) * capacity; }
    void push(float fx_, float fy_, const float re_[3], const float im_[3])
    {
        // Inline: draw() pushes a term per cosine of every window (a call each was ~3 % of a render).
        fx()[count] = fx_;
        fy()[count] = fy_;
        for (int c = 0; c < 3; ++c) re(c)[count] = re_[c], im(c)[count] = im_[c];
        live = ++count;
    }
    /// Pads with zero terms to a multiple of `lanes`.
    void pad();
    LrpTermView view() const { return {data, count, capacity, live}; }
};

/// Σ_t re·cos(2π f_t·d) − im·sin(2π f_t·d) per channel, in `lanes` independent partial sums
/// combined in a fixed order: the loop vectorises without reassociating, so every caller gets
/// bit-identical sums.
void sum_terms(const LrpTermView& terms, float dx, float dy, float out[3]);

/// The same sum with each cosine of a sum taken as a product, cos(a + b) = cos a cos b − sin a sin b
/// (lrp_raster.h): what the random-phase strata use, because on a raster a and b are shared by
/// whole columns and rows of pixels. One running sum per channel over the `live` terms (the
/// padding costs nothing); rounding differs from sum_terms by a few ulps of the terms.
void sum_terms_separable(const LrpTermView& terms, float dx, float dy, float out[3]);

/// Which of the two sums a window takes.
enum class LrpTermSum {
    direct,    ///< sum_terms (the structure: its positions are displaced, no raster to share)
    separable, ///< sum_terms_separable (the random-phase strata: lrp_raster.h repeats it)
};

/// A lattice of windows: point (i, j) at origin + (i·spacing_x, j·spacing_y).
struct LrpLattice {
    double origin[2] = {0, 0};
    double spacing[2] = {1, 1};
    float inverse_spacing[2] = {1, 1};
    std::int64_t wrap[2] = {0, 0};  ///< periodic: cells per period (keys repeat), else 0

    LrpLattice() = default;
    LrpLattice(double spacing_x, double spacing_y, double origin_x = 0, double origin_y = 0);
    std::int64_t nearest(int axis, double position) const
    {
        // floor_exact: std::floor is a libm call on the x86-64 baseline, and this runs per sample.
        return std::int64_t(floor_exact((position - origin[axis]) / spacing[axis] + 0.5));
    }
    /// The lattice index modulo the period (the index itself when not periodic).
    std::int64_t wrapped(int axis, std::int64_t i) const
    {
        if (!wrap[axis]) return i;
        const std::int64_t r = i % wrap[axis];
        return r < 0 ? r + wrap[axis] : r;
    }
};

/// How the windows are normalised.
enum class LrpNormalisation {
    variance,  ///< ÷ √Σw²: stationary variance (random phases)
    partition, ///< ÷ Σw: a partition of unity (fixed phases: copies of one function blend exactly)
    none,      ///< the paper's eq. 1 as printed (kept for measurements)
};

/// Σ_i w_i(x) · terms_i(x − x_i), normalised, over the 3×3 lattice points around the nearest one.
/// `terms_at(i, j)` returns the LrpTermView of lattice point (i, j) (unwrapped indices).
template <LrpTermSum term_sum, class TermsAt>
void sum_windows(const LrpLattice& lattice, LrpNormalisation normalisation, double x, double y, const TermsAt& terms_at,
                 float out[3])
{
    const LrpWindowTable& window = LrpWindowTable::shared();
    const std::int64_t cx = lattice.nearest(0, x), cy = lattice.nearest(1, y);
    float sum[3] = {0, 0, 0};
    float weight = 0, weight_squared = 0;
    for (std::int64_t j = cy - 1; j <= cy + 1; ++j) {
        const float dy = float(y - (lattice.origin[1] + double(j) * lattice.spacing[1]));
        const float ry = dy * lattice.inverse_spacing[1];
        for (std::int64_t i = cx - 1; i <= cx + 1; ++i) {
            const float dx = float(x - (lattice.origin[0] + double(i) * lattice.spacing[0]));
            const float rx = dx * lattice.inverse_spacing[0];
            const float w = window(rx * rx + ry * ry);
            if (!(w > 0)) continue;
            const LrpTermView terms = terms_at(i, j);
            weight += w;
            weight_squared += w * w;
            if (terms.count == 0) continue;
            float local[3];
            if constexpr (term_sum == LrpTermSum::separable)
                sum_terms_separable(terms, dx, dy, local);
            else
                sum_terms(terms, dx, dy, local);
            for (int c = 0; c < 3; ++c) sum[c] += w * local[c];
        }
    }
    // The nearest lattice point is within √½ spacing, where w ≥ 0.32: the weights never vanish.
    const float scale = normalisation == LrpNormalisation::variance    ? 1.0f / std::sqrt(weight_squared)
                        : normalisation == LrpNormalisation::partition ? 1.0f / weight
                                                                       : 1.0f;
    for (int c = 0; c < 3; ++c) out[c] = sum[c] * scale;
}

/// Packed terms of a rectangle of lattice points, drawn once for a raster region (eval_region):
/// the same terms eval() draws point by point, so the sums are bit-identical. Each point's terms
/// may be read a vector past its end (lrp_raster_kernels.h's padding).
class LrpTermCache {
public:
    static constexpr std::size_t read_padding = 16;
    /// Lattice points [i0, i0 + nx) × [j0, j0 + ny); draw(i, j, LrpTerms&) fills one point's terms.
    template <class Draw>
    void fill(std::int64_t i0, std::int64_t j0, int nx, int ny, const Draw& draw)
    {
        i0_ = i0, j0_ = j0, nx_ = nx, ny_ = ny;
        const std::size_t points = std::size_t(nx) * std::size_t(ny);
        offset_.resize(points);
        count_.resize(points);
        live_.resize(points);
        // data_ only grows (a thread's cache serves region after region): no zero-fill per window,
        // and each plane copied in whole vectors of LrpTerms::lanes (pad() makes count a multiple;
        // a memmove call per plane of a few terms cost more than the copy).
        std::size_t used = 0;
        LrpTerms scratch;
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                scratch.count = 0;
                draw(i0 + i, j0 + j, scratch);
                const std::size_t k = std::size_t(j) * std::size_t(nx) + std::size_t(i), count = std::size_t(scratch.count);
                if (data_.size() < used + 8 * count + read_padding)
                    data_.resize(std::max(2 * data_.size(), used + 8 * count + read_padding));
                offset_[k] = used;
                count_[k] = scratch.count;
                live_[k] = scratch.live;
                float* const to = data_.data() + used;
                for (std::size_t a = 0; a < 8; ++a) {
                    const float* const from = scratch.data + a * LrpTerms::capacity;
                    std::size_t t = 0;
                    for (; t + LrpTerms::lanes <= count; t += LrpTerms::lanes)
                        std::memcpy(to + a * count + t, from + t, sizeof(float) * LrpTerms::lanes);
                    for (; t < count; ++t) to[a * count + t] = from[t];
                }
                used += 8 * count;
            }
        std::fill_n(data_.data() + used, read_padding, 0.0f);
    }
    std::int64_t i_begin() const { return i0_; }
    std::int64_t i_end() const { return i0_ + nx_; }
    std::int64_t j_begin() const { return j0_; }
    std::int64_t j_end() const { return j0_ + ny_; }
    LrpTermView at(std::int64_t i, std::int64_t j) const
    {
        const std::size_t k = std::size_t(j - j0_) * nx_ + std::size_t(i - i0_);
        return {data_.data() + offset_[k], count_[k], count_[k], live_[k]};
    }

private:
    std::int64_t i0_ = 0, j0_ = 0;
    int nx_ = 0, ny_ = 0;
    std::vector<float> data_;
    std::vector<std::size_t> offset_;
    std::vector<int> count_, live_;
};

/// One random-phase stratum ready to evaluate.
class LrpStratumNoise {
public:
    struct Options {
        std::uint64_t seed = 1;
        bool shared_phase = false;  ///< rgb-shared colour: one phase for the three channels
        /// Periodic: the period in exemplar pixels (both > 0), else zeros.
        std::array<double, 2> period{0, 0};
        LrpNormalisation normalisation = LrpNormalisation::variance;
    };
    LrpStratumNoise(const LrpStratum& stratum, int spectrum_size, const Options& options);

    /// The stratum's three channels at (x, y) exemplar pixels.
    void eval(double x, double y, const LrpFilter& filter, float out[3]) const;
    /// The terms of lattice point (i, j) under `filter`.
    void draw(std::int64_t i, std::int64_t j, const LrpFilter& filter, LrpTerms& terms) const;
    /// draw() of the lattice points (i_begin + w, j), w < count, at once and transposed (the
    /// lattice-row raster's layout): term t of point w at [t · stride + w] of each plane (fx, fy,
    /// re 0–2, im 0–2, LrpTermView's order), a point's terms in draw()'s order and 0 past its own,
    /// 0 in every lane from `count` to `stride`. Returns the most terms a point has. Each plane
    /// holds term_count() · stride floats; stride ≥ count rounded up to a multiple of 16. The
    /// same values as draw(), bit for bit: lrp_raster_draw.h's kernels, lane by lane.
    int draw_row(std::int64_t i_begin, std::size_t count, std::int64_t j, const LrpFilter& filter, float* const planes[8],
                 std::size_t stride) const;

    const LrpLattice& lattice() const { return lattice_; }
    LrpNormalisation normalisation() const { return normalisation_; }
    int term_count() const { return term_count_; }
    /// Each channel's variance (0 where σ is).
    const std::array<double, 3>& variance() const { return variance_; }
    /// Mean response² over the stored bins: the share of the variance `filter` keeps.
    double kept_variance_fraction(const LrpFilter& filter) const;
    /// Whether `filter` keeps anything of this stratum (else it need not be evaluated): false for
    /// a stratum of zero amplitude (a channel-less band of the photo), whatever the filter.
    bool survives(const LrpFilter& filter) const;
    double spread() const { return spread_; }
    /// 1 where channels 1 and 2 have zero amplitude (the structure's turbulence strata: their
    /// sums there are +0), else 3: what the raster has to sum.
    int channels() const { return amplitude_[1] == 0 && amplitude_[2] == 0 ? 1 : 3; }

private:
    LrpLattice lattice_;
    LrpNormalisation normalisation_;
    std::uint64_t key_;
    bool shared_phase_;
    double period_[2];
    double inverse_size_;
    double spread_;  // the window's spectral 75 % radius, cycles per pixel
    int term_count_;
    std::vector<std::int32_t> bins_;   // kx, ky of every stored bin
    std::vector<std::uint64_t> bin_pairs_;  // the same packed, kx in the low 32 bits (draw_row gathers them)
    std::vector<std::uint32_t> first_; // sub-stratum j's bins: [first_[j], first_[j + 1])
    double min_frequency_ = 0;         // the lowest |f| any draw can have
    std::array<float, 3> amplitude_{};
    std::array<double, 3> variance_{};
};

/// A uniform phase as (cos φ, sin φ) from 10 random bits (a table: no trigonometry per draw).
struct PhaseTable {
    static constexpr int bits = 10;
    std::array<float, 1 << bits> cosine, sine;
    std::array<std::uint64_t, 1 << bits> packed;  // the same: cosine's bits low, sine's high (draw_row gathers them)
    static const PhaseTable& shared();
};

}  // namespace stochtex
