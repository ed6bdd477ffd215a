// stochtex — a procedural texture ready to evaluate.
//
// Built once from a TextureDescription (which is validated), then evaluated from any number of
// threads: every method is const and a pure function of (description, point, footprint), so
// the same seed always gives bit-identical values whatever the thread count.
#pragma once

#include <stochtex/footprint.h>
#include <stochtex/texture_description.h>

#include <array>
#include <memory>

namespace stochtex {

using Rgb = std::array<float, 3>;

/// Pixels [x0, x0 + width) × [y0, y0 + height) of a raster whose pixel (x, y) has its centre at
/// (origin_u + (x + ½)·du, origin_v + (y + ½)·dv), all with one footprint — a row band of a
/// render, a tile, a MIP level. (Positions depend on the pixel index only, never on x0/y0, so
/// any split of a raster into regions gives the same values.)
struct RasterRegion {
    double origin_u = 0, origin_v = 0, du = 0, dv = 0;
    int x0 = 0, y0 = 0, width = 0, height = 0;
    Footprint2D footprint;
    double u(int i) const { return origin_u + (x0 + i + 0.5) * du; }
    double v(int j) const { return origin_v + (y0 + j + 0.5) * dv; }
};

class Texture {
public:
    virtual ~Texture() = default;

    /// Filtered 2D value at (u, v) in texture units; the footprint is the pixel's Jacobian.
    virtual Rgb eval(const Vec2& uv, const Footprint2D& footprint) const = 0;
    /// eval() at every pixel of the region, into rgb (width·height·3 floats, rows of width).
    /// Models override it with faster paths that share work along rows and columns; the values
    /// are bit-identical to eval()'s.
    virtual void eval_region(const RasterRegion& region, float* rgb) const;
    /// Filtered solid (3D) value at a surface point.
    virtual Rgb eval_solid(const SurfacePoint& point) const = 0;
    /// The texture's expected value: what infinite minification converges to.
    virtual Rgb mean() const = 0;

    const TextureDescription& description() const { return description_; }

protected:
    explicit Texture(TextureDescription description) : description_(std::move(description)) {}

private:
    TextureDescription description_;
};

/// Creates the model named by description.model. Throws Error if the description is invalid.
std::unique_ptr<Texture> make_texture(const TextureDescription& description);

/// The same texture made periodic in 2D: eval() repeats with period (period[0], period[1])
/// texture units, so an image covering exactly one period tiles without a seam (the OIIO
/// plugin's virtual image, baked maps). Each band's frequency is snapped so that a whole number
/// of its lattice cells fits the period (≤ 0.1 % change for bands ≥ 512 cells per period);
/// bands too coarse to fit the period at all are treated as filtered away (the histogram map
/// accounts for their variance, as for minification). eval_solid() is not periodic.
/// Throws Error if the model has no periodic form or the period is not positive and finite.
std::unique_ptr<Texture> make_periodic_texture(const TextureDescription& description, const Vec2& period);

}  // namespace stochtex
