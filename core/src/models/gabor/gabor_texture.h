// Random-phase Gabor noise octaves by example (paper 001's texture model, Fig. 6/7): the texture.
//
//   m_c(x) = Σ_k w_ck · n_k(x)      per decorrelated channel c, then ColourMapping,
// n_k the unit-variance noise of octave k (gabor_noise.h) with frequency F_k and bandwidth
// a_k = bandwidth · F_k, in exemplar pixels. The three channels of an octave share impulses and
// have independent phases (uncorrelated; identical in the rgb-shared colour mode).
//
// Filtering is the noise's own analytic filter (no band clamping): the 2D footprint, or the
// solid footprint projected on the tangent plane, becomes the pixel Gaussian's covariance, less
// that of one exemplar pixel: the photo's pixels already blurred what the octaves were fitted to,
// so a render at the photo's scale is not blurred twice (it shows the photo's spectrum, as the
// wavelet model's does), and coarser footprints add exactly the blur that is missing. Only
// when a filtered kernel's support would grow past 8× its area (the octave then keeps at most
// 1/8 of its variance, far less for isotropic footprints) is the octave faded out, to bound the
// cost. With histogram maps, the variance that
// filtering and fading removed — known analytically (gabor_statistics.h) — goes to
// ColourMapping, so minification converges to the texture's true mean.
//
// Periodic form: the 2D impulse lattice wraps (whole cells per period), which makes the kernel
// sum itself periodic — no frequency has to be snapped. Octaves whose kernels are wider than
// half the period cannot wrap and count as filtered away.
#pragma once

#include "colour/colour_mapping.h"
#include "models/gabor/gabor_noise.h"

#include <stochtex/texture.h>

#include <vector>

namespace stochtex {

/// σ_M of one channel: the octaves have unit variance, so sqrt(Σ_k w_k²).
double gabor_channel_sigma(const std::vector<double>& weights);

/// The noise parameters of octave k of a description (units: exemplar pixels).
GaborNoiseParameters gabor_octave(const TextureDescription& description, std::size_t k);

class GaborTexture final : public Texture {
public:
    explicit GaborTexture(const TextureDescription& description);
    /// The periodic form: eval() repeats every period[0] in u and period[1] in v.
    GaborTexture(const TextureDescription& description, const Vec2& period);

    Rgb eval(const Vec2& uv, const Footprint2D& footprint) const override;
    Rgb eval_solid(const SurfacePoint& point) const override;
    Rgb mean() const override { return colour_.mean(); }

    /// eval() / eval_solid() at every pixel: the octaves' filters and fades once per region, the
    /// noises on grids of pixels (GaborNoise::eval_2d_grid, eval_sliced_grid), the colour mapping
    /// batched. Bit-identical to the point methods (the same code with one point).
    void eval_region(const RasterRegion& region, const RgbOutput& out) const override;
    void eval_solid_region(const SolidRegion& region, const RgbOutput& out) const override;
    /// eval_solid() at scattered surface points, each with its own frame and filters: the
    /// octaves' noises point by point as eval_solid() sums them, the colour mapping over chunks
    /// of points with each one's dropped σ. Bit-identical to eval_solid().
    void eval_solid_points(const SurfaceBatch& points, const RgbOutput& out) const override;

private:
    GaborTexture(const TextureDescription& description, const Vec2* period);

    /// What a footprint decides, shared by every pixel that has it: the filter and fade of each
    /// octave that is not faded out, and the σ (units of σ_M) of what filtering removed.
    struct Plan {
        struct Kept {
            std::size_t octave;
            GaborFilter filter;
            float fade;
        };
        std::vector<Kept> octaves;
        std::array<double, 3> dropped_sigma{};
    };
    Plan plan(const Symmetric2& footprint, const TangentFrame& frame) const;
    /// A surface point's slicing frame and the plan of its footprint projected on that plane.
    Plan solid_plan(const SurfacePoint& point, TangentFrame& frame) const;
    /// kept[c][p] += fade · w_c · value[c][p], p < count: one planned octave's noise into the sums.
    void add_octave(const Plan::Kept& planned, const float* const value[3], double* const kept[3], std::size_t count) const;
    /// Pixel centres (x[i], y[j][, z]) in exemplar pixels, i < nx, j < ny: item j·nx + i.
    struct Grid {
        const double* x;
        std::size_t nx;
        const double* y;
        std::size_t ny;
        double z;
    };
    /// The grid's colours, band of rows by band of rows: grid_noise(noise, filter, x, nx, y, ny,
    /// values) evaluates one octave's noise on a band into values[c][·].
    template <class GridNoise>
    void synthesize(const Plan& plan, const Grid& grid, const RgbOutput& out, const GridNoise& grid_noise) const;
    /// The 2D texture on a grid, all with one footprint.
    void eval_2d(const Footprint2D& footprint, const Grid& grid, const RgbOutput& out) const;
    /// The solid texture on a grid of points of one plane, all with the normal and footprint of
    /// `shared` (its position is not read).
    void eval_sliced(const SurfacePoint& shared, const Grid& grid, const RgbOutput& out) const;

    struct Octave {
        GaborNoise noise;
        std::array<double, 3> weight;
    };
    std::vector<Octave> octaves_;
    /// Octaves a periodic texture cannot hold: their weights count as filtered away.
    std::vector<std::array<double, 3>> missing_weights_;
    std::array<double, 3> sigma_m_{};
    bool tracks_dropped_variance_ = false;  // only histogram maps need it
    ColourMapping colour_;
};

}  // namespace stochtex
