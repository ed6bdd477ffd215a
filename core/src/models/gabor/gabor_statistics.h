// Analytic second-order statistics of random-phase Gabor noise (paper 001, §3.3–3.5; its
// supplemental is not available, so these are derived here and checked by tests/gabor_test.cpp).
//
// For one frequency ω, random phases remove every cross term between kernels:
//   Var = λ/2 · (√2 a)^-n,   PSD(f) ∝ exp(−2π|f − ω|²/a²) + exp(−2π|f + ω|²/a²),
//   correlation R(τ) = exp(−π a² |τ|² / 2) · cos(2π ω·τ),
// and a noise whose ω varies per kernel averages these over ω's distribution. gabor_noise.h
// normalises to unit variance, so everything here is per unit variance.
//
// Slicing (Slice-Projection theorem, paper §3.5): the slice's PSD is the 3D PSD projected along the
// normal, i.e. the 2D PSD of the projected frequencies ω^s. For isotropic noise those fill the
// disc |ω^s| ≤ F — the sliced spectrum has power below F that a 2D ring would not: the by-example
// fit (gabor_fit.h) uses these sliced spectra, not the 2D ring.
//
// Filtering by a Gaussian of covariance Σ_f (gabor_kernel.h) keeps the fraction
//   ρ = |A|^-½ · E_ω[exp(−4π² ω^sᵀ A⁻¹Σ_f ω^s)]
// of the variance (exactly: the filtered kernel is again a Gaussian times a harmonic).
#pragma once

#include "models/gabor/gabor_kernel.h"
#include "models/gabor/gabor_noise.h"

namespace stochtex {

/// e^-x · I₀(x) for x ≥ 0 (Abramowitz & Stegun 9.8.1–2, |error| < 2e-7): bounded where I₀ overflows.
double scaled_bessel_i0(double x);

/// Correlation E[n(x) n(x + τ)] of the unit-variance solid noise (5 % truncation ignored).
double gabor_correlation(const GaborNoiseParameters& noise, const Vec3& tau);

/// Radially averaged PSD, per unit variance and cycle² (so ∫ 2πρ·psd(ρ) dρ = 1), of the noise
/// sliced by the plane w = const — equally, of the 2D noise — at radius ρ in cycles per unit.
double gabor_slice_radial_psd(const GaborNoiseParameters& noise, double rho);

/// ρ: the fraction of the unit variance that survives `filter` (built with the noise's
/// bandwidth), for the solid noise sliced by the plane of `frame` (the 2D noise: the default
/// frame, the (u, v) plane).
double gabor_retained_variance(const GaborNoiseParameters& noise, const TangentFrame& frame, const GaborFilter& filter);
// The isotropic case's table is exported, for the OSL shader, as gabor_sphere_table()
// (stochtex/models/gabor_shader_data.h).

}  // namespace stochtex
