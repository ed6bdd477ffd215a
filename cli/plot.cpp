#include "plot.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stex_cli {

using stochtex::Image;

namespace {

void put(Image& image, int x, int y, const std::array<float, 3>& colour)
{
    if (x < 0 || y < 0 || x >= image.width || y >= image.height) return;
    for (int c = 0; c < 3; ++c) image.at(x, y, c) = colour[c];
}

void line(Image& image, double x0, double y0, double x1, double y1, const std::array<float, 3>& colour)
{
    const int steps = int(std::max(std::abs(x1 - x0), std::abs(y1 - y0))) + 1;
    for (int i = 0; i <= steps; ++i) {
        const double t = double(i) / steps;
        const int x = int(std::lround(x0 + t * (x1 - x0))), y = int(std::lround(y0 + t * (y1 - y0)));
        put(image, x, y, colour);
        put(image, x, y + 1, colour);  // two pixels thick: readable when the figure is scaled down
    }
}

}  // namespace

Image plot_panel(int width, int height, const std::vector<Curve>& curves, bool log_x, bool log_y)
{
    Image panel(width, height, 3);
    std::fill(panel.pixels.begin(), panel.pixels.end(), 0.9f);
    auto tx = [&](double v) { return log_x ? std::log10(std::max(v, 1e-30)) : v; };
    auto ty = [&](double v) { return log_y ? std::log10(std::max(v, 1e-30)) : v; };
    double x_lo = std::numeric_limits<double>::max(), x_hi = -x_lo, y_lo = x_lo, y_hi = -x_lo;
    for (const Curve& curve : curves)
        for (std::size_t i = 0; i < curve.x.size(); ++i) {
            x_lo = std::min(x_lo, tx(curve.x[i]));
            x_hi = std::max(x_hi, tx(curve.x[i]));
            y_lo = std::min(y_lo, ty(curve.y[i]));
            y_hi = std::max(y_hi, ty(curve.y[i]));
        }
    const int margin = 8;
    const std::array<float, 3> frame{0.3f, 0.3f, 0.3f};
    line(panel, margin, margin, width - margin, margin, frame);
    line(panel, margin, height - margin, width - margin, height - margin, frame);
    line(panel, margin, margin, margin, height - margin, frame);
    line(panel, width - margin, margin, width - margin, height - margin, frame);
    if (!(x_hi > x_lo) || !(y_hi > y_lo)) return panel;
    auto px = [&](double v) { return margin + (tx(v) - x_lo) / (x_hi - x_lo) * (width - 2 * margin); };
    auto py = [&](double v) { return height - margin - (ty(v) - y_lo) / (y_hi - y_lo) * (height - 2 * margin); };
    for (const Curve& curve : curves)
        for (std::size_t i = 1; i < curve.x.size(); ++i)
            line(panel, px(curve.x[i - 1]), py(curve.y[i - 1]), px(curve.x[i]), py(curve.y[i]), curve.colour);
    return panel;
}

Image heat_map_panel(const std::vector<double>& values, int grid, int size, double lo, double hi)
{
    // sRGB control points of matplotlib's "inferno" (perceptually uniform, legible in grey too),
    // decoded to linear: the figure is written through the sRGB encoding like every image.
    static const std::array<std::array<float, 3>, 5> stops = [] {
        const int srgb[5][3] = {{0, 0, 4}, {87, 16, 110}, {188, 55, 84}, {249, 142, 9}, {252, 255, 164}};
        std::array<std::array<float, 3>, 5> linear{};
        for (int s = 0; s < 5; ++s)
            for (int c = 0; c < 3; ++c) {
                const double v = srgb[s][c] / 255.0;
                linear[s][c] = float(v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4));
            }
        return linear;
    }();
    Image panel(size, size, 3);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const double v = values[std::size_t(y * grid / size) * grid + std::size_t(x * grid / size)];
            const double t = std::clamp(hi > lo ? (v - lo) / (hi - lo) : 0.0, 0.0, 1.0) * (stops.size() - 1);
            const std::size_t s = std::min(std::size_t(t), stops.size() - 2);
            const double u = t - double(s);
            for (int c = 0; c < 3; ++c) panel.at(x, y, c) = float(stops[s][c] * (1 - u) + stops[s + 1][c] * u);
        }
    return panel;
}

void paste(Image& target, const Image& source, int x, int y)
{
    for (int j = 0; j < source.height; ++j)
        for (int i = 0; i < source.width; ++i)
            for (int c = 0; c < 3; ++c)
                if (x + i < target.width && y + j < target.height) target.at(x + i, y + j, c) = source.at(i, j, c);
}

}  // namespace stex_cli
