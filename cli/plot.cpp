#include "plot.h"

#include "bitmap_font.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace stex_cli {

using stochtex::Image;

namespace {

constexpr int kText = 2;  // font scale: 10×14-pixel glyphs, legible when the figure is viewed whole
constexpr int kLineHeight = (kGlyphHeight + 3) * kText;
const std::array<float, 3> kInk{0.0f, 0.0f, 0.0f}, kFrame{0.25f, 0.25f, 0.25f}, kGrid{0.72f, 0.72f, 0.72f};

void put(Image& image, int x, int y, const std::array<float, 3>& colour)
{
    if (x < 0 || y < 0 || x >= image.width || y >= image.height) return;
    for (int c = 0; c < 3; ++c) image.at(x, y, c) = colour[c];
}

void line(Image& image, double x0, double y0, double x1, double y1, const std::array<float, 3>& colour,
          int thickness = 2, int dash = 0)
{
    const int steps = int(std::max(std::abs(x1 - x0), std::abs(y1 - y0))) + 1;
    for (int i = 0; i <= steps; ++i) {
        if (dash > 0 && (i / dash) % 2) continue;
        const double t = double(i) / steps;
        const int x = int(std::lround(x0 + t * (x1 - x0))), y = int(std::lround(y0 + t * (y1 - y0)));
        for (int d = 0; d < thickness; ++d) put(image, x, y + d, colour);  // thick: readable scaled down
    }
}

Image blank(int width, int height)
{
    Image panel(width, height, 3);
    std::fill(panel.pixels.begin(), panel.pixels.end(), 1.0f);
    return panel;
}

std::string number(double v)
{
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%g", std::abs(v) < 1e-12 ? 0.0 : v);
    return buffer;
}

/// Tick positions (in the axis's own units, log10 for a log axis) over [lo, hi].
std::vector<double> ticks(double lo, double hi, bool log)
{
    std::vector<double> out;
    if (log) {
        const bool few_decades = hi - lo < 1.5;  // 1, 2, 5 labels would collide over more
        for (int k = int(std::floor(lo)); k <= int(std::ceil(hi)); ++k)
            for (double m : {1.0, 2.0, 5.0}) {
                if (m != 1 && !few_decades) continue;
                const double t = k + std::log10(m);
                if (t >= lo - 1e-9 && t <= hi + 1e-9) out.push_back(t);
            }
        return out;
    }
    const double raw = (hi - lo) / 5;
    const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
    const double step = magnitude * (raw / magnitude < 1.5 ? 1 : raw / magnitude < 3.5 ? 2 : raw / magnitude < 7.5 ? 5 : 10);
    for (double t = std::ceil(lo / step) * step; t <= hi + 1e-9 * step; t += step) out.push_back(t);
    return out;
}

}  // namespace

