#include "models/tiling/tiling_parameters.h"

#include "schema/base64.h"
#include "schema/quantised_image.h"

#include <stochtex/error.h>
#include <stochtex/models/tiling_parameters.h>

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

/// The fields of an embedded image, for the documentation.
std::vector<ParameterInfo> image_fields()
{
    return {{"width", "integer", "power of two", "", "px", "", {}},
            {"height", "integer", "power of two", "", "px", "", {}},
            {"channels", "integer", "[1, 3]", "", "", "what the output needs", {}},
            {"bits", "integer", "8 | 16", "", "", "bits per stored sample", {}},
            {"ranges", "array of channels pairs of numbers", "min ≤ max", "", "",
             "[min, max] of each channel: sample q stands for min + q / (2^bits − 1) · (max − min)", {}},
            {"png", "string", "≤ 16 MiB of text", "", "",
             "Base64 (RFC 4648, padded, no whitespace) of a PNG holding exactly width × channels·height grey samples of "
             "bits bits: the channel planes stacked top to bottom (grey, so no colour space, gamma or alpha handling can "
             "change the samples)",
             {}}};
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

ParameterSchema<TilingParameters> tiling_schema()
{
    using P = TilingParameters;
    ParameterSchema<P> schema;
    schema.enumeration("output", &P::output, to_string, tiling_output_from_string,
                       {TilingOutput::colour, TilingOutput::colour_map, TilingOutput::normal_map},
                       {"colour", "", "colour: 3 decorrelated colour channels (histogram maps, then mean + basis · y); "
                                      "colour_map: 2 noises in [0, 1] indexing colour_map; normal_map: 2 slopes ∂h/∂x, ∂h/∂y "
                                      "per exemplar pixel (a tangent-space normal map)."});
    schema.number("triangle_edge", &P::triangle_edge, {1.0 / 64, 1, "exemplar widths"},
                  {"0.288675", "exemplar widths", "The triangle grid's edge in widths of the exemplar's shorter side; "
                                                  "stochtex writes 1/(2√3) (Deliot–Heitz): hexagonal tiles ≈ 0.58 exemplar "
                                                  "widths across."});
    ParameterInfo filter_taps{"filter_taps", "integer", "[1, " + std::to_string(P::max_filter_taps) + "]",
                              std::to_string(P::default_filter_taps), "taps per axis",
                              "The footprint estimator's taps per footprint axis (taps × taps texel estimates on an isotropic "
                              "footprint, combined by the law of total variance): 2 halves the filtered mean's error of 1, the "
                              "paper's single per-texel estimate, which renders ≈ 2.4× faster. Written only when not 2.",
                              {}};
    schema.optional_custom(
        filter_taps, [](const P& p) { return p.filter_taps != P::default_filter_taps; },
        [](const Field& f, P& p, const ReadContext&) { p.filter_taps = int(f.integer(1, P::max_filter_taps)); },
        [](const P& p) { return Json(p.filter_taps); },
        [](const P& p, const std::string& path, const std::string& source) {
            if (p.filter_taps < 1 || p.filter_taps > P::max_filter_taps)
                json_fields::fail(source, path, "must be in [1, " + std::to_string(P::max_filter_taps) + "], got " +
                                                    std::to_string(p.filter_taps));
        });
    ParameterInfo blend_contrast{"blend_contrast", "number", NumberRange{1, P::max_blend_contrast, ""}.text(), "1", "",
                                 "Blend contrast γ: the three tiles' weights are B^γ normalised to Σ w² = 1 (B the barycentric "
                                 "coordinates); above 1 the nearest tile dominates, so fewer tiles show through each other "
                                 "(ghosts), at the price of sharper tile borders. 1 is Heitz–Neyret's blend. Written only when not 1.",
                                 {}};
    schema.optional_custom(
        blend_contrast, [](const P& p) { return p.blend_contrast != 1; },
        [](const Field& f, P& p, const ReadContext&) { p.blend_contrast = f.number(); },
        [](const P& p) { return Json(p.blend_contrast); },
        [](const P& p, const std::string& path, const std::string& source) {
            check_in_range(p.blend_contrast, {1, P::max_blend_contrast, ""}, path, source);
        });
    ParameterInfo exemplar{"exemplar", "image", "", "", "",
                           "3 channels for colour, 2 otherwise; periodic (tiles are cut anywhere, with wrap); sides "
                           "powers of two in [16, 1024]. For colour, a channel with a histogram map holds standard-normal "
                           "values (the map's input), the others channel values.",
                           image_fields()};
    schema.custom(
        exemplar, [](const Field& f, P& p, const ReadContext&) { p.exemplar = read_image(f); }, [](const P& p) { return image_json(p.exemplar); },
        [](const P& p, const std::string& path, const std::string& source) {
            check_image(p.exemplar, path, p.output == TilingOutput::colour ? 3 : 2, min_tiling_exemplar_side,
                        max_tiling_exemplar_side, source);
        });
    ParameterInfo colour_map{"colour_map", "image | null", "", "", "",
                             "Only (and always) for colour_map: 3 channels of sRGB-encoded colour in [0, 1], square, "
                             "sides powers of two in [8, 1024]; x follows noise 0, y noise 1. null otherwise.",
                             image_fields()};
    schema.custom(
        colour_map,
        [](const Field& f, P& p, const ReadContext&) {
            if (!f.is_null()) p.colour_map = read_image(f);
        },
        [](const P& p) { return p.colour_map.channels > 0 ? image_json(p.colour_map) : Json(); },
        [](const P& p, const std::string& path, const std::string& source) {
            const bool wants_map = p.output == TilingOutput::colour_map;
            if (wants_map != (p.colour_map.channels > 0))
                json_fields::fail(source, path,
                                  wants_map ? "missing: output colour_map needs a colour map"
                                            : std::string("must be null for output ") + to_string(p.output));
            if (!wants_map) return;
            check_image(p.colour_map, path, 3, min_colour_map_side, max_colour_map_side, source);
            if (p.colour_map.width != p.colour_map.height)
                json_fields::fail(source, path, "must be square, got " + std::to_string(p.colour_map.width) + "x" +
                                                    std::to_string(p.colour_map.height));
            for (std::size_t c = 0; c < 3; ++c)
                if (!(p.colour_map.ranges[c][0] >= 0 && p.colour_map.ranges[c][1] <= 1))
                    json_fields::fail(source, path + ".ranges[" + std::to_string(c) + "]", "sRGB values must lie in [0, 1]");
        });
    return schema;
}

void validate_tiling_colour_fields(const TextureDescription& description, const std::string& source)
{
    const TilingParameters& p = description.parameters.get<TilingParameters>();
    if (p.output == TilingOutput::colour) return;
    // The colour fields do not apply: one spelling keeps such files canonical.
    if (description.colour_mode != ColourMode::rgb)
        json_fields::fail(source, "colour.mode", std::string("must be \"rgb\" for tiling output ") + to_string(p.output));
    for (std::size_t c = 0; c < 3; ++c)
        if (description.histograms[c].enabled())
            json_fields::fail(source, "histograms[" + std::to_string(c) + "]",
                              std::string("must be null for tiling output ") + to_string(p.output));
}

}  // namespace stochtex
