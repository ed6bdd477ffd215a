#include "tiling_parameters.h"

#include "base64.h"
#include "quantised_image.h"

#include <stochtex/error.h>

#include <charconv>
#include <cmath>
#include <limits>

namespace stochtex {

namespace {

using json_fields::Field;
using json_fields::Json;

constexpr TilingOutput all_outputs[] = {TilingOutput::colour, TilingOutput::colour_map, TilingOutput::normal_map};

std::string show(double value)
{
    char text[32];
    return std::string(text, std::to_chars(text, text + sizeof text, value).ptr);
}

bool power_of_two(int n) { return n > 0 && (n & (n - 1)) == 0; }

QuantisedImage read_image(const Field& image)
{
    image.expect_keys({"width", "height", "channels", "bits", "ranges", "png"});
    QuantisedImage result;
    constexpr std::int64_t int_max = std::numeric_limits<int>::max();
    result.width = int(image["width"].integer(0, int_max));
    result.height = int(image["height"].integer(0, int_max));
    result.channels = int(image["channels"].integer(1, 3));
    result.bits = int(image["bits"].integer(0, int_max));
    if (result.bits != 8 && result.bits != 16) image["bits"].fail("expected 8 or 16, got " + std::to_string(result.bits));
    for (const Field& range : image["ranges"].elements(result.channels, "channel ranges")) {
        const std::array<double, 2> r = range.numbers<2>();
        result.ranges.push_back(r);
    }
    // Sizes are checked before decoding, so that a huge declared image costs nothing.
    for (const char* side : {"width", "height"}) {
        const int n = side[0] == 'w' ? result.width : result.height;
        if (!power_of_two(n) || n > max_tiling_exemplar_side)
            image[side].fail("must be a power of two no larger than " + std::to_string(max_tiling_exemplar_side) +
                             ", got " + std::to_string(n));
    }
    const Field png = image["png"];
    const std::string text = png.string();
    if (text.size() > max_image_payload_chars)
        png.fail("payload of " + std::to_string(text.size()) + " characters exceeds the limit of " +
                 std::to_string(max_image_payload_chars));
    try {
        decode_png(base64_decode(text), result);
    } catch (const Error& e) {
        png.fail(e.what());
    }
    return result;
}

Json image_json(const QuantisedImage& image)
{
    Json json = Json::object();
    json["width"] = image.width;
    json["height"] = image.height;
    json["channels"] = image.channels;
    json["bits"] = image.bits;
    json["ranges"] = image.ranges;
    json["png"] = base64_encode(encode_png(image));
    return json;
}

void check_image(const QuantisedImage& image, const std::string& path, int channels, int min_side, int max_side,
                 const std::string& source)
{
    auto check_side = [&](int side, const char* name) {
        if (!power_of_two(side) || side < min_side || side > max_side)
            json_fields::fail(source, path + "." + name,
                              "must be a power of two in [" + std::to_string(min_side) + ", " + std::to_string(max_side) +
                                  "], got " + std::to_string(side));
    };
    check_side(image.width, "width");
    check_side(image.height, "height");
    if (image.channels != channels)
        json_fields::fail(source, path + ".channels",
                          "expected " + std::to_string(channels) + " for this output, got " + std::to_string(image.channels));
    if (image.bits != 8 && image.bits != 16)
        json_fields::fail(source, path + ".bits", "expected 8 or 16, got " + std::to_string(image.bits));
    if (image.ranges.size() != std::size_t(channels))
        json_fields::fail(source, path + ".ranges",
                          "expected " + std::to_string(channels) + " ranges, got " + std::to_string(image.ranges.size()));
    for (std::size_t c = 0; c < image.ranges.size(); ++c) {
        const std::string at = path + ".ranges[" + std::to_string(c) + "]";
        const auto& r = image.ranges[c];
        for (double v : r)
            if (!(std::fabs(v) <= std::numeric_limits<float>::max()))
                json_fields::fail(source, at, "expected finite numbers within float range, got " + show(v));
        if (!(r[0] <= r[1])) json_fields::fail(source, at, "minimum " + show(r[0]) + " exceeds maximum " + show(r[1]));
    }
    const std::size_t expected = std::size_t(image.width) * image.height * image.channels;
    if (image.samples.size() != expected)
        json_fields::fail(source, path + ".png",
                          "holds " + std::to_string(image.samples.size()) + " samples, expected " + std::to_string(expected));
    const unsigned largest = (1u << image.bits) - 1;
    for (std::uint16_t q : image.samples)
        if (q > largest) json_fields::fail(source, path + ".png", "sample " + std::to_string(q) + " exceeds " + std::to_string(largest));
}

}  // namespace

const char* to_string(TilingOutput output)
{
    switch (output) {
    case TilingOutput::colour: return "colour";
    case TilingOutput::colour_map: return "colour_map";
    case TilingOutput::normal_map: return "normal_map";
    }
    throw Error("invalid TilingOutput value " + std::to_string(static_cast<int>(output)));
}

TilingOutput tiling_output_from_string(const std::string& name)
{
    for (TilingOutput output : all_outputs)
        if (name == to_string(output)) return output;
    throw Error("unknown tiling output '" + name + "' (valid: colour, colour_map, normal_map)");
}

TilingParameters read_tiling_parameters(const Field& parameters)
{
    parameters.expect_keys({"output", "triangle_edge", "exemplar", "colour_map"});
    TilingParameters result;
    const Field output = parameters["output"];
    try {
        result.output = tiling_output_from_string(output.string());
    } catch (const Error& e) {
        output.fail(e.what());
    }
    result.triangle_edge = parameters["triangle_edge"].number();
    result.exemplar = read_image(parameters["exemplar"]);
    const Field map = parameters["colour_map"];
    if (!map.is_null()) result.colour_map = read_image(map);
    return result;
}

Json tiling_parameters_json(const TilingParameters& parameters)
{
    Json json = Json::object();
    json["output"] = to_string(parameters.output);
    json["triangle_edge"] = parameters.triangle_edge;
    json["exemplar"] = image_json(parameters.exemplar);
    json["colour_map"] = parameters.colour_map.channels > 0 ? image_json(parameters.colour_map) : Json();
    return json;
}

void validate_tiling(const TextureDescription& description, const std::string& source)
{
    const TilingParameters& p = *description.tiling;
    const double edge = p.triangle_edge;
    if (!(edge >= 1.0 / 64 && edge <= 1))
        json_fields::fail(source, "parameters.triangle_edge", "must be in [0.015625, 1] exemplar widths, got " + show(edge));
    const bool colour = p.output == TilingOutput::colour;
    check_image(p.exemplar, "parameters.exemplar", colour ? 3 : 2, min_tiling_exemplar_side, max_tiling_exemplar_side, source);
    const bool wants_map = p.output == TilingOutput::colour_map;
    if (wants_map != (p.colour_map.channels > 0))
        json_fields::fail(source, "parameters.colour_map",
                          wants_map ? "missing: output colour_map needs a colour map"
                                    : std::string("must be null for output ") + to_string(p.output));
    if (wants_map) {
        check_image(p.colour_map, "parameters.colour_map", 3, min_colour_map_side, max_colour_map_side, source);
        if (p.colour_map.width != p.colour_map.height)
            json_fields::fail(source, "parameters.colour_map", "must be square, got " + std::to_string(p.colour_map.width) +
                                                                   "x" + std::to_string(p.colour_map.height));
        for (std::size_t c = 0; c < 3; ++c)
            if (!(p.colour_map.ranges[c][0] >= 0 && p.colour_map.ranges[c][1] <= 1))
                json_fields::fail(source, "parameters.colour_map.ranges[" + std::to_string(c) + "]",
                                  "sRGB values must lie in [0, 1]");
    }
    if (!colour) {
        // The colour fields do not apply: one spelling keeps such files canonical.
        if (description.colour_mode != ColourMode::rgb)
            json_fields::fail(source, "colour.mode", std::string("must be \"rgb\" for tiling output ") + to_string(p.output));
        for (std::size_t c = 0; c < 3; ++c)
            if (description.histograms[c].enabled())
                json_fields::fail(source, "histograms[" + std::to_string(c) + "]",
                                  std::string("must be null for tiling output ") + to_string(p.output));
    }
}

}  // namespace stochtex
