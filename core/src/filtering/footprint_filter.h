// From a footprint to a filter: the one place where a pixel's footprint (footprint.h) becomes
// the covariance of the Gaussian that filters it, in a model's own units. Used by the models
// that filter analytically (gabor, lrp); the others reduce the footprint to its major axis
// (Footprint2D::major_axis) or sample along its columns (tiling).
#pragma once

#include <stochtex/footprint.h>

#include <algorithm>
#include <cmath>

namespace stochtex {

/// A symmetric 2×2 matrix [[xx, xy], [xy, yy]].
struct Symmetric2 {
    double xx = 0, xy = 0, yy = 0;

    double determinant() const { return xx * yy - xy * xy; }
    double quadratic_form(double x, double y) const { return xx * x * x + 2 * xy * x * y + yy * y * y; }
    double largest_eigenvalue() const
    {
        const double half_trace = 0.5 * (xx + yy);
        return half_trace + std::sqrt(std::max(0.0, 0.25 * (xx - yy) * (xx - yy) + xy * xy));
    }
    double smallest_eigenvalue() const
    {
        const double half_trace = 0.5 * (xx + yy);
        return half_trace - std::sqrt(std::max(0.0, 0.25 * (xx - yy) * (xx - yy) + xy * xy));
    }
};

/// An orthonormal frame: the tangent plane (t, b) of a slice and its normal n.
struct TangentFrame {
    Vec3 t{1, 0, 0}, b{0, 1, 0}, n{0, 0, 1};
};

inline double dot3(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/// The frame of a surface point: n normalised; t along the tangential part of dP/dx (the paper's
/// choice, §5), or any unit vector ⊥ n when that vanishes; b = n × t. The filtered value does not
/// depend on the choice of t (tests/gabor_test.cpp, frame invariance).
TangentFrame tangent_frame(const Vec3& normal, const Vec3& dpdx);

/// Screen-space pixel filter: a Gaussian of σ = ½ pixel (paper 001, §5).
constexpr double pixel_filter_sigma = 0.5;
/// Footprints are clamped to this ratio of their axes' standard deviations (as EWA filters do):
/// a footprint collapsed to a line (grazing angles, degenerate derivatives) is widened across, so
/// the filtered kernels stay within a bounded area.
constexpr double max_footprint_anisotropy = 8;

/// The tangent-space covariance Σ_f = σ² J Jᵀ of the pixel filter, J the 2×2 Jacobian from screen
/// to tangent coordinates (columns: the derivatives along screen x and y), scaled by `scale`
/// (texture units → noise units), with the anisotropy clamped.
Symmetric2 filter_covariance(double j00, double j01, double j10, double j11, double scale);

/// The same for a 2D footprint (the Jacobian of (u, v)), or a solid one projected on a tangent
/// frame (tangent_footprint): the one conversion every analytically filtered model uses.
inline Symmetric2 filter_covariance(const Footprint2D& footprint, double scale)
{
    return filter_covariance(footprint.dudx, footprint.dudy, footprint.dvdx, footprint.dvdy, scale);
}

/// A surface point's footprint in the tangent coordinates (t, b) of `frame`.
inline Footprint2D tangent_footprint(const TangentFrame& frame, const SurfacePoint& point)
{
    return {dot3(frame.t, point.dpdx), dot3(frame.b, point.dpdx), dot3(frame.t, point.dpdy), dot3(frame.b, point.dpdy)};
}

/// Σ − v·I with negative eigenvalues clamped to 0: the blur still to apply when `v` (per axis) is
/// already there (Gaussian blurs compose by adding covariances).
Symmetric2 without_isotropic_blur(const Symmetric2& sigma, double v);

}  // namespace stochtex
