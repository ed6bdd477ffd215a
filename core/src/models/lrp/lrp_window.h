// The window of local random-phase noise (paper 003, §3.4–3.6): a radial Kaiser–Bessel window
// of half-width 1.5 lattice spacings, so a point is covered by the 3×3 lattice points around its
// nearest one and by no other.
//
//   w(y) = I₃(3π √(1 − (y/1.5)²)) / I₃(3π)   for |y| < 1.5, else 0;   w(0) = 1.
//
// Order and constant. The paper prints the series of I₂ ("α = 3", m!(m+2)!, 5 terms), but its
// constant ∫₀^∞ r w²(r) dr ≈ 0.1126 is reproduced only by the order-3 function I₃ evaluated to
// convergence (NOTES-002-003-004.md P3.2; tests/lrp_test.cpp integrates it): I₃ it is.
//
// Synthesis reads the window from a table in y² (no square root, no series per evaluation);
// the exact function is the reference the table is tested against.
#pragma once

#include <array>

namespace stochtex {

/// Half-width of the window in lattice spacings.
constexpr double lrp_window_radius = 1.5;

/// The exact window (std::cyl_bessel_i, double precision).
double lrp_window(double y);

/// ∫₀^1.5 r w²(r) dr (Simpson): the paper's 0.1126.
double lrp_window_radial_energy();

/// Spectral spread of the window at spacing 1, in cycles per spacing: the radius holding
/// `fraction` of |ŵ|²'s energy, along one axis (1D transform of w, the paper's erosion δ:
/// 0.28 for 75 %) and over the 2D disk (radial transform of w(|x|): 0.41 for 75 %). Computed
/// numerically once per fraction; divide by the spacing Δ for cycles per pixel.
double lrp_window_spread_1d(double fraction);
double lrp_window_spread_2d(double fraction);
/// lrp_window_spread_2d without the cache (and its seed): the transform integrated each call.
double lrp_window_spread_2d_computed(double fraction);

/// w as a function of y² on [0, 2.25], linearly interpolated from a table (max error < 1e-4).
class LrpWindowTable {
public:
    static constexpr int size = 1024;
    static const LrpWindowTable& shared();

    float operator()(float y2) const
    {
        if (!(y2 < float(lrp_window_radius * lrp_window_radius))) return 0.0f;
        const float t = y2 * scale_;
        const int i = int(t);
        const float f = t - float(i);
        return value_[i] + f * (value_[i + 1] - value_[i]);
    }

    /// The table itself (size + 2 values: w at y² = k / scale()), for the raster's gathers.
    const float* values() const { return value_.data(); }
    float scale() const { return scale_; }

private:
    LrpWindowTable();
    float scale_;
    std::array<float, size + 2> value_;  // one spare zero: y2·scale_ may round up to `size`
};

}  // namespace stochtex