Image chart_panel(int width, int height, const std::string& title, const Axis& x_axis, const Axis& y_axis,
                  const std::vector<Curve>& curves)
{
    Image panel = blank(width, height);
    auto tx = [&](double v) { return x_axis.log ? std::log10(std::max(v, 1e-30)) : v; };
    auto ty = [&](double v) { return y_axis.log ? std::log10(std::max(v, 1e-30)) : v; };
    double x_lo = std::numeric_limits<double>::max(), x_hi = -x_lo, y_lo = x_lo, y_hi = -x_lo;
    for (const Curve& curve : curves)
        for (std::size_t i = 0; i < curve.x.size(); ++i) {
            if (!std::isfinite(tx(curve.x[i])) || !std::isfinite(ty(curve.y[i]))) continue;
            x_lo = std::min(x_lo, tx(curve.x[i]));
            x_hi = std::max(x_hi, tx(curve.x[i]));
            y_lo = std::min(y_lo, ty(curve.y[i]));
            y_hi = std::max(y_hi, ty(curve.y[i]));
        }
    draw_text(panel, (width - text_width(title, kText)) / 2, 4, title, kInk, kText);
    // Plot area: room for tick values (6 characters) and the turned y label on the left, tick
    // values and the x label below.
    const int left = 3 * kText + kGlyphHeight * kText + text_width("-00000", kText) + 6;
    const int right = width - 10, top = kLineHeight + 8, bottom = height - 2 * kLineHeight - 6;
    draw_text(panel, left + (right - left - text_width(x_axis.label, kText)) / 2, height - kLineHeight, x_axis.label,
              kInk, kText);
    draw_text_vertical(panel, 3 * kText, top + (bottom - top - text_width(y_axis.label, kText)) / 2, y_axis.label,
                       kInk, kText);
    if (x_hi > x_lo && y_hi > y_lo) {
        const double pad = 0.04 * (y_hi - y_lo);
        y_lo -= pad, y_hi += pad;
        auto px = [&](double v) { return left + (v - x_lo) / (x_hi - x_lo) * (right - left); };
        auto py = [&](double v) { return bottom - (v - y_lo) / (y_hi - y_lo) * (bottom - top); };
        for (double t : ticks(x_lo, x_hi, x_axis.log)) {
            line(panel, px(t), top, px(t), bottom, kGrid, 1);
            const std::string label = number(x_axis.log ? std::pow(10.0, t) : t);
            const int label_x = std::clamp(int(px(t)) - text_width(label, kText) / 2, 0, width - text_width(label, kText));
            draw_text(panel, label_x, bottom + 6, label, kInk, kText);
        }
        for (double t : ticks(y_lo, y_hi, y_axis.log)) {
            line(panel, left, py(t), right, py(t), kGrid, 1);
            const std::string label = number(y_axis.log ? std::pow(10.0, t) : t);
            draw_text(panel, left - 6 - text_width(label, kText), int(py(t)) - kGlyphHeight * kText / 2, label, kInk,
                      kText);
        }
        for (const Curve& curve : curves)
            for (std::size_t i = 1; i < curve.x.size(); ++i)
                line(panel, px(tx(curve.x[i - 1])), py(ty(curve.y[i - 1])), px(tx(curve.x[i])), py(ty(curve.y[i])),
                     curve.colour, 3);
    }
    line(panel, left, top, right, top, kFrame, 1);
    line(panel, left, bottom, right, bottom, kFrame, 1);
    line(panel, left, top, left, bottom, kFrame, 1);
    line(panel, right, top, right, bottom, kFrame, 1);
    // Legend, top right inside the plot area: a short stroke of each colour and its name.
    int legend_y = top + 8;
    for (const Curve& curve : curves) {
        const int name_x = right - 10 - text_width(curve.name, kText);
        for (int j = -2; j < kGlyphHeight * kText + 2; ++j)
            for (int i = name_x - 40; i < right - 4; ++i) put(panel, i, legend_y + j, {1.0f, 1.0f, 1.0f});
        line(panel, name_x - 34, legend_y + kGlyphHeight * kText / 2 - 1, name_x - 8,
             legend_y + kGlyphHeight * kText / 2 - 1, curve.colour, 4);
        draw_text(panel, name_x, legend_y, curve.name, kInk, kText);
        legend_y += kLineHeight + 4;
    }
    return panel;
}

