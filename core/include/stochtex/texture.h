// stochtex — a procedural texture ready to evaluate.
//
// Built once from a TextureDescription (which is validated), then evaluated from any number of
// threads: every method is const and a pure function of (description, point, footprint), so
// the same seed always gives bit-identical values whatever the thread count.
#pragma once

#include <stochtex/footprint.h>
#include <stochtex/texture_description.h>

#include <array>
#include <cstddef>
#include <memory>
#include <string>

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

/// A raster of surface points on the plane w = const, normal +w (a solid slice: render --solid):
/// pixel (x, y) is the point (plane.u(x), plane.v(y), w) with the plane's footprint.
struct SolidRegion {
    RasterRegion plane;
    double w = 0;
    /// Pixel (i, j) as a surface point: normal +w, the plane's footprint as its derivatives.
    SurfacePoint point(int i, int j) const
    {
        SurfacePoint point;
        point.p = {plane.u(i), plane.v(j), w};
        point.dpdx = {plane.footprint.dudx, plane.footprint.dvdx, 0};
        point.dpdy = {plane.footprint.dudy, plane.footprint.dvdy, 0};
        return point;
    }
};

/// 2D points, each with its own footprint (count of each).
struct PointBatch {
    const Vec2* uv = nullptr;
    const Footprint2D* footprints = nullptr;
    std::size_t count = 0;
};

/// Surface points (solid evaluation), each with its own footprint.
struct SurfaceBatch {
    const SurfacePoint* points = nullptr;
    std::size_t count = 0;
};

/// Where a batch's values go: channel c of item i is channel[c][i · stride]. Planar output
/// (three arrays, stride 1) is what vectorised paths write; interleaved RGB is one array, stride 3.
struct RgbOutput {
    std::array<float*, 3> channel{};
    std::size_t stride = 1;

    static RgbOutput interleaved(float* rgb) { return {{rgb, rgb + 1, rgb + 2}, 3}; }
    static RgbOutput planar(float* r, float* g, float* b) { return {{r, g, b}, 1}; }
    void set(std::size_t item, const Rgb& value) const
    {
        for (int c = 0; c < 3; ++c) channel[c][item * stride] = value[c];
    }
};

/// A texture model's evaluation. The point methods (eval, eval_solid) are the one-sample case
/// of the batch methods, which every consumer with more than one sample calls (render, MIP
/// levels, plugin tiles, bakes): models override the batch methods with paths that share work
/// between samples (rows share lattice cells, kernel sets), values bit-identical to the point
/// methods'. The defaults loop over the point methods.
class Texture {
public:
    virtual ~Texture() = default;

    /// Filtered 2D value at (u, v) in texture units; the footprint is the pixel's Jacobian.
    virtual Rgb eval(const Vec2& uv, const Footprint2D& footprint) const = 0;
    /// Filtered solid (3D) value at a surface point.
    virtual Rgb eval_solid(const SurfacePoint& point) const = 0;
    /// The texture's expected value: what infinite minification converges to.
    virtual Rgb mean() const = 0;

    /// eval() at every pixel of the region (item j·width + i is pixel (i, j)).
    virtual void eval_region(const RasterRegion& region, const RgbOutput& out) const;
    /// eval() at each point of the batch. Not an override point: no consumer has 2D points with
    /// footprints of their own in bulk (the plugin's tiles and every raster are regions).
    void eval_points(const PointBatch& points, const RgbOutput& out) const;
    /// eval_solid() at every pixel of the solid region (item j·width + i is pixel (i, j)).
    virtual void eval_solid_region(const SolidRegion& region, const RgbOutput& out) const;
    /// eval_solid() at each point of the batch.
    virtual void eval_solid_points(const SurfaceBatch& points, const RgbOutput& out) const;

    /// eval_region() into interleaved RGB (width·height·3 floats, rows of width).
    void eval_region(const RasterRegion& region, float* rgb) const { eval_region(region, RgbOutput::interleaved(rgb)); }

    const TextureDescription& description() const { return description_; }

protected:
    explicit Texture(TextureDescription description) : description_(std::move(description)) {}

private:
    TextureDescription description_;
};

/// How far from the origin a texture may be evaluated, in exemplar pixels (a position in texture
/// units × pixels_per_unit): 2^45. Every model turns positions into lattice indices through a
/// double and an int64; within 2^45 pixels a double still resolves 2^-8 of an exemplar pixel
/// (53 − 45 bits), so spline weights and filters keep their precision, and no index comes near
/// int64 overflow. Beyond it values would be noise, NaN or undefined behaviour, so the entry
/// points that take positions from outside (render(), render_region(), periodic textures,
/// MipImage, bakes, the CLI's options) reject them; eval() and the batch methods expect
/// positions already inside it. At 512 pixels per unit the bound is ±2^36 ≈ 6.9e10 units.
constexpr double max_position_pixels = 35184372088832.0;  // 2^45

/// Whether `position` (texture units) is finite and within ±max_position_pixels exemplar pixels.
bool position_in_range(double position, double pixels_per_unit);
/// Throws Error("<name>: …") unless `position` (texture units) is finite and within
/// ±max_position_pixels exemplar pixels at `pixels_per_unit`; the message gives the bound in
/// texture units.
void check_position(double position, double pixels_per_unit, const std::string& name);

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
