#include "models/lrp/lrp_raster.h"

#include "models/lrp/lrp_raster_kernels.h"
#include "models/lrp/lrp_window.h"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

namespace stochtex {

static_assert(LrpTermCache::read_padding >= lrp_raster::padding, "row_factors reads a vector past a point's terms");

namespace {

/// The grid columns a lattice column's windows reach, and where its dx, rx² tables start: the same
/// for every lattice row, so made once per region instead of once per window.
struct LatticeColumn {
    int k0 = 0, k1 = 0;
    std::size_t at = 0;
};

/// One stratum's buffers in the separable raster.
struct LayerScratch {
    std::vector<float> sum[3];        // per grid row, padded rows
    std::vector<float> sine, cosine;  // column factors, [term][column]
    std::vector<float> p, q;          // row factors, [term][channel]
};

/// One thread's buffers, reused by every region the thread renders.
struct Scratch {
    LayerScratch layer[lrp_raster::max_layers];
    std::vector<float> weight, weight_squared;  // per grid row, padded rows
    std::vector<float> dx, rx2;                 // every lattice column's box of columns, back to back
    std::vector<LatticeColumn> columns;         // per lattice column i
};

Scratch& scratch()
{
    thread_local Scratch s;
    return s;
}

/// One lattice row's tables in the lattice-row raster, kept while pixel rows need them.
struct LatticeRowTables {
    std::int64_t j = 0;
    bool made = false;
    int terms = 0;                            // the most live terms of the row's windows
    std::vector<float> fx, fy, re[3], im[3];  // term t of window w at [t · windows + w]; 0 past its live terms
    std::vector<float> sine, cosine;          // column factors, [(dix · terms + t) · stride + k]
};

/// The lattice-row raster's buffers, one per thread.
struct RowScratch {
    std::vector<std::int32_t> window;  // per grid column: its nearest lattice column − i_begin
    std::vector<float> dx, rx2;        // per slot dix and grid column, [dix · stride + k]
    LatticeRowTables rows[3];          // lattice row j in rows[j mod 3]
    std::vector<float> p[3], q[3];     // row factors of the pixel row's three lattice rows
};

RowScratch& row_scratch()
{
    thread_local RowScratch s;
    return s;
}

std::size_t round_up(std::size_t n, std::size_t multiple) { return (n + multiple - 1) / multiple * multiple; }

void reset(std::vector<float>& buffer, std::size_t size)
{
    buffer.resize(std::max(buffer.size(), size));
    std::fill(buffer.begin(), buffer.begin() + std::ptrdiff_t(size), 0.0f);
}

/// The number of positions (increasing) below `value`, or with `or_equal` not above it
/// (std::lower_bound / std::upper_bound's index). Found from the first and last position as if
/// evenly spaced (a raster's are), then stepped to the exact index: a step or none on a raster,
/// where the binary search that this replaced cost ~6 % of a stratum in mispredicted branches.
template <bool or_equal>
int count_below(const double* position, int count, double value)
{
    const auto below = [value](double p) { return or_equal ? !(value < p) : p < value; };
    if (count == 0 || !below(position[0])) return 0;
    if (below(position[count - 1])) return count;
    const double step = count > 1 ? (position[count - 1] - position[0]) / (count - 1) : 1.0;
    int k = std::clamp(int((value - position[0]) / step), 0, count - 1);  // a guess; exactness below
    while (k > 0 && !below(position[k - 1])) --k;
    while (k < count && below(position[k])) ++k;
    return k;
}

/// [begin, end) of the positions within (centre − reach, centre + reach).
std::pair<int, int> within(const double* position, int count, double centre, double reach)
{
    const int begin = count_below<true>(position, count, centre - reach);
    const int end = begin + count_below<false>(position + begin, count - begin, centre + reach);
    return {begin, end};
}

lrp_raster::Normalisation kernel_normalisation(LrpNormalisation normalisation)
{
    return normalisation == LrpNormalisation::variance    ? lrp_raster::Normalisation::variance
           : normalisation == LrpNormalisation::partition ? lrp_raster::Normalisation::partition
                                                          : lrp_raster::Normalisation::none;
}

/// A lattice row's terms from the region's cache, in LrpStratumNoise::draw_row's layout (term t
/// of point w at [t · stride + w] of each plane, zero past a point's own and from `count` on).
/// Returns the most terms a point has.
int transpose_row(const LrpTermCache& terms, std::int64_t i_begin, std::size_t count, std::int64_t j,
                  float* const planes[8], std::size_t stride)
{
    int live = 0;
    for (std::size_t w = 0; w < count; ++w) live = std::max(live, terms.at(i_begin + std::int64_t(w), j).live);
    for (std::size_t w = 0; w < count; ++w) {
        const LrpTermView view = terms.at(i_begin + std::int64_t(w), j);
        for (std::size_t t = 0; t < std::size_t(live); ++t) {
            const bool held = t < std::size_t(view.live);
            for (std::size_t p = 0; p < 8; ++p)
                planes[p][t * stride + w] = held ? view.data[p * std::size_t(view.stride) + t] : 0.0f;
        }
    }
    for (std::size_t p = 0; p < 8; ++p)
        for (std::size_t t = 0; t < std::size_t(live); ++t) std::fill(planes[p] + t * stride + count, planes[p] + (t + 1) * stride, 0.0f);
    return live;
}

/// The raster for windows a few pixels wide (lrp_raster.h): pixels of a row in the lanes, each
/// lane with its own 3×3 windows. `fill_row(j, planes, stride)` puts lattice row j's terms into
/// the eight planes (transpose_row's layout, for the lattice columns [i_begin, i_end) — every
/// pixel's 3×3 windows, the caller checks) and returns the most terms of its points.
template <class FillRow>
void lattice_row_raster(const LrpStratumNoise& noise, std::int64_t i_begin, std::int64_t i_end, const LrpRasterGrid& grid,
                        float* const out[3], bool add, const FillRow& fill_row)
{
    const LrpLattice& lattice = noise.lattice();
    const std::size_t width = std::size_t(grid.width);
    RowScratch& s = row_scratch();
    const std::size_t stride = round_up(width, lrp_raster::padding) + lrp_raster::padding;
    const std::size_t lattice_columns = std::size_t(i_end - i_begin);
    const std::size_t windows = round_up(lattice_columns, lrp_raster::padding) + lrp_raster::padding;
    constexpr float extent = float(lrp_window_radius * lrp_window_radius);

    // Per grid column: its nearest lattice column, and dx, rx² to that column's neighbours
    // (sum_windows' arithmetic). The padding repeats the last window and lies outside every window.
    s.window.resize(std::max(s.window.size(), stride));
    s.dx.resize(std::max(s.dx.size(), 3 * stride));
    s.rx2.resize(std::max(s.rx2.size(), 3 * stride));
    for (std::size_t k = 0; k < stride; ++k) {
        if (k >= width) {
            s.window[k] = s.window[width - 1];
            for (std::size_t dix = 0; dix < 3; ++dix) s.dx[dix * stride + k] = 0, s.rx2[dix * stride + k] = 2 * extent;
            continue;
        }
        const std::int64_t cx = lattice.nearest(0, grid.x[k]);
        s.window[k] = std::int32_t(cx - i_begin);
        for (std::size_t dix = 0; dix < 3; ++dix) {
            const float dx = float(grid.x[k] - (lattice.origin[0] + double(cx + std::int64_t(dix) - 1) * lattice.spacing[0]));
            const float rx = dx * lattice.inverse_spacing[0];
            s.dx[dix * stride + k] = dx, s.rx2[dix * stride + k] = rx * rx;
        }
    }

    for (LatticeRowTables& row : s.rows) row.made = false;
    const auto tables_of = [&](std::int64_t j) -> const LatticeRowTables& {
        LatticeRowTables& row = s.rows[std::size_t(((j % 3) + 3) % 3)];
        if (row.made && row.j == j) return row;
        row.j = j, row.made = true;
        // The lattice row's terms, transposed (a term of every window along the lanes), as many
        // as its windows' most; a window's terms past its own live ones are 0.
        std::vector<float>* const planes[8] = {&row.fx, &row.fy, &row.re[0], &row.re[1], &row.re[2], &row.im[0], &row.im[1], &row.im[2]};
        float* data[8];
        for (std::size_t p = 0; p < 8; ++p) {
            planes[p]->resize(std::max(planes[p]->size(), std::size_t(noise.term_count()) * windows + lrp_raster::padding));
            data[p] = planes[p]->data();
        }
        const int live = fill_row(j, data, windows);
        // What the kernels read past the last term (everything, where there are none) holds zeros.
        for (float* plane : data) std::fill_n(plane + std::size_t(live) * windows, lrp_raster::padding, 0.0f);
        row.terms = live;
        const std::size_t terms = std::size_t(live);
        row.sine.resize(std::max(row.sine.size(), 3 * terms * stride));
        row.cosine.resize(std::max(row.cosine.size(), 3 * terms * stride));
        for (std::size_t dix = 0; dix < 3; ++dix)
            for (std::size_t t = 0; t < terms; ++t) {
                const std::size_t at = (dix * terms + t) * stride;
                lrp_raster::gathered_sincos(row.fx.data() + t * windows, s.window.data(), std::int32_t(dix) - 1,
                                            s.dx.data() + dix * stride, width, row.sine.data() + at, row.cosine.data() + at);
            }
        return row;
    };

    lrp_raster::PixelRow row;
    row.count = width, row.window = s.window.data(), row.rx2 = s.rx2.data(), row.stride = stride, row.windows = windows;
    row.normalisation = kernel_normalisation(noise.normalisation()), row.add = add;
    for (int r = 0; r < grid.height; ++r) {
        const std::int64_t cy = lattice.nearest(1, grid.y[r]);
        for (int dj = 0; dj < 3; ++dj) {
            const std::int64_t j = cy + dj - 1;
            const float dy = float(grid.y[r] - (lattice.origin[1] + double(j) * lattice.spacing[1]));
            const float ry = dy * lattice.inverse_spacing[1];
            row.ry2[dj] = ry * ry;
            row.reaches[dj] = row.ry2[dj] < extent;
            if (!row.reaches[dj]) continue;
            const LatticeRowTables& tables = tables_of(j);
            const int factors = tables.terms * int(windows);
            row.terms[dj] = tables.terms, row.plane[dj] = lrp_raster::factor_plane(factors);
            s.p[dj].resize(std::max(s.p[dj].size(), 3 * row.plane[dj]));
            s.q[dj].resize(std::max(s.q[dj].size(), 3 * row.plane[dj]));
            const float* const re[3] = {tables.re[0].data(), tables.re[1].data(), tables.re[2].data()};
            const float* const im[3] = {tables.im[0].data(), tables.im[1].data(), tables.im[2].data()};
            lrp_raster::row_factors(dy, tables.fy.data(), re, im, factors, s.p[dj].data(), s.q[dj].data());
            row.cosine[dj] = tables.cosine.data(), row.sine[dj] = tables.sine.data();
            row.p[dj] = s.p[dj].data(), row.q[dj] = s.q[dj].data();
        }
        for (int c = 0; c < 3; ++c) row.out[c] = out[c] + std::size_t(r) * width;
        lrp_raster::accumulate_pixel_row(row);
    }
}

}  // namespace

LrpGridWindows::LrpGridWindows(const LrpLattice& lattice, const LrpRasterGrid& grid)
    : i_begin(lattice.nearest(0, grid.x[0]) - 1),
      i_end(lattice.nearest(0, grid.x[grid.width - 1]) + 2),
      j_begin(lattice.nearest(1, grid.y[0]) - 1),
      j_end(lattice.nearest(1, grid.y[grid.height - 1]) + 2)
{
}

bool lrp_raster_prefers_lattice_rows(const LrpStratumNoise& noise, const LrpRasterGrid& grid)
{
    const double step = grid.width > 1 ? (grid.x[grid.width - 1] - grid.x[0]) / (grid.width - 1) : 1.0;
    return noise.lattice().spacing[0] < lrp_lattice_row_spacing * step;
}

void lrp_raster_stratum_drawn(const LrpStratumNoise& noise, const LrpFilter& filter, const LrpRasterGrid& grid,
                              float* const out[3], bool add)
{
    const LrpGridWindows needed(noise.lattice(), grid);
    lattice_row_raster(noise, needed.i_begin, needed.i_end, grid, out, add,
                       [&](std::int64_t j, float* const planes[8], std::size_t stride) {
                           return noise.draw_row(needed.i_begin, std::size_t(needed.i_end - needed.i_begin), j, filter, planes, stride);
                       });
}

bool lrp_raster_shares_windows(const LrpStratumNoise& a, const LrpStratumNoise& b)
{
    const LrpLattice &p = a.lattice(), &q = b.lattice();
    for (int axis = 0; axis < 2; ++axis)
        if (p.origin[axis] != q.origin[axis] || p.spacing[axis] != q.spacing[axis] ||
            p.inverse_spacing[axis] != q.inverse_spacing[axis] || p.wrap[axis] != q.wrap[axis])
            return false;
    return a.normalisation() == b.normalisation();
}

void lrp_raster_stratum(const LrpStratumNoise& noise, const LrpTermCache& terms, const LrpRasterGrid& grid,
                        float* const out[3], LrpRasterMethod method, bool add)
{
    if (method == LrpRasterMethod::automatic)
        method = lrp_raster_prefers_lattice_rows(noise, grid) ? LrpRasterMethod::lattice_rows : LrpRasterMethod::separable;
    if (method == LrpRasterMethod::lattice_rows) {
        const LrpGridWindows needed(noise.lattice(), grid);
        if (needed.i_begin >= terms.i_begin() && needed.i_end <= terms.i_end() && needed.j_begin >= terms.j_begin() &&
            needed.j_end <= terms.j_end())
            return lattice_row_raster(noise, needed.i_begin, needed.i_end, grid, out, add,
                                      [&](std::int64_t j, float* const planes[8], std::size_t stride) {
                                          return transpose_row(terms, needed.i_begin, std::size_t(needed.i_end - needed.i_begin), j,
                                                               planes, stride);
                                      });
    }
    const LrpRasterLayer layer{&noise, &terms, {out[0], out[1], out[2]}, add};
    lrp_raster_strata(&layer, 1, grid);
}

void lrp_raster_strata(const LrpRasterLayer* layers, int count, const LrpRasterGrid& grid)
{
    Scratch& s = scratch();
    const LrpStratumNoise& noise = *layers[0].noise;
    const LrpTermCache& terms = *layers[0].terms;  // (every layer's covers the same lattice points)
    const LrpLattice& lattice = noise.lattice();
    const std::size_t row_stride = round_up(std::size_t(grid.width), lrp_raster::padding) + lrp_raster::padding;
    const std::size_t cells = row_stride * std::size_t(grid.height);
    for (int l = 0; l < count; ++l)
        for (auto& channel : s.layer[l].sum) reset(channel, cells);
    reset(s.weight, cells);
    reset(s.weight_squared, cells);
    // A window reaches |d| < 1.5 spacings (rx² < 2.25 in float); the margin covers float rounding,
    // the kernel's weight test decides.
    const double reach[2] = {lrp_window_radius * lattice.spacing[0] * 1.0001, lrp_window_radius * lattice.spacing[1] * 1.0001};
    constexpr float extent = float(lrp_window_radius * lrp_window_radius);

    // Each lattice column's box of grid columns and their dx, rx² (shared by the lattice's rows).
    s.columns.resize(std::max(s.columns.size(), std::size_t(terms.i_end() - terms.i_begin())));
    std::size_t filled = 0;
    for (std::int64_t i = terms.i_begin(); i < terms.i_end(); ++i) {
        const double xi = lattice.origin[0] + double(i) * lattice.spacing[0];
        LatticeColumn& column = s.columns[std::size_t(i - terms.i_begin())];
        std::tie(column.k0, column.k1) = within(grid.x, grid.width, xi, reach[0]);
        column.at = filled;
        if (column.k0 >= column.k1) continue;
        const std::size_t n = std::size_t(column.k1 - column.k0), columns = round_up(n, lrp_raster::padding) + lrp_raster::padding;
        filled += columns;
        s.dx.resize(std::max(s.dx.size(), filled));
        s.rx2.resize(std::max(s.rx2.size(), filled));
        for (std::size_t k = 0; k < columns; ++k) {
            const double x = k < n ? grid.x[std::size_t(column.k0) + k] : 0;
            // sum_windows takes the 3×3 points around the nearest one, exactly: a column whose
            // nearest lattice column is farther gets weight 0 (as does the padding).
            if (k < n && std::abs(lattice.nearest(0, x) - i) <= 1) {
                const float dx = float(x - xi);
                const float rx = dx * lattice.inverse_spacing[0];
                s.dx[column.at + k] = dx, s.rx2[column.at + k] = rx * rx;
            } else {
                s.dx[column.at + k] = 0, s.rx2[column.at + k] = 2 * extent;
            }
        }
    }

    // Lattice rows, then columns, in sum_windows' order (j, then i, ascending): every pixel adds
    // its windows in the order eval() does.
    for (std::int64_t j = terms.j_begin(); j < terms.j_end(); ++j) {
        const double yj = lattice.origin[1] + double(j) * lattice.spacing[1];
        const auto [r0, r1] = within(grid.y, grid.height, yj, reach[1]);
        if (r0 >= r1) continue;
        for (std::int64_t i = terms.i_begin(); i < terms.i_end(); ++i) {
            const double xi = lattice.origin[0] + double(i) * lattice.spacing[0];
            const LatticeColumn& column = s.columns[std::size_t(i - terms.i_begin())];
            const int k0 = column.k0, k1 = column.k1;
            if (k0 >= k1) continue;
            // The column tables hold the window's box of columns; each row reads its chord.
            const std::size_t n = std::size_t(k1 - k0), columns = round_up(n, lrp_raster::padding) + lrp_raster::padding;
            const float* const dx = s.dx.data() + column.at;
            const float* const rx2 = s.rx2.data() + column.at;
            lrp_raster::WindowRow row;
            row.layers = count;
            LrpTermView views[lrp_raster::max_layers];
            for (int l = 0; l < count; ++l) {
                const LrpTermView& view = views[l] = layers[l].terms->at(i, j);
                LayerScratch& buffers = s.layer[l];
                const std::size_t table = columns * std::size_t(view.live);
                buffers.sine.resize(std::max(buffers.sine.size(), table));
                buffers.cosine.resize(std::max(buffers.cosine.size(), table));
                for (int t = 0; t < view.live; ++t)
                    lrp_raster::sincos_of_products(view.fx()[t], dx, n, buffers.sine.data() + std::size_t(t) * columns,
                                                   buffers.cosine.data() + std::size_t(t) * columns);
                buffers.p.resize(std::max(buffers.p.size(), 3 * lrp_raster::factor_plane(view.live)));
                buffers.q.resize(std::max(buffers.q.size(), 3 * lrp_raster::factor_plane(view.live)));
                lrp_raster::WindowTerms& layer = row.layer[l];
                layer.p = buffers.p.data(), layer.q = buffers.q.data(), layer.terms = view.live;
                layer.channels = layers[l].noise->channels(), layer.stride = columns;
            }
            for (int r = r0; r < r1; ++r) {
                const float dy = float(grid.y[r] - yj);
                const float ry = dy * lattice.inverse_spacing[1];
                if (!(ry * ry < extent)) continue;                        // every weight of the row is 0
                if (std::abs(lattice.nearest(1, grid.y[r]) - j) > 1) continue;  // not among the row's 3×3
                // The row's chord of the window, rx² + ry² < 2.25 (margins for float rounding),
                // where the box is wide enough for the search to pay.
                int c0 = 0, c1 = k1 - k0;
                if (n > 2 * lrp_raster::padding) {
                    const double half = lattice.spacing[0] * std::sqrt(double(extent) - double(ry * ry) + 1e-6) * 1.0001;
                    std::tie(c0, c1) = within(grid.x + k0, k1 - k0, xi, half);
                    if (c0 >= c1) continue;
                }
                const std::size_t at = std::size_t(r) * row_stride + std::size_t(k0 + c0);
                for (int l = 0; l < count; ++l) {
                    const LrpTermView& view = views[l];
                    LayerScratch& buffers = s.layer[l];
                    const float* const re[3] = {view.re(0), view.re(1), view.re(2)};
                    const float* const im[3] = {view.im(0), view.im(1), view.im(2)};
                    lrp_raster::row_factors(dy, view.fy(), re, im, view.live, buffers.p.data(), buffers.q.data());
                    lrp_raster::WindowTerms& layer = row.layer[l];
                    layer.cosine = buffers.cosine.data() + c0, layer.sine = buffers.sine.data() + c0;
                    for (int c = 0; c < 3; ++c) layer.sum[c] = buffers.sum[c].data() + at;
                }
                row.rx2 = rx2 + c0, row.ry2 = ry * ry, row.count = std::size_t(c1 - c0);
                row.weight = s.weight.data() + at, row.weight_squared = s.weight_squared.data() + at;
                lrp_raster::accumulate_window_row(row);
            }
        }
    }
    for (int l = 0; l < count; ++l) {
        const float* const sums[3] = {s.layer[l].sum[0].data(), s.layer[l].sum[1].data(), s.layer[l].sum[2].data()};
        lrp_raster::normalise(sums, s.weight.data(), s.weight_squared.data(), row_stride, std::size_t(grid.width), grid.height,
                              kernel_normalisation(noise.normalisation()), layers[l].add, layers[l].out);
    }
}

}  // namespace stochtex
