// Minimal raster plots for `stex compare`: labelled charts, bars and heat maps drawn into RGB
// images, text in the 5×7 bitmap font (bitmap_font.h).
#pragma once

#include <stochtex/image.h>

#include <array>
#include <string>
#include <vector>

namespace stex_cli {

struct Curve {
    std::vector<double> x, y;
    std::array<float, 3> colour;  // linear RGB
    std::string name;             // in the legend
};

struct Axis {
    std::string label;  // with its unit, e.g. "frequency (cycles/px)"
    bool log = false;   // log10 scale, ticks at 1, 2, 5 × 10^k
};

/// A w×h chart: the title on top, the curves in a framed plot area whose axes span the data's
/// bounding box, with ticks, tick values and axis labels, and a legend of the curves' names.
stochtex::Image chart_panel(int width, int height, const std::string& title, const Axis& x, const Axis& y,
                            const std::vector<Curve>& curves);

struct Bar {
    std::string label;
    double value;  // NaN draws "n/a"
    std::array<float, 3> colour;
};

/// Horizontal bars from 0, labelled on the left and valued on the right, with a dashed
/// vertical marker at `marker` labelled `marker_label` (e.g. a distance's unit).
stochtex::Image bar_panel(int width, int height, const std::string& title, const std::vector<Bar>& bars,
                          double marker, const std::string& marker_label);

/// A grid×grid array of values (rows top to bottom) as a size×size false-colour panel (an
/// inferno-like map: dark for lo and below, pale yellow for hi and above), nearest-neighbour scaled.
stochtex::Image heat_map_panel(const std::vector<double>& values, int grid, int size, double lo, double hi);
/// The heat map's colour scale from lo (bottom) to hi (top) as a w×h strip.
stochtex::Image heat_map_scale(int width, int height, double lo, double hi);

/// Copies `source` into `target` with its top-left corner at (x, y) (clipped).
void paste(stochtex::Image& target, const stochtex::Image& source, int x, int y);

/// `source` enlarged by an integer factor (nearest neighbour): small photos stay visible.
stochtex::Image enlarged(const stochtex::Image& source, int factor);

}  // namespace stex_cli
