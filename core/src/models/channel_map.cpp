#include <stochtex/channel_map.h>

#include <stochtex/error.h>

#include "colour/chroma_given_brightness.h"
#include "colour/histogram_map.h"
#include "models/model.h"

#include <cmath>
#include <string>

namespace stochtex {

double channel_sigma(const TextureDescription& description, int channel)
{
    if (channel < 0 || channel > 2) throw Error("channel_sigma: channel " + std::to_string(channel) + " is not 0, 1 or 2");
    const Model& model = model_of(description, "channel_sigma");
    if (!model.info().capabilities.gaussian_channels)
        throw Error("channel_sigma: model '" + description.model + "' has no Gaussian channels");
    return model.channel_sigma(description, channel);
}

namespace {

/// f_c as a callable: the monotone cubic is built once per polyline, not once per sample.
struct ChannelFunction {
    MonotoneCubic map;
    double sigma = 0;
    double operator()(double z) const { return map.empty() ? sigma * z : map(z); }
};

ChannelFunction channel_function(const TextureDescription& description, int channel)
{
    require_independent_channels(description, "channel colour map", "bake the texture to an image instead");
    ChannelFunction f;
    f.sigma = channel_sigma(description, channel);
    const HistogramMap& histogram = description.histograms[channel];
    if (histogram.enabled()) f.map = MonotoneCubic(histogram.z, histogram.value);
    return f;
}

}  // namespace

double channel_value(const TextureDescription& description, int channel, double z)
{
    return channel_function(description, channel)(z);
}

std::vector<std::array<double, 2>> channel_value_polyline(const TextureDescription& description, int channel,
                                                          double z_min, double z_max, double tolerance,
                                                          int max_points)
{
    if (!(z_min < z_max) || !(tolerance > 0) || max_points < 2)
        throw Error("channel_value_polyline: need z_min < z_max, tolerance > 0 and at least 2 points");
    const ChannelFunction f = channel_function(description, channel);

    // Start from the range's ends and the knots inside it: the cubic's pieces meet there.
    std::vector<double> z{z_min};
    for (double knot : description.histograms[channel].z)
        if (knot > z_min && knot < z_max) z.push_back(knot);
    z.push_back(z_max);

    constexpr int checks = 32;
    auto segment_fits = [&](double a, double b) {
        const double fa = f(a), fb = f(b);
        for (int i = 1; i < checks; ++i) {
            const double s = double(i) / checks;
            if (std::abs(f(a + s * (b - a)) - (fa + s * (fb - fa))) > tolerance) return false;
        }
        return true;
    };
    // Halve every segment that misses the tolerance until none does (a smooth map converges
    // quadratically, so few rounds are needed).
    for (bool refined = true; refined;) {
        refined = false;
        std::vector<double> next{z.front()};
        for (std::size_t i = 0; i + 1 < z.size(); ++i) {
            if (!segment_fits(z[i], z[i + 1])) {
                next.push_back(0.5 * (z[i] + z[i + 1]));
                refined = true;
            }
            next.push_back(z[i + 1]);
        }
        z.swap(next);
        if (int(z.size()) > max_points)
            throw Error("channel_value_polyline: channel " + std::to_string(channel) + " needs more than " +
                        std::to_string(max_points) + " points for a tolerance of " + std::to_string(tolerance));
    }
    std::vector<std::array<double, 2>> polyline;
    polyline.reserve(z.size());
    for (double zk : z) polyline.push_back({zk, f(zk)});
    return polyline;
}

}  // namespace stochtex
