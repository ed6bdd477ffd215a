// The ptm model as a texture: the coefficient maps, MIP-mapped, lit by the description's light.
//
// The maps are converted once to three functions per texel (R, G, B; an lrgb texel's luminance
// function times its chroma — exact) and box-filtered into a MIP pyramid of coefficients.
// Radiance is linear in the coefficients, so a filtered lookup of coefficients followed by
// evaluation at the light is the filtered radiance for any light — what a renderer that relights
// per shading point needs — up to the clamp of negative radiance, applied after filtering.
// A lookup is trilinear: bilinear in the two levels around log2(footprint in texels), wrapping.
//
// One texture unit is pixels_per_unit texels (the maps' width, as written by stex); the texture
// repeats with the maps' size. The periodic form stretches the maps so that a whole number of
// repeats fills the period (no change when the period is a multiple of the maps' size).
// eval_solid() projects on the (u, v) = (x, y) plane.
//
// Unbounded (PtmParameters::unbounded; docs/models/ptm.md, "Unbounded"): the maps, periodic, are
// tiled and blended over the tiling model's triangle grid (tiling_grid.h) — one grid, one set of
// tile offsets and weights for all 18 function coefficients, so each texel's reflectance function
// is blended as a whole and the shading turns with the light:
//   f(p) = ν + Σ_i w_i (f_l(p + s_i) − ν),   Σ w_i² = 1,
// ν the maps' mean function (the 1 × 1 level), f_l the pyramid level of the footprint. Centred,
// because Σ w_i ∈ [1, √3] would raise the mean (and the radiance) by up to 73 %; Σ w² = 1 keeps
// the variance of every coefficient (and so of the radiance under any light) for uncorrelated
// tiles. Lit at L this is exactly ν·B(L) + Σ w_i (relit_i − ν·B(L)) before the clamp: the blend
// of the source relit at L. The weights are taken at the footprint's centre (the tiling model's
// per-texel estimator); minification converges to ν, the exact mean. The periodic form uses the
// grid's periodic lattice.
//
// Batch evaluation: a region has one footprint, so eval_region / eval_solid_region resolve its
// level of detail once, wrap texel indices without a division per texel and share the grid's
// vertex draws along the rows (TileCache); per pixel the sums are eval()'s, in eval()'s order,
// so values are bit-identical to it.
#pragma once

#include "models/ptm/legendre_basis.h"
#include "blending/tiling_grid.h"

#include <stochtex/texture.h>
#include <stochtex/models/ptm_parameters.h>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace stochtex {

/// `stex info` lines for a ptm description: colour model, maps, light, file.
std::string describe_ptm(const TextureDescription& description);

class PtmTexture final : public Texture {
public:
    explicit PtmTexture(const TextureDescription& description);
    PtmTexture(const TextureDescription& description, const Vec2& period);

    Rgb eval(const Vec2& uv, const Footprint2D& footprint) const override;
    Rgb eval_solid(const SurfacePoint& point) const override;
    void eval_region(const RasterRegion& region, const RgbOutput& out) const override;
    void eval_solid_region(const SolidRegion& region, const RgbOutput& out) const override;
    Rgb mean() const override { return mean_; }

    /// The filtered R, G, B reflectance functions at uv (Legendre coefficients): for relighting
    /// with any light direction after one lookup.
    std::array<legendre::Terms, 3> functions(const Vec2& uv, double footprint_units) const;
    int level_count() const { return int(levels_.size()); }

private:
    PtmTexture(const TextureDescription& description, const Vec2* period);
    struct Level {
        int width, height;
        std::vector<float> functions;  // 18 floats per texel: R, G, B × b0 … b5
    };
    static constexpr int floats_per_texel = 18;
    /// A footprint's level of detail, resolved once: the finer level and the weight of the next.
    struct Detail {
        int fine = 0;
        double t = 0;
    };
    Detail detail(double footprint_units) const;
    void add_texel(const Level& level, int x, int y, double weight, double* sum) const;
    void bilinear(const Level& level, double x, double y, double* sum, double weight) const;
    /// The trilinear lookup at level-0 texel position (x, y), added to sum with `weight`.
    void trilinear(double x, double y, const Detail& detail, double* sum, double weight) const;
    /// The filtered functions (R, G, B × b0 … b5) at texture position uv.
    void function_sum(const Vec2& uv, const Detail& detail, TileCache& cache, double* sum) const;
    Rgb lit(const std::array<legendre::Terms, 3>& functions) const;
    Rgb lit(const double* sum) const;
    /// The region's pixels lit, filtered at one footprint (texture units).
    void eval_raster(const RasterRegion& region, double footprint_units, const RgbOutput& out) const;

    std::vector<Level> levels_;
    legendre::Terms basis_{};
    double texels_per_unit_[2] = {1, 1};  // level-0 texels per texture unit, per axis
    Rgb mean_{};
    std::optional<TilingGrid> grid_;  // unbounded only: positions in level-0 texels

};

}  // namespace stochtex
