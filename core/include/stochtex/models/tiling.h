// stochtex — tiling textures that are not analysed from one colour photo (docs/models/tiling.md):
// colour-mapped noise vector fields (two noises indexing a 2D colour map; phasor noise), and
// normal maps from a height photo. (`stex analyze --model tiling` covers colour photos.)
#pragma once

#include <stochtex/image.h>
#include <stochtex/texture.h>
#include <stochtex/texture_description.h>
#include <stochtex/models/tiling_parameters.h>

#include <array>
#include <cstdint>
#include <memory>
#include <string>

namespace stochtex {

struct TilingSourceOptions {
    int exemplar_size = 256;  ///< exemplar sides: the largest powers of two ≤ this (16 … 1024)
    int bits = 8;             ///< 8 or 16 bits per stored sample
    std::uint32_t seed = 1;
    double unit_size_m = 1.0;
    std::string source_name;  ///< recorded in the provenance
    int filter_taps = TilingParameters::default_filter_taps;  ///< stored as TilingParameters::filter_taps
};

/// Two noise photos (their luminance, made periodic, mapped to [0, 1] by mean ± 3σ) index the
/// named colour map (256²: "green", "rgb" or a phasor profile map below). Throws Error for
/// unusable inputs or an unknown map (the error lists the names).
TextureDescription colour_mapped_texture(const Image& noise_a, const Image& noise_b, const std::string& colour_map,
                                         const TilingSourceOptions& options);

/// Phasor noise (rasterised at exemplar_size², `frequency` cycles per pixel) with a phasor
/// profile map ("phasor-sine", "phasor-square", "phasor-sawtooth").
TextureDescription phasor_texture(const std::string& colour_map, double frequency, const TilingSourceOptions& options);

/// A height photo (luminance × strength, in height units per pixel) → its slopes, tiled and
/// blended; renders as a tangent-space normal map filtered LEAN-style.
TextureDescription normal_map_texture(const Image& height, double strength, const TilingSourceOptions& options);

/// Shading a normal_map tiling texture (docs/models/tiling.md, "Normal maps"): Lambert on the
/// mean normal plus a specular lobe whose slope distribution is Gaussian with the footprint's
/// slope covariance added to the base roughness (LEAN mapping) — or, with lean = false, the
/// lobe of the mean normal alone (what filtering the normal map as an image gives).
struct NormalMapShading {
    std::array<double, 3> light{0.5, 0.3, 0.81};  ///< towards the light, tangent space (normalised)
    std::array<double, 3> view{0, 0, 1};          ///< towards the viewer
    double base_roughness = 0.08;                 ///< the facets' own slope standard deviation
    double albedo = 0.5, specular = 0.04;
    bool lean = true;
};

/// A texture whose eval() is that shading (grey, in RGB) of the normal-map texture; render it
/// with render() like any texture. Throws Error unless the description is a normal_map tiling.
std::unique_ptr<Texture> make_shaded_normal_map(const TextureDescription& description, const NormalMapShading& shading);

}  // namespace stochtex
