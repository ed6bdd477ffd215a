#include <stochtex/error.h>
#include <stochtex/stex_file.h>
#include <stochtex/models/wavelet_shader_data.h>
#include <stochtex/models/wavelet_parameters.h>

#include "models/wavelet/wavelet_noise.h"
#include "models/wavelet/wavelet_texture.h"

namespace stochtex {

WaveletShaderData wavelet_shader_data(const TextureDescription& description)
{
    if (description.model != "wavelet")
        throw Error("model '" + description.model + "' has no wavelet shader data (only the wavelet model)");
    validate(description, "texture");
    // The numbers are read back from the texture the core evaluates, never recomputed: an
    // exporter cannot drift from the synthesis.
    const WaveletTexture texture(description);
    WaveletShaderData data;
    data.band_count = int(description.parameters.get<WaveletParameters>().band_weights[0].size());
    data.pixels_per_unit = description.pixels_per_unit;
    data.sigma_n2 = WaveletNoise2D::shared().variance();
    data.sigma_m = texture.sigma_m();
    data.solid_gain = texture.solid_gain();
    for (int j = 0; j < data.band_count; ++j) {
        const auto& first = texture.band(0, std::size_t(j));
        if (first.tile != &WaveletNoise2D::shared() || first.scale[0] != first.scale[1] ||
            first.scale[0] != first.solid_scale || first.gain != 1.0)
            throw Error("wavelet shader data: band " + std::to_string(j) + " does not use the shared tile");
        data.scale.push_back(first.solid_scale);
        for (int c = 0; c < 3; ++c) {
            const auto& band = texture.band(c, std::size_t(j));
            data.weight[c].push_back(band.weight);
            data.offset[c].push_back({band.offset[0], band.offset[1], band.offset[2]});
        }
    }
    data.colour = shader_colour_data(description);
    return data;
}

NoiseTile wavelet_noise_tile_2d()
{
    const WaveletNoise2D& tile = WaveletNoise2D::shared();
    return {tile.period_x(), tile.period_y(), 1, tile.coefficients()};
}

NoiseTile wavelet_noise_tile_3d()
{
    const WaveletNoise3D& tile = WaveletNoise3D::shared();
    return {tile.tile_size(), tile.tile_size(), tile.tile_size(), tile.coefficients()};
}

}  // namespace stochtex
