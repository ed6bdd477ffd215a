// The wavelet raster's inner loops, vectorised with Highway (wavelet_raster_kernels.cpp, dispatched
// to the best instruction set of the CPU at run time).
//
// Each kernel performs, lane by lane, exactly the IEEE operations of the scalar expression it
// replaces, in the same order (no fused multiply-add: the core builds with -ffp-contract=off), so
// its values are bit-identical to WaveletNoise2D::eval / WaveletTexture::eval on every target.
#pragma once

#include <cstddef>
#include <cstdint>

namespace stochtex::wavelet_raster {

/// out[k] = (w[0]·at[k] + w[1]·at[k + stride]) + w[2]·at[k + 2·stride], k < count: a row's three
/// coefficient rows combined with its y-spline (WaveletNoise2D::combine_rows for many columns).
void combine_rows(const float w[3], const float* at, std::size_t stride, std::size_t count, float* out);

/// out[x] = (wz[0]·P0 + wz[1]·P1) + wz[2]·P2, Pk = (wy[0]·rows[3k][x] + wy[1]·rows[3k+1][x]) +
/// wy[2]·rows[3k+2][x], x < count: the nine coefficient rows around a solid raster row, combined
/// in z and y with their splines (WaveletNoise3D::eval's order) for every lattice column.
void combine_planes(const float wz[3], const float wy[3], const float* const rows[9], std::size_t count, float* out);

/// The x-splines of a raster's columns, structure of arrays: column i reads combined[index[i] + k]
/// with weight w_k[i]. `group` (filled by plan_columns) says, per vector of columns, whether the
/// vector's three reads fit one vector loaded from combined[group[g]] (then they are lane
/// permutations of it, far cheaper than gathers: every band a filter keeps has ≤ 2 lattice cells
/// per pixel) or, if group[g] < 0, need gathers.
struct ColumnSplines {
    const std::int32_t* index;
    const float* w0;
    const float* w1;
    const float* w2;
    const std::int32_t* group;
};

/// Fills group[] for the columns' index[] (count columns; group holds count entries).
void plan_columns(const std::int32_t* index, std::size_t count, std::int32_t* group);

/// How many floats accumulate_band may read past the last combined column (the caller pads).
constexpr std::size_t combined_padding = 64;

/// Where a raster's columns fall on a band's lattice. Column i is at u = origin_u + (x0 + i + ½)·du
/// (RasterRegion::u), lattice x = u·scale + offset; its quadratic B-spline (of x − ½) reads the
/// coefficients from index = floor(x − ½) wrapped into [0, period), as base − period·floor(base /
/// period) (for a power-of-two period the same as base & (period − 1)), with the weights that
/// WaveletNoise2D::spline_x and QuadraticBSplineWeights compute, bit for bit.
struct ColumnPositions {
    double origin_u, du;
    int x0;
    double scale, offset;
    int period;
    double inverse_period;
};
void column_splines(const ColumnPositions& positions, std::size_t count, std::int32_t* index, float* w0, float* w1,
                    float* w2);

/// kept[i] += fade_weight · (gain · double(value_i)), value_i = (w0·c0 + w1·c1) + w2·c2 with
/// c_k = combined[index[i] + k], for i < count: one band's contribution to a row of pixels.
void accumulate_band(const ColumnSplines& columns, const float* combined, double gain, double fade_weight,
                     double* kept, std::size_t count);

/// Scattered points of a solid batch (planar, texture units) and one band's map to its lattice:
/// point k is at lattice (x[k]·scale + offset[0], y[k]·scale + offset[1], z[k]·scale + offset[2]).
struct SolidBandPoints {
    const double* x;
    const double* y;
    const double* z;
    double scale;
    const double* offset;  // 3 values
};

/// out[k] = WaveletNoise3D::eval at point k's lattice position, k < count: the splines of each
/// axis (QuadraticBSplineWeights), the 27 coefficients of a size³ tile (index (z·size + y)·size +
/// x, size a power of two) gathered, and eval()'s sums in eval()'s order.
void solid_noise_at_points(const SolidBandPoints& points, std::size_t count, const float* coefficients, int size,
                           float* out);

}  // namespace stochtex::wavelet_raster
