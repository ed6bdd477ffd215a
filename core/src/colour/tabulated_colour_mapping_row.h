// TabulatedColourMapping's table lookup over a row of values, vectorised with Highway
// (tabulated_colour_mapping_row.cpp, dispatched to the CPU's best instruction set). Lane by
// lane the IEEE operations of TabulatedColourMapping::interpolate, in its order (no fused
// multiply-add), so every target gives the scalar lookup's bits.
#pragma once

#include <cstddef>

namespace stochtex::tabulated_row {

struct ChannelTable {
    const float* values;  ///< [row · columns + column]
    double z0, inverse_step;
    int columns, rows;
};

/// y[i] = the table's bilinear value at (z[i], sigma[i]), i < count; sigma[i] ≥ 0 (lanes that
/// the caller answers otherwise — σ outside the table — read valid entries and are overwritten).
void interpolate(const ChannelTable& table, const double* z, const double* sigma, std::size_t count, double* y);

}  // namespace stochtex::tabulated_row
