// stochtex — a gabor texture reduced to plain numbers, for programs that re-implement its
// synthesis outside the core: the OSL shader written by `stex osl` (osl/stochtex_gabor.h,
// docs/osl.md). With these numbers and the sphere-average table, osl/stochtex_gabor.h reproduces
// Texture::eval() and eval_solid() of make_texture(description) (the non-periodic texture):
// the same impulses (the cell keys' 64-bit seeds below, SplitMix64 mixing), the same analytic
// filter, the same octave fades and retained variances, then ShaderColourData's mapping.
#pragma once

#include <stochtex/models/shader_colour_data.h>
#include <stochtex/texture_description.h>

#include <array>
#include <cstdint>
#include <vector>

namespace stochtex {

/// One octave's noise (GaborNoise of gabor_octave(description, k)), in exemplar pixels.
struct GaborShaderOctave {
    double frequency = 0, bandwidth = 0;  ///< F and a
    double radius = 0;                    ///< support radius (5 % envelope)
    double cell_2d = 0, cell_3d = 0;      ///< cell sides: one impulse per cell
    double gain_2d = 1, gain_3d = 1;      ///< 1 / σ of the raw kernel sums
    std::array<double, 3> weight{};       ///< per decorrelated channel
    std::uint64_t key_2d = 0, key_3d = 0;  ///< the seed, mixed: cell (i, j[, k]) has key + i·step_i + …
    /// Kind oriented (0 otherwise): the share p_k of oriented impulses, their ω / F, and the bound
    /// p_k·2^53 an impulse's 53-bit draw must be below to be oriented (GaborNoise::oriented_bound).
    double oriented_fraction = 0;
    std::array<double, 3> orientation{0, 0, 0};
    std::uint64_t oriented_below = 0;
};

struct GaborShaderData {
    double pixels_per_unit = 0;
    int kind = 0;  ///< GaborKind: 0 isotropic, 1 anisotropic, 2 hybrid, 3 oriented
    std::array<double, 3> direction{0, 0, 1};  ///< as stored (anisotropic ω = F · direction / length)
    double direction_length = 1;
    std::array<double, 3> plane_e1{1, 0, 0}, plane_e2{0, 1, 0};  ///< hybrid: the plane of ω
    int channels = 3;  ///< 1: rgb-shared (one noise for the three channels)
    std::vector<GaborShaderOctave> octaves;
    std::array<double, 3> sigma_m{};
    ShaderColourData colour;
};

/// Throws Error if the description is invalid or not a gabor texture.
GaborShaderData gabor_shader_data(const TextureDescription& description);

/// The table behind the isotropic retained variance (gabor_statistics.cpp): E over the unit
/// sphere of exp(−α u₁² − β u₂²), size × size values, values[j·size + i] at log(1 + α) = i·step,
/// log(1 + β) = j·step, interpolated bilinearly between nodes.
struct GaborSphereTable {
    int size = 0;
    double step = 0;
    std::vector<float> values;
};
GaborSphereTable gabor_sphere_table();

}  // namespace stochtex
