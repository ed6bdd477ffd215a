// The covariance lookup's line quadrature (ColourMapFilter::lookup) with Highway
// (colour_map_kernels.cpp, dispatched to the CPU's best instruction set): first every node's
// texel offsets and fractions in each table, vectorised across the nodes, and a prefetch of all
// the rows they read (a line crosses ~one map row per node: requested together, the loads
// overlap instead of waiting one by one); then node by node the bilinear fetches on RGB vectors
// of four floats (one load per texel; a gather per channel measured slower), summed in node order.
//
// Both passes perform the IEEE operations of ColourMapFilter::Packed::fetch and of the sum, in
// their order (no fused multiply-add: the core builds with -ffp-contract=off), so the values are
// the scalar code's bits on every target (RasterPaths.TilingGivesTheSameBitsOnEveryInstructionSet).
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
    const double* node;  ///< t_k
    const double* weight;  ///< w_k (summed as float(w_k) · colour_k)
    int count;           ///< ≤ max_nodes
};
constexpr int max_nodes = 64;

/// rgb = Σ_k float(w_k) · S_k in node order, S_k the tables' blended bilinear fetch at node k.
void line_sum(const LineNodes& line, float* rgb);

}  // namespace stochtex::colour_map_kernels
