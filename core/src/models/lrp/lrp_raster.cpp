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

/// One thread's buffers, reused by every region the thread renders.
struct Scratch {
    std::vector<float> sum[3], weight, weight_squared;  // per grid row, padded rows
    std::vector<float> dx, rx2;                         // every lattice column's box of columns, back to back
    std::vector<LatticeColumn> columns;                 // per lattice column i
    std::vector<float> sine, cosine;                    // column factors, [term][column]
    std::vector<float> p, q;                            // row factors, [term][channel]
};

Scratch& scratch()
{
    thread_local Scratch s;
    return s;
}

std::size_t round_up(std::size_t n, std::size_t multiple) { return (n + multiple - 1) / multiple * multiple; }

void reset(std::vector<float>& buffer, std::size_t size)
{
    buffer.resize(std::max(buffer.size(), size));
    std::fill(buffer.begin(), buffer.begin() + std::ptrdiff_t(size), 0.0f);
}

/// [begin, end) of the positions within (centre − reach, centre + reach).
std::pair<int, int> within(const double* position, int count, double centre, double reach)
{
    const double* begin = std::upper_bound(position, position + count, centre - reach);
    const double* end = std::lower_bound(begin, position + count, centre + reach);
    return {int(begin - position), int(end - position)};
}

}  // namespace

void lrp_raster_stratum(const LrpStratumNoise& noise, const LrpTermCache& terms, const LrpRasterGrid& grid,
                        float* const out[3])
{
    Scratch& s = scratch();
    const LrpLattice& lattice = noise.lattice();
    const std::size_t row_stride = round_up(std::size_t(grid.width), lrp_raster::padding) + lrp_raster::padding;
    const std::size_t cells = row_stride * std::size_t(grid.height);
    for (auto& channel : s.sum) reset(channel, cells);
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
            const LrpTermView view = terms.at(i, j);
            // The column tables hold the window's box of columns; each row reads its chord.
            const std::size_t n = std::size_t(k1 - k0), columns = round_up(n, lrp_raster::padding) + lrp_raster::padding;
            const float* const dx = s.dx.data() + column.at;
            const float* const rx2 = s.rx2.data() + column.at;
            const std::size_t table = columns * std::size_t(view.live);
            s.sine.resize(std::max(s.sine.size(), table));
            s.cosine.resize(std::max(s.cosine.size(), table));
            for (int t = 0; t < view.live; ++t)
                lrp_raster::sincos_of_products(view.fx()[t], dx, n, s.sine.data() + std::size_t(t) * columns,
                                               s.cosine.data() + std::size_t(t) * columns);
            s.p.resize(std::max(s.p.size(), 3 * lrp_raster::factor_plane(view.live)));
            s.q.resize(std::max(s.q.size(), 3 * lrp_raster::factor_plane(view.live)));
            const float* const re[3] = {view.re(0), view.re(1), view.re(2)};
            const float* const im[3] = {view.im(0), view.im(1), view.im(2)};
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
                lrp_raster::row_factors(dy, view.fy(), re, im, view.live, s.p.data(), s.q.data());
                lrp_raster::WindowRow row;
                row.cosine = s.cosine.data() + c0, row.sine = s.sine.data() + c0, row.stride = columns;
                row.p = s.p.data(), row.q = s.q.data(), row.terms = view.live;
                row.rx2 = rx2 + c0, row.ry2 = ry * ry, row.count = std::size_t(c1 - c0);
                const std::size_t at = std::size_t(r) * row_stride + std::size_t(k0 + c0);
                for (int c = 0; c < 3; ++c) row.sum[c] = s.sum[c].data() + at;
                row.weight = s.weight.data() + at, row.weight_squared = s.weight_squared.data() + at;
                lrp_raster::accumulate_window_row(row);
            }
        }
    }
    // sum_windows' normalisation.
    const LrpNormalisation normalisation = noise.normalisation();
    for (int r = 0; r < grid.height; ++r)
        for (int k = 0; k < grid.width; ++k) {
            const std::size_t at = std::size_t(r) * row_stride + std::size_t(k);
            const float scale = normalisation == LrpNormalisation::variance    ? 1.0f / std::sqrt(s.weight_squared[at])
                                : normalisation == LrpNormalisation::partition ? 1.0f / s.weight[at]
                                                                               : 1.0f;
            const std::size_t pixel = std::size_t(r) * std::size_t(grid.width) + std::size_t(k);
            for (int c = 0; c < 3; ++c) out[c][pixel] = s.sum[c][at] * scale;
        }
}

}  // namespace stochtex
