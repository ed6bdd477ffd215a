// stochtex/models/tiling.h: tiling descriptions from noise pairs, phasor fields and height maps.
#include <stochtex/models/tiling.h>

#include <stochtex/error.h>
#include <stochtex/stex_file.h>
#include <stochtex/texture.h>
#include <stochtex/models/tiling_parameters.h>

#include "models/tiling/colour_maps.h"
#include "models/tiling/phasor_field.h"
#include "schema/quantised_image.h"
#include "models/tiling/tiling_exemplar.h"
#include "models/tiling/tiling_parameters.h"

#include <algorithm>
#include <cmath>

namespace stochtex {

namespace {

constexpr int colour_map_size = 256;

std::vector<float> luminance(const Image& image)
{
    std::vector<float> plane(image.pixel_count());
    for (std::size_t i = 0; i < plane.size(); ++i) {
        const float* p = &image.pixels[i * image.channels];
        plane[i] = image.channels >= 3 ? 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2] : p[0];
    }
    return plane;
}

void check_options(const TilingSourceOptions& options)
{
    if (options.exemplar_size < min_tiling_exemplar_side || options.exemplar_size > max_tiling_exemplar_side)
        throw Error("exemplar size must be in [" + std::to_string(min_tiling_exemplar_side) + ", " +
                    std::to_string(max_tiling_exemplar_side) + "], got " + std::to_string(options.exemplar_size));
    if (options.bits != 8 && options.bits != 16) throw Error("exemplar bits must be 8 or 16, got " + std::to_string(options.bits));
    if (!(options.unit_size_m > 0) || !std::isfinite(options.unit_size_m)) throw Error("unit size must be a positive number of metres");
    if (options.filter_taps < 1 || options.filter_taps > TilingParameters::max_filter_taps)
        throw Error("filter taps must be in [1, " + std::to_string(TilingParameters::max_filter_taps) + "], got " +
                    std::to_string(options.filter_taps));
}

/// The periodic centred crop of a photo's luminance, at the options' exemplar size.
std::vector<float> exemplar_plane(const Image& image, const TilingSourceOptions& options, int& side)
{
    side = power_of_two_floor(std::min({image.width, image.height, options.exemplar_size}));
    if (side < min_tiling_exemplar_side)
        throw Error("image is " + std::to_string(image.width) + "x" + std::to_string(image.height) + ", too small for an exemplar");
    return periodic_crop(luminance(image), image.width, image.height, side, side);
}

/// A tiling description around `parameters`, with the colour fields a non-colour output uses.
TextureDescription describe_source(TilingParameters parameters, int source_width, int source_height,
                                   const TilingSourceOptions& options, const std::string& kind)
{
    TextureDescription d;
    d.model = "tiling";
    d.seed = options.seed;
    d.pixels_per_unit = parameters.exemplar.width;
    d.unit_size_m = options.unit_size_m;
    d.colour_mode = ColourMode::rgb;
    parameters.filter_taps = options.filter_taps;
    d.parameters = std::move(parameters);
    Provenance& provenance = d.provenance;
    provenance.source = options.source_name;
    provenance.source_width = source_width;
    provenance.source_height = source_height;
    provenance.input_colour_space = "file";
    provenance.tool = "stochtex " STOCHTEX_VERSION;
    provenance.options = {{"model", "tiling"}, {"source", kind}, {"exemplar_size", std::to_string(options.exemplar_size)},
                          {"exemplar_bits", std::to_string(options.bits)}, {"seed", std::to_string(options.seed)}};
    if (options.filter_taps != TilingParameters::default_filter_taps)  // (default files stay as they were)
        provenance.options.push_back({"filter_taps", std::to_string(options.filter_taps)});
    // The colour mean is informational for these outputs: the texture's own limit of minification.
    const Rgb mean = make_texture(d)->mean();
    d.mean = {mean[0], mean[1], mean[2]};
    validate(d, options.source_name.empty() ? "tiling source" : options.source_name);
    return d;
}

TilingParameters colour_mapped_parameters(std::vector<std::vector<float>> noises, int side, const std::string& colour_map, int bits)
{
    TilingParameters parameters;
    parameters.output = TilingOutput::colour_map;
    parameters.exemplar = quantise(noises, side, side, bits, {{0, 1}, {0, 1}});
    const std::vector<float> map = named_colour_map(colour_map, colour_map_size);
    std::vector<std::vector<float>> planes(3, std::vector<float>(std::size_t(colour_map_size) * colour_map_size));
    for (std::size_t i = 0; i < planes[0].size(); ++i)
        for (int c = 0; c < 3; ++c) planes[c][i] = map[i * 3 + c];
    parameters.colour_map = quantise(planes, colour_map_size, colour_map_size, 8, {{0, 1}, {0, 1}, {0, 1}});
    return parameters;
}

}  // namespace

