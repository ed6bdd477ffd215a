// PTM coefficient maps: layout, relighting, and the .stex description that holds them.
#include <stochtex/error.h>
#include <stochtex/models/ptm.h>
#include <stochtex/models/ptm_parameters.h>

#include "models/ptm/ptm_functions.h"

#include <algorithm>
#include <cmath>

namespace stochtex {

const char* to_string(PtmColour colour) { return colour == PtmColour::lrgb ? "lrgb" : "rgb"; }

PtmColour ptm_colour_from_string(const std::string& name)
{
    for (PtmColour colour : {PtmColour::lrgb, PtmColour::rgb})
        if (name == to_string(colour)) return colour;
    throw Error("unknown PTM colour model '" + name + "' (valid: lrgb, rgb)");
}

int ptm_channel_count(PtmColour colour) { return colour == PtmColour::lrgb ? 9 : 18; }

int ptm_function_channel_count(PtmColour colour) { return colour == PtmColour::lrgb ? 6 : 18; }

std::vector<std::string> ptm_channel_names(PtmColour colour)
{
    std::vector<std::string> names;
    const std::vector<std::string> functions = colour == PtmColour::lrgb ? std::vector<std::string>{"Y"}
                                                                         : std::vector<std::string>{"R", "G", "B"};
    for (const std::string& function : functions)
        for (int k = 0; k < legendre::term_count; ++k) names.push_back(function + ".b" + std::to_string(k));
    if (colour == PtmColour::lrgb)
        for (const char* channel : {"chroma.R", "chroma.G", "chroma.B"}) names.push_back(channel);
    return names;
}

std::array<legendre::Terms, 3> texel_colour_functions(PtmColour colour, const float* texel)
{
    std::array<legendre::Terms, 3> functions{};
    for (int c = 0; c < 3; ++c)
        for (int k = 0; k < legendre::term_count; ++k)
            functions[c][k] = colour == PtmColour::lrgb ? double(texel[k]) * texel[legendre::term_count + c]
                                                        : double(texel[c * legendre::term_count + k]);
    return functions;
}

Image relight(const PtmMaps& maps, const Vec3& light)
{
    const legendre::Terms basis = basis_at(checked_light_direction(light, "light"));
    const int channels = maps.coefficients.channels;
    if (channels != ptm_channel_count(maps.colour)) throw Error("relight: the maps have the wrong channel count");
    Image image(maps.width(), maps.height(), 3);
    for (std::size_t i = 0; i < image.pixel_count(); ++i) {
        const auto functions = texel_colour_functions(maps.colour, &maps.coefficients.pixels[i * channels]);
        // Radiance cannot be negative; a biquadratic dips below zero at grazing lights.
        for (int c = 0; c < 3; ++c) image.pixels[i * 3 + c] = float(std::max(0.0, legendre::dot(functions[c], basis)));
    }
    return image;
}

TextureDescription make_ptm_description(PtmMaps maps, const Vec3& light)
{
    if (maps.width() < 1 || maps.coefficients.channels != ptm_channel_count(maps.colour))
        throw Error("ptm description: empty maps or a wrong channel count");
    TextureDescription description;
    description.model = "ptm";
    description.pixels_per_unit = maps.width();
    // Colour is the model's own: the colour block is the identity with no histograms, and its
    // mean is informational (the maps' mean colour under `light`).
    description.colour_mode = ColourMode::rgb;
    const Image lit = relight(maps, light);
    for (int c = 0; c < 3; ++c) {
        double sum = 0;
        for (std::size_t i = 0; i < lit.pixel_count(); ++i) sum += lit.pixels[i * 3 + c];
        description.mean[c] = sum / double(lit.pixel_count());
    }
    PtmParameters parameters;
    parameters.colour = maps.colour;
    parameters.light = checked_light_direction(light, "light");
    parameters.maps = std::make_shared<const PtmMaps>(std::move(maps));
    description.provenance.source_width = parameters.maps->width();
    description.provenance.source_height = parameters.maps->height();
    description.parameters = std::move(parameters);
    return description;
}

}  // namespace stochtex
