#include <stochtex/error.h>
#include <stochtex/models/gabor_parameters.h>
#include <stochtex/models/gabor_shader_data.h>
#include <stochtex/stex_file.h>

#include "models/gabor/gabor_noise.h"
#include "models/gabor/gabor_texture.h"

#include <cmath>

namespace stochtex {

GaborShaderData gabor_shader_data(const TextureDescription& description)
{
    if (description.model != "gabor")
        throw Error("model '" + description.model + "' has no gabor shader data (only the gabor model)");
    validate(description, "texture");
    const GaborParameters& gabor = description.parameters.get<GaborParameters>();
    GaborShaderData data;
    data.pixels_per_unit = description.pixels_per_unit;
    data.kind = int(gabor.kind);
    data.direction = gabor.direction;
    data.direction_length = std::sqrt(dot3(gabor.direction, gabor.direction));
    // The numbers are read from the noises the core evaluates, never recomputed: an exporter
    // cannot drift from the synthesis.
    for (std::size_t k = 0; k < gabor.frequencies.size(); ++k) {
        const GaborNoise noise(gabor_octave(description, k));
        const GaborNoiseParameters& p = noise.parameters();
        if (k == 0) {
            data.channels = p.channels;
            data.plane_e1 = noise.plane_e1();
            data.plane_e2 = noise.plane_e2();
        }
        GaborShaderOctave octave;
        octave.frequency = p.frequency;
        octave.bandwidth = p.bandwidth;
        octave.radius = noise.radius();
        octave.cell_2d = noise.cell_size_2d()[0];
        octave.cell_3d = noise.cell_size_3d();
        octave.gain_2d = noise.gain_2d();
        octave.gain_3d = noise.gain_3d();
        for (int c = 0; c < 3; ++c) octave.weight[c] = gabor.weights[c][k];
        octave.key_2d = noise.key_2d();
        octave.key_3d = noise.key_3d();
        if (gabor.kind == GaborKind::oriented) {
            octave.oriented_fraction = p.oriented_fraction;
            // ω = F · direction / |direction|, as GaborNoise's constructor forms it.
            const double length = std::sqrt(dot3(p.direction, p.direction));
            for (int e = 0; e < 3; ++e) octave.orientation[e] = p.direction[e] / length;
            octave.oriented_below = noise.oriented_bound();
        }
        data.octaves.push_back(octave);
    }
    for (int c = 0; c < 3; ++c) data.sigma_m[c] = gabor_channel_sigma(gabor.weights[c]);
    data.colour = shader_colour_data(description);
    return data;
}

}  // namespace stochtex
