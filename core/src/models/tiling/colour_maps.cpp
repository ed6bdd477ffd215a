#include "models/tiling/colour_maps.h"

#include <stochtex/error.h>

#include <array>
#include <cmath>
#include <functional>

namespace stochtex {

namespace {

using Colour = std::array<double, 3>;

Colour mix(const Colour& x, const Colour& y, double t)
{
    return {x[0] + (y[0] - x[0]) * t, x[1] + (y[1] - x[1]) * t, x[2] + (y[2] - x[2]) * t};
}

double smoothstep(double t) { return t * t * (3 - 2 * t); }

Colour green(double a, double b)
{
    // Dark to light green along a, towards yellow-green along b: smooth everywhere.
    const Colour shade = mix({0.05, 0.22, 0.06}, {0.55, 0.82, 0.38}, smoothstep(a));
    return mix(shade, {0.72, 0.78, 0.22}, 0.45 * smoothstep(b));
}

Colour saturated(double a, double b)
{
    const double x = a - 0.5, y = b - 0.5;
    if (std::hypot(x, y) < 0.07) return {1, 0.9, 0};
    const double turn = std::atan2(y, x) / (2 * M_PI) + 0.5;  // [0, 1]
    static const Colour sectors[3] = {{1, 0, 0}, {0, 0.85, 0}, {0, 0.1, 1}};
    return sectors[int(turn * 3) % 3];
}

/// profile(φ) ∈ [0, 1] of the phase φ = atan2(sin, cos) recovered from the (sin, cos) pair.
Colour phasor(double a, double b, const std::function<double(double)>& profile)
{
    const double phase = std::atan2(2 * a - 1, 2 * b - 1);
    return mix({0.06, 0.04, 0.02}, {0.96, 0.78, 0.45}, profile(phase));
}

double sine_profile(double phase) { return 0.5 + 0.5 * std::sin(phase); }
double square_profile(double phase) { return std::sin(phase) >= 0 ? 1.0 : 0.0; }
double sawtooth_profile(double phase) { return phase / (2 * M_PI) + 0.5; }

}  // namespace

const std::vector<std::string>& colour_map_names()
{
    static const std::vector<std::string> names{"green", "rgb", "phasor-sine", "phasor-square", "phasor-sawtooth"};
    return names;
}

std::vector<float> named_colour_map(const std::string& name, int size)
{
    std::function<Colour(double, double)> map;
    if (name == "green") map = green;
    if (name == "rgb") map = saturated;
    if (name == "phasor-sine") map = [](double a, double b) { return phasor(a, b, sine_profile); };
    if (name == "phasor-square") map = [](double a, double b) { return phasor(a, b, square_profile); };
    if (name == "phasor-sawtooth") map = [](double a, double b) { return phasor(a, b, sawtooth_profile); };
    if (!map) {
        std::string known;
        for (const std::string& n : colour_map_names()) known += (known.empty() ? "" : ", ") + n;
        throw Error("unknown colour map '" + name + "' (known: " + known + ")");
    }
    std::vector<float> rgb(std::size_t(size) * size * 3);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const Colour c = map((x + 0.5) / size, (y + 0.5) / size);
            for (int k = 0; k < 3; ++k) rgb[(std::size_t(y) * size + x) * 3 + k] = float(c[k]);
        }
    return rgb;
}

}  // namespace stochtex
