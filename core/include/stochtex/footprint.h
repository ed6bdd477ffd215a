// stochtex — where a texture is evaluated, and over what area.
//
// Every model receives the same evaluation context (after pbrt-v4's TextureEvalContext):
//   * 2D: a point (u, v) in texture units and the Jacobian of (u, v) with respect to screen
//     x and y — the pixel footprint as a parallelogram (a covariance follows from it).
//   * 3D (solid): a point, the surface normal and the screen derivatives dP/dx, dP/dy.
// One texture unit is one exemplar width (TextureDescription::pixels_per_unit exemplar pixels).
// A zero footprint means "point sample, no filtering".
#pragma once

#include <array>

namespace stochtex {

using Vec2 = std::array<double, 2>;
using Vec3 = std::array<double, 3>;

struct Footprint2D {
    // Texture-space derivatives of the lookup position along screen x and screen y.
    double dudx = 0, dvdx = 0, dudy = 0, dvdy = 0;

    static Footprint2D point() { return {}; }
    /// An axis-aligned square footprint of `size` texture units (a raster's pixel spacing).
    static Footprint2D square(double size) { return {size, 0, 0, size}; }

    /// The same footprint in other units (e.g. exemplar pixels: scale = pixels per unit).
    Footprint2D scaled(double scale) const { return {dudx * scale, dvdx * scale, dudy * scale, dvdy * scale}; }

    /// Largest singular value of the Jacobian: the footprint's longest axis, in texture units.
    double major_axis() const;
};

struct SurfacePoint {
    Vec3 p{0, 0, 0};      ///< position in texture units (solid texture space)
    Vec3 n{0, 0, 1};      ///< unit surface normal (needed by models that slice, e.g. Gabor)
    Vec3 dpdx{0, 0, 0};   ///< dP/dx_screen
    Vec3 dpdy{0, 0, 0};   ///< dP/dy_screen

    /// Longest axis of the footprint projected on the tangent plane, in texture units.
    double major_axis() const;
};

}  // namespace stochtex
