// The phase-augmented Gabor kernel (paper 001, eq. 5), its slice by a plane (eq. 6) and its
// convolution with the pixel's Gaussian filter (eq. 10):
//
//   g(x; a, ω, φ) = exp(−π a² |x|²) · cos(2π ω·x + φ)
//
// Slicing. For a kernel centred at x_i and a plane through x with unit normal n and tangents
// (t, b), write d = x − x_i = p + h·n with p = (t·d, b·d) in the plane and h = n·d. Then
//   g(d) = exp(−π a² h²) · exp(−π a² |p|²) · cos(2π ω^s·p + φ + 2π h (n·ω)),   ω^s = (t·ω, b·ω):
// the paper's w^s = exp(−π a² d²) and φ^s = φ − 2π d (n·ω) with its signed distance d = −h. This
// is an identity, not an approximation: the sliced kernel equals the 3D kernel on the plane.
//
// Filtering. Convolving the 2D kernel g(p; a, ω^s, φ) with a normalised Gaussian of covariance
// Σ_f is exact in closed form (a Gaussian times a harmonic stays one). With A = I + 2π a² Σ_f:
//   (g ∗ G_f)(p) = |A|^-½ · exp(−2π² ω^sᵀ A⁻¹ Σ_f ω^s) · exp(−π a² pᵀ A⁻¹ p) · cos(2π (A⁻¹ω^s)·p + φ).
// The paper (eq. 10) replaces the envelope pᵀA⁻¹p by the isotropic |A|^-½ |p|² of the same
// determinant; we keep the exact anisotropic envelope, which costs two multiplications more.
// This "A-form" needs no inverse of Σ_f, so singular footprints (Σ_f = 0: point sampling;
// rank 1: a footprint collapsed to a line) are handled without special cases.
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

/// Σ − v·I with negative eigenvalues clamped to 0: the blur still to apply when `v` (per axis) is
/// already there (Gaussian blurs compose by adding covariances).
Symmetric2 without_isotropic_blur(const Symmetric2& sigma, double v);

/// The filter of one kernel bandwidth `a` by Σ_f, in the A-form above.
struct GaborFilter {
    Symmetric2 matrix{1, 0, 1};     ///< A: the envelope's support is the ellipse pᵀA⁻¹p ≤ r², of extent r·√A_ii
    Symmetric2 inverse_a{1, 0, 1};  ///< A⁻¹: the filtered frequency is A⁻¹ω^s; the envelope metric is a²A⁻¹
    Symmetric2 damping;    ///< 2π² A⁻¹Σ_f: the amplitude of a kernel of in-plane frequency ω^s is
                           ///< amplitude · exp(−ω^sᵀ damping ω^s)
    double amplitude = 1;  ///< |A|^-½: also how much the support's area grows (by 1/amplitude)
    bool identity = true;  ///< Σ_f = 0: the kernel is unchanged (point sampling)

    GaborFilter() = default;
    GaborFilter(double a, const Symmetric2& sigma_f);
};

}  // namespace stochtex
