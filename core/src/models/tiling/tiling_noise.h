// Tiling-and-blending noise and its moment estimators (paper 002 §§1–5).
//
//   N(p) = ν + Σ_i w_i(p) (E(p + s_i) − ν)                                     (eq. 1, centred)
// over the three vertices i of the triangle holding p (tiling_grid.h), s_i = round(o_i − c_i) the
// tile's random whole-pixel shift (o_i the vertex's offset, c_i its centre); E is the exemplar (any
// 1–3 channels: they share the tiles, so their moments stay coherent), ν its exact mean. All
// positions are in exemplar pixels.
//
// The filtered moments of N over a footprint are estimated from the exemplar's moment pyramid
// (moment_pyramid.h):
//   per texel at level l (eqs. 51, 54, 58):  N̂ = ν + Σ w_i (E_l,i − ν),  Ĉ = Σ w_i² C_l,i
//     — w_i squared: the three tiles are uncorrelated, so only each tile's own spread counts;
//   over a footprint (eqs. 52, 55–60): a grid of taps covering the footprint's parallelogram,
//     each a per-texel estimate at the level of the tap spacing with its own blend weights,
//     combined by the law of total variance (moments of the union, never a mean of variances).
// With Σ w_i² = 1, the coarsest level gives exactly (ν, Cov E) wherever it is evaluated.
#pragma once

#include "models/tiling/moment_pyramid.h"
#include "blending/tiling_grid.h"

#include <stochtex/footprint.h>

#include <array>
#include <memory>
#include <vector>

namespace stochtex {

/// How the footprint estimator samples the pyramid.
struct FootprintSampling {
    /// Taps per footprint axis (isotropic footprints); 1 is the paper's single per-texel estimate.
    int taps = 2;
    /// Upper bound of taps along an anisotropic footprint's long axis.
    int max_taps = 8;
    TexelInterpolation interpolation = TexelInterpolation::linear;
};

/// The footprint estimator's taps for one footprint, resolved once (tap counts, their offsets
/// and their level): a raster shares it across all its pixels.
struct TapPlan {
    static constexpr int max_taps_per_axis = 64;  ///< more are capped (sampling.max_taps ≤ 64)
    static constexpr int max_planned_taps = 64;   ///< beyond, the mixture is MomentMixture's
    int na = 1, nb = 1;  ///< taps along the footprint's axes a and b
    double level = 0;    ///< their (continuous) pyramid level
    MomentPyramid::LevelChoice choice;
    TexelInterpolation interpolation = TexelInterpolation::linear;
    /// Tap (i, j) is at (x + along_a[i][0] + along_b[j][0], y + along_a[i][1] + along_b[j][1]).
    std::array<std::array<double, 2>, max_taps_per_axis> along_a{}, along_b{};
    /// MomentMixture's coefficients for equal weights, tap k (row-major): weight / total_k and
    /// the scatter factor total_(k−1) · weight / total_k; `total` the weights' final sum.
    double weight = 1, total = 1;
    std::array<double, max_planned_taps> ratio{}, scatter{};
};

class TilingNoise {
public:
    /// The pyramid of a periodic exemplar (shared: several grids may tile one exemplar).
    TilingNoise(std::shared_ptr<const MomentPyramid> pyramid, TilingGrid grid);

    int channels() const { return pyramid_->channels(); }
    int width() const { return pyramid_->width(); }
    int height() const { return pyramid_->height(); }
    const MomentPyramid& pyramid() const { return *pyramid_; }
    const TilingGrid& grid() const { return grid_; }
    /// ν and Cov E: the exemplar's exact moments (the pyramid's 1 × 1 level).
    const Moments& global() const { return global_; }

    /// N at a point (the exemplar interpolated bilinearly): level 0, variance 0.
    Moments point(double x, double y) const { return texel_estimate(x, y, 0, TexelInterpolation::linear); }
    /// Per-texel estimator at (continuous) pyramid level `level`.
    Moments texel_estimate(double x, double y, double level, TexelInterpolation interpolation) const;
    /// Arbitrary-footprint estimator.
    Moments footprint_estimate(double x, double y, const Footprint2D& footprint_px, const FootprintSampling& sampling) const;

    /// The taps of footprint_estimate() for this footprint.
    TapPlan plan(const Footprint2D& footprint_px, const FootprintSampling& sampling) const;
    /// footprint_estimate() with the taps planned and the grid's vertices cached: the same
    /// values, bit for bit (footprint_estimate() is this with a fresh plan and cache).
    Moments footprint_estimate(double x, double y, const TapPlan& plan, TileCache& cache) const;

private:
    Moments estimate(double x, double y, double level, TexelInterpolation interpolation, const TileBlend& blend) const;
    /// estimate() at a planned level (any interpolation).
    Moments tap_estimate(double x, double y, const TapPlan& plan, TileCache& cache) const;
    /// The linear tap estimate of a `Channels`-channel pyramid, packed (mean, upper-triangle pairs).
    template <int Channels>
    void tap_moments(double x, double y, const TapPlan& plan, TileCache& cache, double* mean, double* pairs) const;
    /// footprint_estimate() for linear interpolation and ≤ max_planned_taps taps.
    template <int Channels>
    Moments planned_estimate(double x, double y, const TapPlan& plan, TileCache& cache) const;

    std::shared_ptr<const MomentPyramid> pyramid_;
    TilingGrid grid_;
    Moments global_;
};

}  // namespace stochtex
