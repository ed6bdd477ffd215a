// The raster path of a random-phase stratum (LrpStratumNoise): separable sums over a grid.
//
// A term of window i at pixel (x, y) is re·cos θ − im·sin θ with θ = 2π(f_x dx + f_y dy),
// dx = x − x_i, dy = y − y_i. Written as cos(a + b), it is
//
//   ca·P − sa·Q,   (ca, sa) = (cos, sin)(2π f_x dx),   P = re·cb − im·sb,  Q = re·sb + im·cb,
//
// (cb, sb) = (cos, sin)(2π f_y dy). On a grid every pixel of a column shares dx and every pixel
// of a row shares dy, so the raster takes one sine/cosine per term per window *column* (a table
// over the window's columns, shared by its rows) and one per term per window *row*, and per pixel
// only the six products and sums above. LrpStratumNoise::eval uses the same decomposition
// (sum_terms_separable), so the raster and the point path are bit-identical: every table value
// is computed directly from its own dx or dy (no recurrence, nothing that drifts), and the SIMD
// kernels (lrp_raster_kernels.h) repeat the scalar operations lane by lane.
//
// Two ways to lay that sum out over the lanes. `separable` goes window by window over its box of
// pixels: a wide window fills the vectors, but a window 1–3 pixels wide fills 4 lanes at most
// and pays its per-window calls and tables for a handful of pixels. `lattice_rows` goes pixel
// row by pixel row with pixels as lanes, each lane summing its own 3×3 windows (slot by slot,
// in sum_windows' order): a lattice row's column tables are made once for the whole width (each
// lane's own window's frequency, gathered), a pixel row's row factors once for all the lattice
// row's windows, and each lane takes its window's factors by a lane permutation. The same
// factors and the same operations per pixel, so both give eval()'s values.
#pragma once

#include "models/lrp/lrp_noise.h"

namespace stochtex {

/// Exemplar-pixel positions of a raster's columns and rows (both strictly increasing).
struct LrpRasterGrid {
    const double* x = nullptr;
    int width = 0;
    const double* y = nullptr;
    int height = 0;
};

/// The lattice points [i_begin, i_end) × [j_begin, j_end) whose 3×3 windows hold every pixel of
/// the grid (nearest() never decreases along an axis: the grid's ends bound every pixel's).
struct LrpGridWindows {
    std::int64_t i_begin, i_end, j_begin, j_end;
    LrpGridWindows(const LrpLattice& lattice, const LrpRasterGrid& grid);
};

/// How lrp_raster_stratum sums (the same values either way).
enum class LrpRasterMethod {
    automatic,     ///< lattice_rows for windows narrower than lrp_lattice_row_spacing pixels, else separable
    separable,     ///< window by window, each over its box of pixels (wide windows fill the vectors)
    lattice_rows,  ///< pixel row by pixel row, each lane (pixel) with its own 3×3 windows
};

/// Lattice spacings, in grid columns, below which `automatic` takes the lattice-row raster.
constexpr double lrp_lattice_row_spacing = 16;

/// Whether `automatic` takes the lattice-row raster for this stratum on this grid.
bool lrp_raster_prefers_lattice_rows(const LrpStratumNoise& noise, const LrpRasterGrid& grid);

/// lrp_raster_stratum by the lattice-row raster, drawing the terms itself a lattice row at a time
/// (LrpStratumNoise::draw_row: the row's points in the lanes, straight into the raster's layout;
/// no LrpTermCache of the region: for windows of a few pixels the cache's copy of every window's
/// terms, several MB a region, cost more than drawing).
void lrp_raster_stratum_drawn(const LrpStratumNoise& noise, const LrpFilter& filter, const LrpRasterGrid& grid,
                              float* const out[3], bool add = false);

/// out[c][r · width + k] = noise.eval(x[k], y[r], filter)'s channel c, bit for bit, where `terms`
/// holds the lattice points' terms under `filter` for every lattice point whose window reaches
/// the grid; with `add`, out[c][…] + that value instead (eval_region's sum over strata, without
/// a pass of its own). Buffers: one per-thread scratch, grown once (no allocation per call after that).
void lrp_raster_stratum(const LrpStratumNoise& noise, const LrpTermCache& terms, const LrpRasterGrid& grid,
                        float* const out[3], LrpRasterMethod method = LrpRasterMethod::automatic, bool add = false);

/// One stratum of lrp_raster_strata: its terms (LrpTermCache, as lrp_raster_stratum takes them)
/// and where its values go (a null out[c]: channel c not written; with `add`, out + the value).
struct LrpRasterLayer {
    const LrpStratumNoise* noise = nullptr;
    const LrpTermCache* terms = nullptr;
    float* out[3] = {nullptr, nullptr, nullptr};
    bool add = false;
};

/// Whether two strata have the same windows (lattice and normalisation): the same weights at
/// every pixel, so lrp_raster_strata may take them together.
bool lrp_raster_shares_windows(const LrpStratumNoise& a, const LrpStratumNoise& b);

/// lrp_raster_stratum's separable raster of `count` (≤ lrp_raster::max_layers) strata that share
/// their windows (lrp_raster_shares_windows), their term caches filled for the same lattice points:
/// each window's weights at each pixel computed once for all of them (a turbulence stratum is a
/// texture stratum's lattice with other terms). Each layer's values are lrp_raster_stratum's,
/// bit for bit: the same weights, terms and operations, each layer summing into its own buffers.
void lrp_raster_strata(const LrpRasterLayer* layers, int count, const LrpRasterGrid& grid);

}  // namespace stochtex
