// The triangle grid of tiling and blending (paper 002 §1; Deliot–Heitz 2019, notes P2.1).
//
// The plane is covered by hexagonal tiles centred on the vertices of a grid of equilateral
// triangles. A point lies in one triangle; its three vertices' tiles overlap there and are
// blended with the weights w = B / ‖B‖₂ (B the barycentric coordinates), so Σ w_i² = 1 and the
// blend of three uncorrelated tiles keeps the exemplar's variance everywhere (eq. 1). Each
// vertex draws a random offset into the exemplar from a hash of its lattice index.
//
// Blend contrast γ ≥ 1 (Mikkelsen 2022, Burley 2019): w = B^γ / ‖B^γ‖₂. The tile whose vertex is
// nearest takes more of the blend, so fewer tiles show through each other (ghosts) where three
// overlap; Σ w_i² = 1 still holds, so the blend still keeps the exemplar's variance wherever the
// tiles are uncorrelated. γ = 1 (the default) is Heitz–Neyret's and Deliot–Heitz's blend.
//
// Units: exemplar pixels. A tile's content is addressed relative to its vertex,
// exemplar(p − centre + offset) (tiling_noise.h rounds the shift to whole pixels): then a
// periodic lattice (below) makes the whole texture periodic, whatever the exemplar's size, since
// vertices one period apart share their offset (and know the periods between them).
//
// Periodic form: the lattice is stretched (per axis, the least possible) so that the period
// holds a whole number n of cells along x and m of the lattice's vertical repeats (√3 edges,
// two rows) along y; vertex (i, j) is then identified with (i + n, j) and (i − m, j + 2m).
#pragma once

#include <array>
#include <climits>
#include <cmath>
#include <cstdint>

namespace stochtex {

struct TileVertex {
    double weight;                 ///< w_i: Σ w_i² = 1 over the three vertices
    std::array<double, 2> centre;  ///< the vertex, exemplar pixels
    std::array<double, 2> offset;  ///< random, in [0, 1)² exemplar widths and heights
    /// Whole periods between this vertex and its representative in the periodic lattice (the
    /// vertex that drew the offset; 0 when not periodic), exemplar pixels.
    std::array<double, 2> period_shift;
};
using TileBlend = std::array<TileVertex, 3>;

/// Where the point (x, y) reads a periodic width × height exemplar in `vertex`'s tile (exemplar
/// pixels; the caller wraps). The tile's shift is a whole number of pixels: a raster at the
/// exemplar's pixel scale then reads exemplar pixels, not blends of four (which would lose
/// fine-scale variance); it is rounded at the lattice representative, so periods stay exact.
/// Every tiled model (the tiling noise, the unbounded ptm) addresses its tiles through this.
std::array<double, 2> tile_position(const TileVertex& vertex, double x, double y, int width, int height);

/// Remembers the offsets the grid drew for recently used vertices (a direct-mapped table of
/// 64): a raster's neighbouring pixels and taps share their triangles' vertices, and drawing a
/// vertex (three SplitMix64 rounds) costs more than the rest of its blend. Owned by one thread
/// (a raster row, a batch); the values are the ones draw() gives, so caching changes no bit.
class TileCache {
public:
    TileCache() { for (Slot& slot : slots_) slot.i = slot.j = INT64_MIN; }

private:
    friend class TilingGrid;
    struct Slot {
        std::int64_t i, j;
        std::array<double, 2> offset, period_shift;
    };
    std::array<Slot, 64> slots_;
};

/// Sharpens three blend weights (or barycentrics) in place: w_i^contrast, renormalised so that
/// Σ w_i² = 1. contrast 1 only normalises. Every path that blends tiles (the grid's blend(), the
/// tiling raster's packed weights) goes through this one function. Inline, with whole contrasts
/// by repeated squaring: the raster calls it per position and tap, where std::pow halved the
/// render's speed.
inline void sharpen_blend_weights(std::array<double, 3>& w, double contrast)
{
    // γ = 1 skips the power so that the default blend keeps its exact operations (and bits).
    if (contrast != 1) {
        const bool whole = contrast <= 64 && contrast == std::floor(contrast);
        for (double& v : w) {
            if (!whole) {
                v = std::pow(v, contrast);
                continue;
            }
            double power = 1, base = v;
            for (int e = int(contrast); e > 0; e >>= 1, base *= base)
                if (e & 1) power *= base;
            v = power;
        }
    }
    const double norm = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    for (double& v : w) v /= norm;
}

class TilingGrid {
public:
    /// edge: the triangles' edge in exemplar pixels; contrast: the blend contrast γ ≥ 1 (above).
    TilingGrid(std::uint32_t seed, double edge, double contrast = 1);
    /// Periodic with `period` exemplar pixels per axis (positive, finite).
    TilingGrid(std::uint32_t seed, double edge, const std::array<double, 2>& period, double contrast = 1);

    TileBlend blend(double x, double y) const;
    /// The same blend, the vertices' offsets looked up in (and added to) `cache`.
    TileBlend blend(double x, double y, TileCache& cache) const;

    /// Vertex (i, j) as blend() gives it (centre, offset, period shift; weight 0).
    TileVertex vertex(std::int64_t i, std::int64_t j) const;
    /// The edges actually used along x and y (differ from `edge` only in the periodic form).
    const std::array<double, 2>& edges() const { return edge_; }
    /// 1 / edges(): the tiling raster's triangle geometry multiplies by them
    /// (models/tiling/tiling_raster_kernels.h).
    const std::array<double, 2>& inverse_edges() const { return inverse_edge_; }
    /// The seed of the vertices' offsets (for re-implementations: tiling_shader_data.h).
    std::uint32_t seed() const { return seed_; }
    /// The blend contrast γ (1: the variance-preserving blend of the papers, unsharpened).
    double contrast() const { return contrast_; }

private:
    /// The offset and the period shift of vertex (i, j).
    void draw(std::int64_t i, std::int64_t j, TileVertex& vertex) const;
    template <class Draw>
    TileBlend blend_with(double x, double y, const Draw& draw) const;

    std::uint32_t seed_;
    std::array<double, 2> edge_;
    std::array<double, 2> inverse_edge_;  // 1 / edge_
    double contrast_ = 1;
    std::int64_t cells_x_ = 0, repeats_y_ = 0;  // periodic lattice (n, m); 0: not periodic
};

}  // namespace stochtex
