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

#include "filtering/footprint_filter.h"

#include <algorithm>
#include <cmath>

namespace stochtex {

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