Image bar_panel(int width, int height, const std::string& title, const std::vector<Bar>& bars, double marker,
                const std::string& marker_label)
{
    Image panel = blank(width, height);
    draw_text(panel, (width - text_width(title, kText)) / 2, 4, title, kInk, kText);
    std::size_t longest = 0;
    for (const Bar& bar : bars) longest = std::max(longest, bar.label.size());
    const int left = 8 + int(longest + 1) * (kGlyphWidth + 1) * kText, right = width - text_width(" 0.000", kText) - 10;
    const int top = kLineHeight + 8 + kLineHeight, bottom = height - 6;
    double top_value = marker;
    for (const Bar& bar : bars)
        if (std::isfinite(bar.value)) top_value = std::max(top_value, bar.value);
    top_value *= 1.05;
    auto px = [&](double v) { return left + std::clamp(v / top_value, 0.0, 1.0) * (right - left); };
    const int row = std::max(1, (bottom - top) / int(std::max<std::size_t>(1, bars.size())));
    for (std::size_t b = 0; b < bars.size(); ++b) {
        const int y = top + int(b) * row, text_y = y + (row - kGlyphHeight * kText) / 2;
        draw_text(panel, 8, text_y, bars[b].label, kInk, kText);
        char value[32];
        if (std::isfinite(bars[b].value)) std::snprintf(value, sizeof value, "%.3f", bars[b].value);
        else std::snprintf(value, sizeof value, "n/a");
        if (std::isfinite(bars[b].value))
            for (int j = y + row / 6; j < y + row - row / 6; ++j)
                for (int i = left; i < int(px(bars[b].value)); ++i) put(panel, i, j, bars[b].colour);
        draw_text(panel, int(px(std::isfinite(bars[b].value) ? bars[b].value : 0)) + 6, text_y, value, kInk, kText);
    }
    line(panel, left, top - 4, left, bottom, kFrame, 1);
    line(panel, px(marker), top - 4, px(marker), bottom, kFrame, 1, 6);
    draw_text(panel, int(px(marker)) - text_width(marker_label, kText) - 6, top - kLineHeight - 2, marker_label, kInk,
              kText);
    return panel;
}

namespace {
/// sRGB control points of matplotlib's "inferno" (perceptually uniform, legible in grey too),
/// decoded to linear: the figure is written through the sRGB encoding like every image.
std::array<float, 3> inferno(double t)
{
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
    t = std::clamp(t, 0.0, 1.0) * (stops.size() - 1);
    const std::size_t s = std::min(std::size_t(t), stops.size() - 2);
    const double u = t - double(s);
    std::array<float, 3> colour;
    for (int c = 0; c < 3; ++c) colour[c] = float(stops[s][c] * (1 - u) + stops[s + 1][c] * u);
    return colour;
}
}  // namespace

Image heat_map_panel(const std::vector<double>& values, int grid, int size, double lo, double hi)
{
    Image panel(size, size, 3);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const double v = values[std::size_t(y * grid / size) * grid + std::size_t(x * grid / size)];
            put(panel, x, y, inferno(hi > lo ? (v - lo) / (hi - lo) : 0.0));
        }
    return panel;
}

Image heat_map_scale(int width, int height, double lo, double hi)
{
    Image strip = blank(width, height);
    const int bar = std::min(width, 24);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < bar; ++x) put(strip, x, y, inferno(1.0 - double(y) / std::max(1, height - 1)));
    const std::string top = number(std::round(hi)), bottom = number(std::round(lo));
    draw_text(strip, bar + 4, 0, top, kInk, kText);
    draw_text(strip, bar + 4, height - kGlyphHeight * kText, bottom, kInk, kText);
    draw_text_vertical(strip, bar + 8, (height - text_width("dB", kText)) / 2, "dB", kInk, kText);
    return strip;
}

void paste(Image& target, const Image& source, int x, int y)
{
    for (int j = 0; j < source.height; ++j)
        for (int i = 0; i < source.width; ++i)
            for (int c = 0; c < 3; ++c)
                if (x + i >= 0 && y + j >= 0 && x + i < target.width && y + j < target.height)
                    target.at(x + i, y + j, c) = source.at(i, j, c);
}

Image enlarged(const Image& source, int factor)
{
    Image out(source.width * factor, source.height * factor, source.channels);
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x)
            for (int c = 0; c < source.channels; ++c) out.at(x, y, c) = source.at(x / factor, y / factor, c);
    return out;
}

}  // namespace stex_cli
