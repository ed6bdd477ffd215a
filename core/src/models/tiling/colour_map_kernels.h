// The covariance lookup's line quadrature (ColourMapFilter::lookup), vectorised across the
// nodes with Highway (colour_map_kernels.cpp, dispatched to the CPU's best instruction set).
//
// Every node's colour is computed lane by lane with the IEEE operations, in the order, of
// ColourMapFilter::Packed::fetch (no fused multiply-add: the core builds with
// -ffp-contract=off); the weighted sum over the nodes is then taken in node order, as lookup()
// did. So the values are the scalar code's bits on every target, and a node's colour does not
// depend on the lane it falls in.
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
