// Tiling and blending by example (paper 002): the texture of model "tiling".
//
// The .stex holds a small periodic exemplar (texture_description.h, TilingParameters). Its
// channels are blended over a triangle grid (tiling_noise.h); what they mean depends on the
// output:
//   colour     — 3 decorrelated colour channels, as in the wavelet model: each channel's
//                histogram map (histogram-preserving blending: the exemplar was Gaussianised,
//                the map restores the photo's histogram), then rgb = mean + basis · y;
//   colour_map — 2 noises in [0, 1] indexing a 2D colour map S (colour-mapped noise vector
//                field; phasor noise is the pair (sin, cos) and a map profile ∘ atan2);
//   normal_map — 2 slopes: the RGB is the encoded normal of the mean slope (n·½ + ½); the
//                slope covariance (LEAN, normal_map_filter.h) is available from moments().
//
// Filtering: the footprint estimator gives the channels' mean μ̂ and covariance Σ̂ over the
// pixel; colour then integrates the histogram maps over 𝒩(μ̂, Σ̂) (ColourMapping's
// Gauss–Hermite), colour_map looks up the pre-blurred colour-map table Ŝ(μ̂, Σ̂)
// (colour_map_filter.h). So minification converges to the exemplar's exact statistics.
//
// Colour's histogram maps are tabulated over (mean, spread) (tabulated_colour_mapping.h), for
// eval() and the batch methods alike.
//
// Evaluation: every method runs the packed single-precision estimator (tiling_raster.h) —
// eval_region and eval_solid_region a row of positions at a time with the footprint's taps
// planned once, eval() and eval_solid() one position — so values are bit-identical between
// them; moments() is the double estimator (TilingNoise), their reference. Footprints it does
// not serve (the mixture interpolation, more than 64 taps) take the double path everywhere.
//
// Solid: no solid exemplar exists, so eval_solid() blends three axis-aligned planar tilings
// (independent grids) with weights ∝ n_k⁴ normalised so that Σ ω_k² = 1: variance-preserving
// like the tiles themselves, and filtered with each plane's projected footprint.
//
// Periodic form: the triangle grid is stretched to a periodic lattice of the requested period
// (tiling_grid.h); tiles are addressed relative to their vertex, so nothing else changes.
#pragma once

#include "models/tiling/colour_map_filter.h"
#include "colour/tabulated_colour_mapping.h"
#include "models/tiling/tiling_noise.h"
#include "models/tiling/tiling_raster.h"

#include <stochtex/texture.h>
#include <stochtex/models/tiling_parameters.h>

#include <array>

#include <memory>
#include <optional>
#include <string>

namespace stochtex {

struct TilingFilterOptions {
    FootprintSampling sampling;
    ColourMapMethod colour_map = ColourMapMethod::covariance;
};
/// The filtering a tiling description asks for: the defaults with its filter_taps.
TilingFilterOptions filter_options(const TilingParameters& parameters);

class TilingTexture final : public Texture {
public:
    /// Filtered as the description says (its filter_taps).
    explicit TilingTexture(const TextureDescription& description);
    /// Filtered as `options` say, whatever the description's filter_taps (the ablations).
    TilingTexture(const TextureDescription& description, const TilingFilterOptions& options);
    /// The periodic form: eval() repeats every period[0] in u and period[1] in v.
    TilingTexture(const TextureDescription& description, const Vec2& period);
    TilingTexture(const TilingTexture&) = delete;  // rasters_ refer to planes_ and packed_
    TilingTexture& operator=(const TilingTexture&) = delete;

    Rgb eval(const Vec2& uv, const Footprint2D& footprint) const override;
    Rgb eval_solid(const SurfacePoint& point) const override;
    void eval_region(const RasterRegion& region, const RgbOutput& out) const override;
    void eval_solid_region(const SolidRegion& region, const RgbOutput& out) const override;
    /// colour() of the exemplar's exact moments; a colour map through the reference lookup
    /// (ColourMapFilter::filtered), so the mean written in a .stex does not depend on the packed
    /// lookup's rounding.
    Rgb mean() const override;

