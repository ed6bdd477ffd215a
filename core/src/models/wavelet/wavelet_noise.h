// Cook–DeRose wavelet noise bands (SIGGRAPH 2005), the basis of the wavelet model (paper 000).
//
// A band N is a quadratic B-spline whose coefficients are Gaussian white noise minus its
// down-then-up-sampled version, so N carries (almost) only frequencies in [1/4, 1/2) cycles per
// lattice unit. The coefficient tile is periodic; the texture decorrelates bands and channels
// with per-band random offsets.
//
// σ_N² (the band variance, paper eq. 2, "≈ 0.265") depends on the tile, the filters and the
// dimension. We never assume it: each tile measures its own spatial mean of N² exactly (a dense
// regular grid over one full period), in 2D and 3D; a 3D band sliced by a plane has the 3D
// pointwise variance (stationarity), which tests confirm by Monte Carlo.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

namespace stochtex {

/// The quadratic B-spline weights at a lattice coordinate and the index of the first of its
/// three coefficients, wrapped into one period (see WaveletNoise2D::spline_x / spline_y).
struct LatticeSpline {
    std::int64_t first;
    float w[3];
};

class WaveletNoise2D {
public:
    /// The shared process-wide 256² tile (built once, thread-safe).
    static const WaveletNoise2D& shared();
    /// A tile of period_x × period_y lattice cells (both even, 4 … 1024), built on first use
    /// and kept for the life of the process (thread-safe); 256 × 256 is shared(). Periodic
    /// textures use these to fit a whole number of tiles into an image's period.
    static const WaveletNoise2D& with_period(int period_x, int period_y);
    WaveletNoise2D(int period_x, int period_y, std::uint64_t tile_seed);

    /// N(x, y), x and y in lattice units. Periodic with period (period_x(), period_y()).
    float eval(double x, double y) const { return eval(spline_x(x), spline_y(y)); }

    // The separable parts of eval(), for rasters: a row shares spline_y, a column spline_x.
    LatticeSpline spline_x(double x) const { return wrapped_spline(x, nx_, inverse_nx_, mask_x_); }
    LatticeSpline spline_y(double y) const { return wrapped_spline(y, ny_, inverse_ny_, mask_y_); }
    float eval(const LatticeSpline& sx, const LatticeSpline& sy) const
    {
        const float* row = padded_row(sy.first) + sx.first;
        const std::size_t width = padded_width();
        float column[3];
        for (int k = 0; k < 3; ++k) column[k] = combine_rows(sy, row + k, width);
        return sx.w[0] * column[0] + sx.w[1] * column[1] + sx.w[2] * column[2];
    }
    /// Rasters combine a row's three coefficient rows once for all its pixels; these are the
    /// two halves of eval(x, y), with eval()'s arithmetic in eval()'s order (bit-identical).
    const float* padded_row(std::int64_t first) const { return &padded_[std::size_t(first) * padded_width()]; }
    std::size_t padded_width() const { return std::size_t(nx_) + 3; }
    static float combine_rows(const LatticeSpline& sy, const float* at, std::size_t width)
    {
        return sy.w[0] * at[0] + sy.w[1] * at[width] + sy.w[2] * at[2 * width];
    }

    int period_x() const { return nx_; }
    int period_y() const { return ny_; }
    /// The B-spline coefficients, period_x · period_y floats, rows contiguous (for spectral analysis).
    const std::vector<float>& coefficients() const { return coefficients_; }
    /// Spatial mean of N² over one period (σ_N² of this tile), exact.
    double variance() const { return variance_; }

    /// Sampled on a regular grid of spacing 2^-j lattice units, the variance of N depends on
    /// where the grid sits within a lattice cell (the B-spline weights differ with the phase):
    /// up to ±20 % for j = 0, which is exactly how a render at the photo's pixel scale samples
    /// the finest band. This returns a grid phase φ in [0, 2^-j) at which the grid's variance
    /// equals variance(), for j < balanced_phase_count; the texture puts its offsets there.
    double balanced_phase(int j) const { return balanced_phase_[j]; }
    static constexpr int balanced_phase_count = 3;

private:
    double grid_variance(int j, double phase) const;

    /// floor() as an integer without a libm call (x86-64's baseline has no rounding instruction).
    static std::int64_t floor_to_int(double x)
    {
        const auto i = std::int64_t(x);
        return i - (double(i) > x);
    }
    /// The first index is wrapped into [0, n] (n only by rounding at exact multiples of the
    /// period; the padded tile holds columns up to n + 2). mask = n − 1 when n is a power of
    /// two (the common case: one AND instead of a multiplication and a floor).
    static LatticeSpline wrapped_spline(double x, int n, double inverse_n, int mask)
    {
        const double shifted = x - 0.5;
        const std::int64_t base = floor_to_int(shifted);
        const float t = float(shifted - double(base));
        LatticeSpline s;
        s.first = mask >= 0 ? (base & mask) : base - n * floor_to_int(double(base) * inverse_n);
        s.w[0] = 0.5f * (1 - t) * (1 - t);
        s.w[2] = 0.5f * t * t;
        s.w[1] = 1 - s.w[0] - s.w[2];
        return s;
    }

    int nx_, ny_;
    double inverse_nx_, inverse_ny_;
    int mask_x_, mask_y_;  // period − 1 for power-of-two periods, else −1
    std::vector<float> coefficients_;
    /// The coefficients with three more columns and rows (wrapped copies), so that eval()
    /// wraps a lattice index once and then reads its 3 × 3 neighbourhood without wrapping.
    std::vector<float> padded_;
    double variance_ = 0;
    double balanced_phase_[balanced_phase_count] = {};
};

class WaveletNoise3D {
public:
    static const WaveletNoise3D& shared();
    WaveletNoise3D(int tile_size, std::uint64_t tile_seed);

    /// N(x, y, z), lattice units: the 3 × 3 × 3 coefficients combined in z and y first, then in x
    /// (the order a solid raster shares along a row: eval_row()).
    float eval(double x, double y, double z) const;
    /// A row of a solid raster at lattice (y, z): C[x] for the size() lattice columns x, then
    /// C[0], C[1] again (size() + 2 floats), the coefficients combined in z and y with eval()'s
    /// weights and order, so that N(x, y, z) = wx0·C[i] + wx1·C[i+1] + wx2·C[i+2] with
    /// i = wx.first & (size − 1): bit-identical to eval().
    void eval_row(double y, double z, float* columns) const;
    int tile_size() const { return size_; }
    double variance() const { return variance_; }
    /// The B-spline coefficients, tile_size³ floats, index (z · size + y) · size + x (exporters).
    const std::vector<float>& coefficients() const { return coefficients_; }

private:
    int size_;
    int mask_;
    std::vector<float> coefficients_;
    double variance_ = 0;
};

/// Quadratic B-spline weights for the three coefficients around x, and the index of the first.
/// (Cook–DeRose evaluate at "mid = ceil(x - 1/2)"; this is the same spline, written for floor.)
struct QuadraticBSplineWeights {
    std::int64_t first;  ///< index of the leftmost of the three coefficients (positions reach 2^45 cells)
    float w[3];
    explicit QuadraticBSplineWeights(double x)
    {
        const double shifted = x - 0.5;
        const double base = std::floor(shifted);
        const float t = float(shifted - base);  // in [0, 1)
        first = std::int64_t(base);
        w[0] = 0.5f * (1 - t) * (1 - t);
        w[2] = 0.5f * t * t;
        w[1] = 1 - w[0] - w[2];
    }
};

}  // namespace stochtex
