#include "blending/tiling_grid.h"

#include "numerics/exact_rounding.h"
#include "numerics/random.h"

#include <stochtex/error.h>

#include <algorithm>
#include <cmath>

namespace stochtex {

namespace {
const double sqrt3 = std::sqrt(3.0);

std::int64_t floor_mod(std::int64_t a, std::int64_t n) { return ((a % n) + n) % n; }
}  // namespace

TilingGrid::TilingGrid(std::uint32_t seed, double edge, double contrast)
    : seed_(seed), edge_{edge, edge}, inverse_edge_{1 / edge, 1 / edge}, contrast_(contrast)
{
    if (!(edge > 0) || !std::isfinite(edge)) throw Error("tiling grid: the triangle edge must be positive");
    if (!(contrast >= 1) || !std::isfinite(contrast)) throw Error("tiling grid: the blend contrast must be ≥ 1 and finite");
}

TilingGrid::TilingGrid(std::uint32_t seed, double edge, const std::array<double, 2>& period, double contrast)
    : TilingGrid(seed, edge, contrast)
{
    for (double p : period)
        if (!(p > 0) || !std::isfinite(p)) throw Error("tiling grid: the period must be positive and finite");
    // Along x the lattice repeats every edge; along y every √3 edges (two rows of triangles).
    cells_x_ = std::max<std::int64_t>(1, std::llround(period[0] / edge));
    repeats_y_ = std::max<std::int64_t>(1, std::llround(period[1] / (sqrt3 * edge)));
    edge_ = {period[0] / double(cells_x_), period[1] / (sqrt3 * double(repeats_y_))};
    inverse_edge_ = {1 / edge_[0], 1 / edge_[1]};
}

void TilingGrid::draw(std::int64_t i, std::int64_t j, TileVertex& vertex) const
{
    vertex.period_shift = {0, 0};
    if (cells_x_ > 0) {
        // The periodic lattice's representative of (i, j): j in [0, 2m), then i in [0, n);
        // (i, j) = (I + a n − k m, J + 2 k m) lies a whole periods along x and k along y away.
        const std::int64_t rows = 2 * repeats_y_;
        const std::int64_t row = floor_mod(j, rows);
        const std::int64_t k = (j - row) / rows;
        const std::int64_t shifted = i + k * repeats_y_;
        const std::int64_t column = floor_mod(shifted, cells_x_);
        const std::int64_t a = (shifted - column) / cells_x_;
        vertex.period_shift = {double(a) * (edge_[0] * double(cells_x_)), double(k) * (edge_[1] * sqrt3 * double(repeats_y_))};
        i = column;
        j = row;
    }
    SplitMix64 rng(mix_seed(seed_, std::uint64_t(i), std::uint64_t(j)));
    const double ox = rng.uniform();
    vertex.offset = {ox, rng.uniform()};
}

std::array<double, 2> tile_position(const TileVertex& vertex, double x, double y, int width, int height)
{
    const double shift_x = round_exact(vertex.offset[0] * width - (vertex.centre[0] - vertex.period_shift[0]));
    const double shift_y = round_exact(vertex.offset[1] * height - (vertex.centre[1] - vertex.period_shift[1]));
    return {x - vertex.period_shift[0] + shift_x, y - vertex.period_shift[1] + shift_y};
}

template <class Draw>
TileBlend TilingGrid::blend_with(double x, double y, const Draw& draw) const
{
    // Skew to the lattice basis (1, 0), (½, √3/2): cell = floor, f = barycentric fractions.
    const double gx = x / edge_[0], gy = y / edge_[1];
    const double sy = 2 * gy / sqrt3, sx = gx - 0.5 * sy;
    const double cx = floor_exact(sx), cy = floor_exact(sy);
    const double fx = sx - cx, fy = sy - cy;
    const std::int64_t i = std::int64_t(cx), j = std::int64_t(cy);
    std::array<std::int64_t, 6> vertices;
    std::array<double, 3> b;
    if (fx + fy < 1) {
        vertices = {i, j, i + 1, j, i, j + 1};
        b = {1 - fx - fy, fx, fy};
    } else {
        vertices = {i + 1, j + 1, i + 1, j, i, j + 1};
        b = {fx + fy - 1, 1 - fy, 1 - fx};
    }
    sharpen_blend_weights(b, contrast_);
    TileBlend result;
    for (int k = 0; k < 3; ++k) {
        const std::int64_t vi = vertices[2 * k], vj = vertices[2 * k + 1];
        result[k].weight = b[k];
        result[k].centre = {edge_[0] * (double(vi) + 0.5 * double(vj)), edge_[1] * (0.5 * sqrt3 * double(vj))};
        draw(vi, vj, result[k]);
    }
    return result;
}

TileVertex TilingGrid::vertex(std::int64_t i, std::int64_t j) const
{
    TileVertex v;
    v.weight = 0;
    v.centre = {edge_[0] * (double(i) + 0.5 * double(j)), edge_[1] * (0.5 * sqrt3 * double(j))};
    draw(i, j, v);
    return v;
}

TileBlend TilingGrid::blend(double x, double y) const
{
    return blend_with(x, y, [this](std::int64_t i, std::int64_t j, TileVertex& vertex) { draw(i, j, vertex); });
}

TileBlend TilingGrid::blend(double x, double y, TileCache& cache) const
{
    return blend_with(x, y, [this, &cache](std::int64_t i, std::int64_t j, TileVertex& vertex) {
        // Rows of vertices differ by j: 8 per row, 8 rows, so a raster row's band fits.
        TileCache::Slot& slot = cache.slots_[std::size_t((std::uint64_t(i) & 7) | ((std::uint64_t(j) & 7) << 3))];
        if (slot.i != i || slot.j != j) {
            draw(i, j, vertex);
            slot = {i, j, vertex.offset, vertex.period_shift};
            return;
        }
        vertex.offset = slot.offset;
        vertex.period_shift = slot.period_shift;
    });
}

}  // namespace stochtex
