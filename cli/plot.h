// Minimal raster plots for `stex compare`: panels with curves drawn into an RGB image.
#pragma once

#include <stochtex/image.h>

#include <array>
#include <vector>

namespace stex_cli {

struct Curve {
    std::vector<double> x, y;
    std::array<float, 3> colour;  // linear RGB
};

/// Draws curves into a w×h panel with a light background and a frame; axes are the data's
/// bounding box (log10 of x and/or y when requested).
stochtex::Image plot_panel(int width, int height, const std::vector<Curve>& curves, bool log_x, bool log_y);

/// A grid×grid array of values (rows top to bottom) as a size×size false-colour panel (an
/// inferno-like map: dark for lo and below, pale yellow for hi and above), nearest-neighbour scaled.
stochtex::Image heat_map_panel(const std::vector<double>& values, int grid, int size, double lo, double hi);

/// Copies `source` into `target` with its top-left corner at (x, y) (clipped).
void paste(stochtex::Image& target, const stochtex::Image& source, int x, int y);

}  // namespace stex_cli