    /// The blended channels' filtered moments at uv over the footprint (2D), all of them, in
    /// double precision (TilingNoise::footprint_estimate: the reference of the packed path).
    Moments moments(const Vec2& uv, const Footprint2D& footprint) const;
    /// The moments eval() and the batch methods use (TilingRaster, single precision, only the
    /// second moments colour() reads; the double path where TilingRaster does not serve the plan).
    Moments raster_moments(const Vec2& uv, const Footprint2D& footprint) const;
    /// The output colour of channels with these moments.
    Rgb colour(const Moments& moments) const;
    const TilingNoise& noise() const { return planes_[0]; }
    const TilingFilterOptions& options() const { return options_; }
    /// The colour map's filter (colour_map output only, else null).
    const ColourMapFilter* colour_map_filter() const { return colour_map_ ? &*colour_map_ : nullptr; }

private:
    TilingTexture(const TextureDescription& description, const Vec2* period, const TilingFilterOptions& options);
    /// The solid blend's weights and per-plane taps for one normal and footprint.
    struct SolidPlan {
        std::array<double, 3> weight{};  ///< ω_k / ‖ω‖ (0: plane unused)
        std::array<TilingRaster::Plan, 3> taps;
    };
    /// One thread's caches of one plane's grid (the packed path's and the double path's).
    struct PlaneCache {
        TilingRaster::Workspace workspace;
        TileCache tiles;
        std::vector<double> x;
        std::vector<float> packed;
        std::vector<double> channels;  ///< colour_row's planar means and spreads
        std::vector<PairCovariance> covariance;  ///< colour_row's colour-map covariances
        std::vector<Rgb> colours;
        PlaneCache() = default;
        /// A cache for one evaluation (its taps share a few vertices).
        explicit PlaneCache(bool single) : workspace(single ? 2 : 6, single ? 2 : 4) {}
    };
    /// A point evaluation's cache of plane k (this thread's, emptied).
    static PlaneCache& single_cache(int k);
    SolidPlan solid_plan(const SurfacePoint& point) const;
    /// colour(raster.unpack(record)) of `count` packed records (TilingRaster's layout) into out
    /// items first + i, bit-identical to it: the colour output's histogram maps resolved once per
    /// row (TabulatedColourMapping's row form), the unpacking to double Moments skipped.
    void colour_row(const float* packed, std::size_t count, const RgbOutput& out, std::size_t first, PlaneCache& cache) const;
    /// The solid blend of the planes' moments (planes of weight 0 are not read).
    Moments solid_moments(const SolidPlan& plan, const std::array<Moments, 3>& planes) const;
    /// Plane k's moments at (x, y) exemplar pixels with a planned footprint.
    Moments plane_moments(int k, double x, double y, const TilingRaster::Plan& plan, PlaneCache& cache) const;
    /// plane_moments() at (x[i], y), i < count (x monotone), into out[i].
    void plane_row(int k, const double* x, std::size_t count, double y, const TilingRaster::Plan& plan, PlaneCache& cache,
                   Moments* out) const;

    TilingFilterOptions options_;
    TilingOutput output_;
    /// planes_[0] is the 2D texture; planes_[1], [2] the extra planes of the solid blend.
    std::vector<TilingNoise> planes_;
    std::shared_ptr<const PackedMomentPyramid> packed_;
    std::vector<TilingRaster> rasters_;  ///< one per plane
    std::shared_ptr<const TabulatedColourMapping> colour_mapping_;
    std::optional<ColourMapFilter> colour_map_;
};

/// The moment pyramid of a description's (dequantised) exemplar.
std::shared_ptr<const MomentPyramid> tiling_pyramid(const TilingParameters& parameters);

/// The tiling part of `stex info`: output, exemplar, grid geometry, exact exemplar statistics.
std::string describe_tiling(const TextureDescription& description);

}  // namespace stochtex
