// The tiling raster's address stage, vectorised across pixels with Highway
// (tiling_raster_kernels.cpp, dispatched to the best instruction set of the CPU at run time).
//
// For one tap of a row of pixels — tap positions x[i] on one line y (a tap's offset from its
// pixel is the footprint's, so a raster row's taps of one index share y) — it finds each
// position's triangle (the blend weights) and, for each of the triangle's three tiles, where
// the bilinear lookup reads the packed pyramid (two record offsets, the fractions). Lane by
// lane it performs the IEEE operations of the scalar expressions it documents (no fused
// multiply-add: the core builds with -ffp-contract=off), so every target gives the same bits
// and a pixel's values do not depend on the lane it falls in.
#pragma once

#include <cstddef>
#include <cstdint>

namespace stochtex::tiling_raster {

/// Vectors hold at most this many doubles on any target (AVX-512: 8): inputs are padded to it.
constexpr std::size_t max_lanes = 8;
/// Positions per pass of the address stage and the lookups: the stride of their buffers' fields.
constexpr std::size_t chunk = 64;

/// The second moments a packed record keeps (lane Channels + p holds moment (first[p], second[p])):
/// for 3 channels the variances only (what the colour output reads), for 1–2 all of them.
template <int Channels>
struct RecordPairs;
template <>
struct RecordPairs<1> {
    static constexpr int count = 1, first[1] = {0}, second[1] = {0};
};
template <>
struct RecordPairs<2> {
    static constexpr int count = 3, first[3] = {0, 0, 1}, second[3] = {0, 1, 1};
};
template <>
struct RecordPairs<3> {
    static constexpr int count = 3, first[3] = {0, 1, 2}, second[3] = {0, 1, 2};
};

/// A pyramid level's geometry for the address stage (PackedMomentPyramid::Level).
struct LevelGeometry {
    double scale_x, scale_y;          ///< texels per level-0 pixel
    double width, height;             ///< texels (powers of two)
    std::int32_t row;                 ///< records per row (width + 1)
};

/// Entries of a tap row's vertex tables for `columns` vertex columns: both vertex rows, padded
/// to whole vectors.
constexpr std::size_t vertex_entries(std::size_t columns) { return (2 * columns + max_lanes - 1) / max_lanes * max_lanes; }

/// One tap row. Triangle (TilingGrid::blend's geometry with reciprocals): sy = (y / edge_y) ·
/// 2/√3 and fy = sy − floor(sy) are the row's; per tap position x sx = x · (1/edge_x) − ½ sy,
/// cx = floor(sx), fx = sx − cx; below the diagonal (fx + fy < 1) the vertices are (cx, j),
/// (cx + 1, j), (cx, j + 1) with B = (1 − fx − fy, fx, fy), else (cx + 1, j + 1), (cx + 1, j),
/// (cx, j + 1) with B = (fx + fy − 1, 1 − fy, 1 − fx); w = B · (1 / √(B·B)).
/// Tile k reads the exemplar at (x + T_x, y + T_y), T the vertex's translation, read from the
/// vertex tables: entry c for vertex (i_min + c, j), entry columns + c for (i_min + c, j + 1).
/// Lookup (MomentPyramid::sample_level_linear's centres and wrap): lx = p · scale_x − ½,
/// x0 = floor(lx), fx = float(lx − x0), ix = x0 − width · floor(x0 / width), likewise y; the
/// records read are at (iy · row + ix) · 8 and ((iy + 1 mod height) · row + ix) · 8 floats.
/// The y side of a lookup (y + T_y, fy, iy, its row's offsets) depends on the vertex alone, y
/// being the row's: it is computed once per vertex entry, into the scratch tables, and read
/// by the lanes as the translations are (iy + 1 mod height as (iy + 1) & (height − 1)); the
/// offsets as iy · row · 8 + ix · 8 in int32, the same integers.
struct TapRow {
    const double* x;  ///< n pixel positions (n a multiple of max_lanes); the tap's are (x + a) + b
    std::size_t n;
    double a, b;      ///< the tap's offset along the footprint's axes (x components)
    double y, sy, fy, inverse_edge_x;
    double i_min;
    std::size_t columns;            ///< vertex columns: 2 · columns vertex entries
    const double* translation_x;    ///< vertex_entries(columns) entries (the padding any value)
    const double* translation_y;
    LevelGeometry lower, upper;
    bool has_upper;
    float* vertex_fy;               ///< scratch: 2 · vertex_entries(columns) floats
    std::int32_t* vertex_rows;      ///< scratch: 4 · vertex_entries(columns) offsets
};

/// The address stage's buffers, as TilingRaster::estimate_chunk lays them out: run r = 3 · tap +
/// tile holds `chunk` values per field, offsets at offsets + (offset_fields · r + f) · chunk,
/// fractions at fractions + (fraction_fields · r + f) · chunk. Per tile: at the lower (and upper)
/// level, the record offsets of the texel pair of rows iy and iy + 1, the fractions and their
/// complements 1 − f (in float, as the lookup uses them); the blend weight w (float) and w · w.
enum OffsetField { lower_row0, lower_row1, upper_row0, upper_row1, offset_fields };
enum FractionField { lower_fx, lower_fy, upper_fx, upper_fy, weight, lower_gx, lower_gy, upper_gx, upper_gy, weight_squared, fraction_fields };

/// Where the three tiles of a tap row read: the tap's runs (3 · tap + tile, tile 0–2), from
/// position 0; the upper level's fields are written when has_upper.
struct TileReads {
    std::int32_t* offsets;
    float* fractions;
};

void plan_tap_row(const TapRow& row, const TileReads& out);

/// The lookups and the mixture of `count` positions from plan_tap_row's reads (OffsetField,
/// FractionField).
/// Per position and tap, the three tiles' bilinear records (8 floats: lane-wise, in
/// vectors of up to 8), blended towards the upper level by t, are summed as w · (means + w ·
/// moments) · record (`means` 1 on the mean lanes, 0 on the moment lanes); the taps then
/// combine as MomentMixture::add with the plan's ratio, scatter and weight, the moments
/// divided by the weights' total at the end (one tap: its sum as it is).
struct TapSums {
    const float* lower;
    const float* upper;  ///< null: one level
    float t;
    int taps, channels;  ///< the record's moment lanes: RecordPairs<channels>
    const std::int32_t* offsets;
    const float* fractions;
    const float* ratio;
    const float* scatter;
    float weight, inverse_total;
};
void accumulate_taps(const TapSums& sums, std::size_t count, float* out);

/// The colour output's inputs from `count` packed 3-channel records (8 floats each: centred
/// means, then the variances), planar: z[c][i] = mean[c] + double(mean lane c), spread[c][i] =
/// √max(0, double(variance lane c)) — TilingTexture::colour()'s operations, lane-wise.
void colour_inputs(const float* packed, std::size_t count, const double* mean, double* const* z, double* const* spread);

}  // namespace stochtex::tiling_raster
