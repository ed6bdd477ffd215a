// The normal distribution: CDF, inverse CDF and Gauss–Hermite expectations.
#pragma once

#include <array>
#include <cmath>
#include <vector>

namespace stochtex {

inline double normal_cdf(double z) { return 0.5 * std::erfc(-z * M_SQRT1_2); }

/// Φ⁻¹(p) for p in (0, 1), accurate to ~1e-15 (Acklam's rational approximation refined by one
/// Halley step). p outside (0, 1) is clamped to the nearest double inside.
double inverse_normal_cdf(double p);

/// Nodes and weights such that E[f(Z)], Z ~ N(0, 1), ≈ Σ weight_i f(node_i). Exact for
/// polynomials of degree < 2·count; computed once by Golub–Welsch (no hand-copied tables).
struct GaussHermite {
    static constexpr int count = 12;
    std::array<double, count> node;
    std::array<double, count> weight;
    static const GaussHermite& standard_normal();
};

/// The same expectation with 3, 5 or 7 nodes (`count` clamped to [3, 7], even counts rounded
/// down), nodes ascending and symmetric about 0; exact for polynomials of degree < 2·nodes. The
/// nodes and weights are tabulated: Golub–Welsch gives them only to a few ulps, not exactly
/// symmetric, and the tiling colour-map filter's renders depend on every bit of them.
struct SmallGaussHermite {
    std::vector<double> node, weight;
    static const SmallGaussHermite& standard_normal(int count);
};

}  // namespace stochtex
