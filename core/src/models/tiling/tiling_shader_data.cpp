#include <stochtex/error.h>
#include <stochtex/models/tiling_parameters.h>
#include <stochtex/models/tiling_shader_data.h>
#include <stochtex/stex_file.h>

#include "models/tiling/tiling_texture.h"
#include "schema/parameter_schema.h"

#include <algorithm>

namespace stochtex {

TilingShaderData tiling_shader_data(const TextureDescription& description)
{
    if (description.model != "tiling")
        throw Error("model '" + description.model + "' has no tiling shader data (only the tiling model)");
    validate(description, "texture");
    const TilingParameters& parameters = description.parameters.get<TilingParameters>();
    if (parameters.output == TilingOutput::colour_map)
        throw Error("tiling texture with output colour_map: no OSL transcription (its filtered colour-map table); "
                    "use osl/stochtex_texture.osl with the OIIO plugin, or a baked map");
    // The transcription blends with B / ‖B‖ (osl/stochtex_tiling.h): refuse rather than render
    // another texture.
    if (parameters.blend_contrast != 1)
        throw Error("tiling texture with parameters.blend_contrast " + number_text(parameters.blend_contrast) +
                    ": no OSL transcription (the shader blends with contrast 1); use osl/stochtex_texture.osl with the "
                    "OIIO plugin, or a baked map");
    // The numbers are read from the texture the core evaluates, never recomputed.
    const TilingTexture texture(description);
    const TilingNoise& noise = texture.noise();
    const MomentPyramid& pyramid = noise.pyramid();
    const FootprintSampling& sampling = texture.options().sampling;
    if (sampling.interpolation != TexelInterpolation::linear)
        throw Error("tiling shader data: only the linear texel interpolation has a shader form");
    TilingShaderData data;
    data.pixels_per_unit = description.pixels_per_unit;
    data.output = int(parameters.output);
    data.channels = pyramid.channels();
    data.width = pyramid.width();
    data.height = pyramid.height();
    data.level_count = pyramid.level_count();
    data.seed = noise.grid().seed();
    data.edge_x = noise.grid().edges()[0];
    data.edge_y = noise.grid().edges()[1];
    data.taps = sampling.taps;
    data.max_taps = sampling.max_taps;
    const Moments global = noise.global();
    for (int c = 0; c < data.channels; ++c) data.global_mean[c] = global.mean[c];

    constexpr int stride = 9;
    for (int l = 0; l < data.level_count; ++l) data.atlas_height += std::max(1, data.height >> l);
    data.atlas.assign(std::size_t(data.width) * data.atlas_height * stride, 0.0f);
    const int pairs[6][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}};
    int row = 0;
    for (int l = 0; l < data.level_count; ++l) {
        const int lw = std::max(1, data.width >> l), lh = std::max(1, data.height >> l);
        for (int y = 0; y < lh; ++y)
            for (int x = 0; x < lw; ++x) {
                const Moments m = pyramid.texel(l, x, y);
                float* texel = &data.atlas[(std::size_t(row + y) * data.width + x) * stride];
                for (int c = 0; c < data.channels; ++c) texel[c] = float(m.mean[c]);
                for (int p = 0; p < 6; ++p)
                    if (pairs[p][1] < data.channels) texel[3 + p] = float(m.moment(pairs[p][0], pairs[p][1]));
            }
        row += lh;
    }
    data.colour = shader_colour_data(description);
    return data;
}

}  // namespace stochtex
