// The covariance lookup's line quadrature (ColourMapFilter::lookup) with Highway
// (colour_map_kernels.cpp, dispatched to the CPU's best instruction set), in single precision:
// first every node's texel offsets in each table and its four bilinear corner weights (node
// weight × level-blend weight × bilinear fractions), vectorised across the nodes; then node by
// node the corners on RGB vectors of four floats (one load per texel; a gather per channel
// measured slower), summed in node order. (A prefetch of every row the nodes read paid while
// lines had up to 63 nodes; with at most 31 it cost 4–9 %.)
//
// Lane-wise IEEE operations only, in a fixed order (no fused multiply-add: the core builds with
// -ffp-contract=off), so the values are the same bits on every target
// (RasterPaths.TilingGivesTheSameBitsOnEveryInstructionSet).
#pragma once

#include <cstddef>
#include <cstdint>

namespace stochtex::colour_map_kernels {

/// One blurred table of a fractional level pair (ColourMapFilter::Packed::Table).
struct Table {
    const float* rgb;     ///< texel (x, y) at rgb + y · stride + 3 x
    std::size_t stride;   ///< floats per row
    int width, height, last_x0, last_y0;
    float weight;         ///< its level-blend weight
};

/// The nodes a + t_k · step_a, b + t_k · step_b (clamped to [0, 1]) of a line.
struct LineNodes {
    const Table* tables;
    int table_count;     ///< 1–4
    double a, b, step_a, step_b;
    const float* node;   ///< t_k, readable up to count + node_padding
    const float* weight;  ///< w_k, readable up to count + node_padding
    int count;           ///< ≤ max_nodes
};
constexpr int max_nodes = 64;
/// Entries readable past the last node (a whole vector of floats on any target).
constexpr int node_padding = 16;

/// rgb = Σ_k Σ_m Σ_corners c · texel in node order, c = float(w_k) · weight_m · the bilinear
/// weight of the corner at node k in table m.
void line_sum(const LineNodes& line, float* rgb);

}  // namespace stochtex::colour_map_kernels
