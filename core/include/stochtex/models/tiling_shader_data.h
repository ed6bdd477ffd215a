// stochtex — a tiling texture reduced to plain numbers and one image, for programs that
// re-implement its synthesis outside the core: the OSL shader written by `stex osl`
// (osl/stochtex_tiling.h, docs/osl.md). With them, osl/stochtex_tiling.h reproduces
// Texture::eval() of make_texture(description) (the 2D, non-periodic texture):
//
//   grid     triangles of edge (edge_x, edge_y) exemplar pixels; vertex (i, j) at
//            (edge_x (i + j/2), edge_y (√3/2) j) draws its offset from SplitMix64(mix_seed(seed, i, j))
//   tiles    the exemplar read at p + round(offset · size − centre), blended with w = B / |B|
//   filter   the footprint estimator's taps (taps, max_taps), each a texel estimate at the
//            level of its spacing in the moment pyramid (the atlas below)
//   output   colour: ShaderColourData's mapping with each channel's spread; normal_map: the
//            encoded normal of the mean slopes.
#pragma once

#include <stochtex/models/shader_colour_data.h>
#include <stochtex/texture_description.h>

#include <array>
#include <cstdint>
#include <vector>

namespace stochtex {

struct TilingShaderData {
    double pixels_per_unit = 0;
    int output = 0;  ///< TilingOutput: 0 colour, 2 normal_map (colour_map has no shader form)
    int channels = 0;
    int width = 0, height = 0;  ///< the exemplar, exemplar pixels (powers of two)
    int level_count = 0;        ///< moment pyramid levels, level 0 the exemplar
    std::uint32_t seed = 0;
    double edge_x = 0, edge_y = 0;  ///< the grid's triangle edges, exemplar pixels
    int taps = 2, max_taps = 8;     ///< the footprint estimator's sampling
    std::array<double, 3> global_mean{};  ///< ν: the exemplar's exact mean
    /// The pyramid as one image of width × atlas_height texels, 9 channels (means of 3 channels,
    /// then the centred second moments (0,0) (0,1) (0,2) (1,1) (1,2) (2,2); absent channels 0);
    /// level l's max(1, w >> l) × max(1, h >> l) texels start at row Σ_{k<l} max(1, h >> k).
    int atlas_height = 0;
    std::vector<float> atlas;  ///< row-major, 9 floats per texel
    ShaderColourData colour;
};

/// Throws Error if the description is invalid, not a tiling texture, or one without a shader
/// form (the colour_map output).
TilingShaderData tiling_shader_data(const TextureDescription& description);

}  // namespace stochtex
