// Normal-map filtering from slope moments, after LEAN mapping (Olano & Baker 2010; paper 002
// §4 and its §6.5, notes P2.6).
//
// A height field's slopes s = (∂h/∂x, ∂h/∂y) are two tiling-and-blending noises sharing their
// tiles, so their mean and 2×2 covariance over a footprint come from the moment estimators
// (tiling_noise.h, eqs. 52, 55–60). The footprint's micro-facets then have a Gaussian slope
// distribution 𝒩(μ, Σ + Σ_base); its normal distribution function, evaluated at the half
// vector, is the filtered specular lobe: minification turns unresolved bumps into roughness
// instead of into sparkling aliasing.
#pragma once

#include "models/tiling/moment_pyramid.h"

#include <array>

namespace stochtex {

using Direction = std::array<double, 3>;

/// The unit normal of a facet with slopes (sx, sy): (−sx, −sy, 1) normalised.
Direction normal_from_slopes(double sx, double sy);

/// D(h): the density of facet normals equal to the unit half vector h (tangent space, z up)
/// for slopes 𝒩(mean, covariance + base_variance · I) (channels 0 and 1 of `slopes`), per
/// unit projected area, as in a Beckmann lobe. h·z must be positive.
double lean_ndf(const Moments& slopes, double base_variance, const Direction& half);

/// Blinn–Phong-like shading of one facet normal with the same lobe width: the unfiltered
/// per-sample shading the LEAN estimate is compared with (a Gaussian of slope differences).
double facet_ndf(double sx, double sy, double base_variance, const Direction& half);

}  // namespace stochtex
