#include "schema/quantised_image.h"

#include <stochtex/error.h>

#include "image/png_memory.h"

#include <algorithm>
#include <cmath>

namespace stochtex {

double QuantisedImage::value(int channel, int x, int y) const
{
    const double q = samples[(std::size_t(channel) * height + y) * width + x];
    const auto& range = ranges[std::size_t(channel)];
    return range[0] + q / double((1 << bits) - 1) * (range[1] - range[0]);
}

QuantisedImage quantise(const std::vector<std::vector<float>>& planes, int width, int height, int bits)
{
    std::vector<std::array<double, 2>> ranges;
    for (const std::vector<float>& plane : planes) {
        const auto [lo, hi] = std::minmax_element(plane.begin(), plane.end());
        // Stored as floats in the file: round outward so every value stays inside.
        ranges.push_back({std::nextafter(float(*lo), -INFINITY), std::nextafter(float(*hi), INFINITY)});
    }
    return quantise(planes, width, height, bits, ranges);
}

QuantisedImage quantise(const std::vector<std::vector<float>>& planes, int width, int height, int bits,
                        const std::vector<std::array<double, 2>>& ranges)
{
    if (bits != 8 && bits != 16) throw Error("quantised image: bits must be 8 or 16, got " + std::to_string(bits));
    QuantisedImage image;
    image.width = width, image.height = height, image.channels = int(planes.size()), image.bits = bits;
    image.ranges = ranges;
    const double levels = double((1 << bits) - 1);
    const std::size_t count = std::size_t(width) * height;
    image.samples.reserve(count * planes.size());
    for (std::size_t c = 0; c < planes.size(); ++c) {
        const double lo = float(ranges[c][0]), span = float(ranges[c][1]) - lo;
        for (std::size_t i = 0; i < count; ++i) {
            const double t = span > 0 ? (planes[c][i] - lo) / span : 0.0;
            image.samples.push_back(std::uint16_t(std::lround(std::clamp(t, 0.0, 1.0) * levels)));
        }
    }
    return image;
}

std::vector<std::vector<double>> dequantise(const QuantisedImage& image)
{
    std::vector<std::vector<double>> planes(std::size_t(image.channels));
    for (int c = 0; c < image.channels; ++c) {
        planes[c].reserve(std::size_t(image.width) * image.height);
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x) planes[c].push_back(image.value(c, x, y));
    }
    return planes;
}

std::vector<std::uint8_t> encode_png(const QuantisedImage& image)
{
    // The planes stacked, as one grey image (docs/stex-format.md).
    return codec::encode_grey_png(image.width, image.height * image.channels, image.bits, image.samples.data());
}

void decode_png(const std::vector<std::uint8_t>& png, QuantisedImage& image)
{
    static const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (png.size() < 8 || !std::equal(signature, signature + 8, png.begin())) throw Error("not a PNG image");
    int width = 0, height = 0, channels = 0, stored_bits = 0;
    std::string error = codec::decode_grey_png(png, width, height, channels, stored_bits, nullptr);
    if (!error.empty()) throw Error(error);
    const int expected_height = image.height * image.channels;
    if (width != image.width || height != expected_height || channels != 1)
        throw Error("PNG is " + std::to_string(width) + "x" + std::to_string(height) + " with " +
                    std::to_string(channels) + " channel(s); expected " + std::to_string(image.width) + "x" +
                    std::to_string(expected_height) + " grey (the planes stacked)");
    if (stored_bits != image.bits)
        throw Error("PNG has " + std::to_string(stored_bits) + "-bit samples; bits says " + std::to_string(image.bits));
    error = codec::decode_grey_png(png, width, height, channels, stored_bits, &image.samples);
    if (!error.empty()) throw Error(error);
}

}  // namespace stochtex
