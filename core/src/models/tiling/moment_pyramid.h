// Mean, variance and covariance MIP pyramids of an exemplar (paper 002 eqs. 50, 53, 57).
//
// Level l's texel ℙ covers a block of level-0 pixels (2^l × 2^l, or the whole side once a side
// is down to one texel) and holds, exactly and in double precision,
//   E_l(ℙ)      the channels' means over the block                       (eq. 50)
//   C_l,ab(ℙ)   the centred second moments (1/#ℙ) Σ (E_a − E_l,a)(E_b − E_l,b) over the block:
//               the variance V_l for a = b (eq. 53), the covariance for a ≠ b (eq. 57).
// Level l+1 is built from level l by the law of total variance — the moments of a union are
// the mean of the parts' moments plus the scatter of the parts' means (never the mean of the
// variances alone) — in centred form, which is exact and free of cancellation. So V_0 ≡ 0 and
// the 1 × 1 level holds the exemplar's exact mean and (co)variances.
//
// Lookups interpolate bilinearly between texel centres, with wrap (the exemplar is periodic),
// and linearly between levels; they return the (mean, moments) of the interpolated texel.
#pragma once

#include <array>
#include <vector>

namespace stochtex {

constexpr int max_moment_channels = 3;

/// Means and centred second moments of up to 3 channels; moment(a, b) is symmetric.
struct Moments {
    int channels = 0;
    std::array<double, max_moment_channels> mean{};
    std::array<double, max_moment_channels * max_moment_channels> second{};  // [a·3 + b], centred
    double moment(int a, int b) const { return second[std::size_t(a * max_moment_channels + b)]; }
    double& moment(int a, int b) { return second[std::size_t(a * max_moment_channels + b)]; }
};

/// How a lookup between texel centres combines the four neighbours' moments.
enum class TexelInterpolation {
    linear,   ///< moments interpolated like the means: the paper's (trilinear) fetch of V
    mixture,  ///< the moments of the weighted union of the four texels (law of total variance)
};

class MomentPyramid {
public:
    /// planes: 1 to 3 channels of width × height values; sides powers of two.
    MomentPyramid(const std::vector<std::vector<double>>& planes, int width, int height);

    int channels() const { return channels_; }
    int level_count() const { return int(levels_.size()); }
    int width() const { return levels_[0].width; }
    int height() const { return levels_[0].height; }
    /// The exact texel (x, y) of level `level` (no interpolation; indices wrap).
    Moments texel(int level, int x, int y) const;
    /// The texel moments at continuous position (x, y) in level-0 pixels, at continuous level
    /// `level` (clamped to [0, level_count() − 1]).
    Moments sample(double level, double x, double y, TexelInterpolation interpolation) const;
    /// A continuous level resolved as sample() resolves it (clamped, the level below and the
    /// fraction towards the next), once for all the lookups of one footprint.
    struct LevelChoice {
        int lower = 0;
        double t = 0;
    };
    LevelChoice choose_level(double level) const;
    /// sample(level, x, y, linear) written packed: mean[channels()], then the upper triangle of
    /// the moments row by row (pairs[(0,0), (0,1), …]) — the same values, bit for bit, without
    /// building Moments (the hot path of the tiling raster).
    void sample_linear(const LevelChoice& level, double x, double y, double* mean, double* pairs) const;
    /// sample_linear() for a pyramid of `Channels` channels (1, 2 or 3: instantiated for those).
    template <int Channels>
    void sample_linear(const LevelChoice& level, double x, double y, double* mean, double* pairs) const;
    int pairs() const { return pairs_; }
    /// The whole exemplar's exact moments: the 1 × 1 level.
    Moments global() const { return texel(level_count() - 1, 0, 0); }

private:
    struct Level {
        int width, height;
        // Per texel one record: the channels' means, then the upper triangle of the symmetric
        // moments (a lookup reads one record, not two arrays).
        std::vector<double> data;
        double scale_x = 1, scale_y = 1;  // texels of this level per level-0 pixel (powers of two)
    };
    Moments unpack(const Level& level, std::size_t texel) const;
    void pack(const Moments& moments, Level& level, std::size_t texel) const;
    Moments sample_level(int level, double x, double y, TexelInterpolation interpolation) const;
    template <int Channels>
    void sample_level_linear(int level, double x, double y, double* mean, double* pairs) const;

    int channels_;
    int pairs_;   // channels (channels + 1) / 2
    int record_;  // channels + pairs: doubles per texel
    std::vector<Level> levels_;
};

/// Moments of a weighted union of parts (weights sum to 1): mean of the means; second moments
/// = Σ w (C + (μ − μ̄)(μ − μ̄)ᵀ). The law of total variance (paper 002 eqs. 55–56, 59–60).
class MomentMixture {
public:
    explicit MomentMixture(int channels) { total_.channels = channels; }
    void add(double weight, const Moments& part);
    /// The union's moments (requires the weights added to sum to 1).
    Moments result() const;

private:
    Moments total_;  // Σ w μ and Σ w (C + μμᵀ), centred at the end
    double weight_ = 0;
};

}  // namespace stochtex