TextureDescription colour_mapped_texture(const Image& noise_a, const Image& noise_b, const std::string& colour_map,
                                         const TilingSourceOptions& options)
{
    check_options(options);
    int side_a = 0, side_b = 0;
    std::vector<std::vector<float>> noises{exemplar_plane(noise_a, options, side_a), exemplar_plane(noise_b, options, side_b)};
    const int side = std::min(side_a, side_b);
    for (auto* plane : {&noises[0], &noises[1]}) {
        const int from = plane == &noises[0] ? side_a : side_b;
        if (from != side) {  // the larger crop's centre, at the common size (already periodic)
            std::vector<float> crop(std::size_t(side) * side);
            const int o = (from - side) / 2;
            for (int y = 0; y < side; ++y) std::copy_n(&(*plane)[std::size_t(o + y) * from + o], side, &crop[std::size_t(y) * side]);
            *plane = periodic_crop(crop, side, side, side, side);
        }
        // mean ± 3σ → [0, 1]: the middle of the map is the noise's mean.
        double sum = 0, sum2 = 0;
        for (float v : *plane) sum += v, sum2 += double(v) * v;
        const double mean = sum / plane->size(), sigma = std::sqrt(std::max(1e-20, sum2 / plane->size() - mean * mean));
        for (float& v : *plane) v = float(std::clamp(0.5 + (v - mean) / (6 * sigma), 0.0, 1.0));
    }
    return describe_source(colour_mapped_parameters(std::move(noises), side, colour_map, options.bits),
                           std::max(noise_a.width, noise_b.width), std::max(noise_a.height, noise_b.height), options,
                           "noise pair, colour map " + colour_map);
}

TextureDescription phasor_texture(const std::string& colour_map, double frequency, const TilingSourceOptions& options)
{
    check_options(options);
    PhasorFieldOptions field;
    field.size = power_of_two_floor(options.exemplar_size);
    field.frequency = frequency;
    field.seed = options.seed;
    std::array<std::vector<float>, 2> pair = phasor_field(field);
    return describe_source(colour_mapped_parameters({std::move(pair[0]), std::move(pair[1])}, field.size, colour_map, options.bits),
                           0, 0, options, "phasor noise, colour map " + colour_map);
}

TextureDescription normal_map_texture(const Image& height, double strength, const TilingSourceOptions& options)
{
    check_options(options);
    if (!(strength > 0) || !std::isfinite(strength)) throw Error("height strength must be positive");
    int side = 0;
    const std::vector<float> h = exemplar_plane(height, options, side);
    // Central differences on the periodic height: slopes per exemplar pixel.
    std::vector<std::vector<float>> slopes(2, std::vector<float>(h.size()));
    auto at = [&](int x, int y) { return h[std::size_t((y + side) % side) * side + std::size_t((x + side) % side)]; };
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x) {
            slopes[0][std::size_t(y) * side + x] = float(0.5 * strength * (at(x + 1, y) - at(x - 1, y)));
            slopes[1][std::size_t(y) * side + x] = float(0.5 * strength * (at(x, y + 1) - at(x, y - 1)));
        }
    TilingParameters parameters;
    parameters.output = TilingOutput::normal_map;
    parameters.exemplar = quantise(slopes, side, side, options.bits);
    return describe_source(std::move(parameters), height.width, height.height, options, "height map, strength " + std::to_string(strength));
}

}  // namespace stochtex
