// The Gabor kernel sum of a row of points, vectorised with Highway (gabor_raster_kernels.cpp,
// dispatched to the best instruction set of the CPU at run time). GaborNoise evaluates every point
// — a single eval() too — through this one kernel, so the point and the raster paths are one
// implementation and their values are bit-identical (docs/models/gabor.md, "Precision").
//
// Lanes are points of one row (same y and z, consecutive x); the cells they can reach are
// visited once per vector of points, each cell's impulse read from a CellImpulses cache that a
// block of rows shares. A lane adds a kernel only if the point is inside the kernel's support
// (q ≤ limit, below); the others add exact zeros, which leave an IEEE sum unchanged, so a point's
// value is the same whichever points share its vector, block or region.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace stochtex::gabor_raster {

/// The impulses of a set of cells, structure of arrays, prepared for one filter (and, solid, one
/// slicing frame). For a point p and an impulse at position c, with d = p − c:
///   kernel = exp(min(log_amplitude − q, −87))·cos(2π (w·d) + φ_channel),   q = Σ_k (e_k·d)²
/// (Envelope's e_k), kept where q ≤ limit.
struct CellImpulses {
    std::vector<double> x, y, z;  ///< impulse positions (z unused in 2D)
    std::vector<float> wx, wy, wz;  ///< w: the filtered (and sliced) frequency, cycles per unit
    std::vector<float> log_amplitude;  ///< ln of the filtered kernel's amplitude (−ω^sᵀ·damping·ω^s)
    std::vector<float> cos_phase[3], sin_phase[3];

    std::size_t size() const { return x.size(); }
    void clear();
    /// Every array to n impulses (kept ones unchanged, new ones to be written).
    void resize(std::size_t n);
};

/// Cells [first, first + count) of a CellImpulses are one row of cells along x, the first with
/// index i_first. For one row of points, the cells that point x can reach are those with
/// floor((x + lo) / cell) ≤ i ≤ floor((x + hi) / cell): lo and hi bound the filtered support's
/// extent along x over this row of cells (with a margin, so that every kernel the q ≤ limit test
/// could keep is visited whatever the grouping).
struct CellRow {
    std::uint32_t first = 0, count = 0;
    std::int64_t i_first = 0;
    double lo = 0, hi = 0;
    bool every_cell = false;  ///< visit all `count` cells (a list already culled for the points)
};

/// q = Σ_k (e_k·d)² = π a² · (the filtered support's quadratic form): a sum of squares of linear
/// forms (a Cholesky factor) rather than the quadratic form's terms, which would cancel in float
/// for elongated footprints. 2D: e_0 = 0 and only the (x, y) components are read.
struct Envelope {
    float e[3][3] = {};
    float limit = 0;  ///< π a² r²: the 5 % support
};

/// One row of points: x[0 .. count) at (y, z), summed over `rows`.
struct RowInput {
    const CellImpulses* cells = nullptr;
    const CellRow* rows = nullptr;
    std::size_t row_count = 0;
    double cell_x = 1;  ///< cell side along x
    double y = 0, z = 0;
    Envelope envelope;
    double gain = 1;  ///< out = float(sum · gain)
    int channels = 3;  ///< 1 or 3
    bool solid = false;
};

/// out[c][k] = float(gain · Σ kernels of channel c) at x[k], k < count, c < channels.
void sum_row(const RowInput& input, const double* x, std::size_t count, float* const out[3]);

/// A single point's candidate cells of the solid noise, culled in double before their impulses
/// are prepared (GaborNoise::eval_sliced): rows of cells (j, k), i from i0 to i1.
struct CandidateRow {
    std::int64_t i0, i1, j, k;
};
/// Cell (i, j, k) has the key key0 + i·step_i + j·step_j + k·step_k (wrapping) and its impulse
/// at ((i, j, k) + fraction) · cell, the fractions the 21-bit fields of mix64(key) plus ½, times
/// 2^-21 (gabor_noise.cpp's cell_key_3d, position_fraction). Kept: (p − c)ᵀ m (p − c) ≤ limit.
struct CandidateTest {
    std::uint64_t key0, step_i, step_j, step_k;
    double cell;
    double p[3];
    double m[3][3];
    double limit;
};
/// The kept cells' keys and impulse positions, rows in order and i ascending, into key, x, y, z
/// (room for every candidate plus 64); returns how many. The same integer and IEEE double
/// operations in every lane, so every instruction set keeps the same cells.
std::size_t test_candidates(const CandidateTest& test, const CandidateRow* rows, std::size_t row_count, std::uint64_t* key,
                            double* x, double* y, double* z);

}  // namespace stochtex::gabor_raster
