// stochtex — a wavelet texture reduced to plain numbers, for programs that re-implement its
// synthesis outside the core: the OSL shaders written by `stex osl` (docs/osl.md).
//
// With these numbers and the two noise tiles, this reproduces Texture::eval() and eval_solid()
// of make_texture(description) (the non-periodic texture) up to float rounding:
//
//   footprint_px = footprint's major axis (texture units) · pixels_per_unit
//   fade_j       = band fade of band j at footprint_px (1 below 2^j, 0 from 2^(j+1), in between
//                  1 − s²(3 − 2s) with s = log2(footprint_px) − j)
//   kept_c       = Σ_j fade_j · weight[c][j] · N(p · scale[j] + offset[c][j])
//                  N: the quadratic B-spline over tile_2d (2D) or tile_3d (solid, times solid_gain)
//   dropped_c    = sqrt(σ_N² · Σ_j (1 − fade_j²) weight[c][j]²) / sigma_m[c]
//   y_c          = histogram map c absent: kept_c (times solid_gain in solid mode)
//                  else Σ_i gh_weight[i] · f_c(z_c + dropped_c · gh_node[i]), z_c = kept_c / sigma_m[c]
//                  (f_c the monotone cubic Hermite through (z, value) with tangents `slope`,
//                  clamped to the end values; one plain f_c(z_c) when dropped_c < 1e-4)
//   rgb          = mean + basis · y   (colour: shader_colour_data.h)
#pragma once

#include <stochtex/models/shader_colour_data.h>
#include <stochtex/texture_description.h>

#include <array>
#include <vector>

namespace stochtex {

struct WaveletShaderData {
    int band_count = 0;
    double pixels_per_unit = 0;
    double sigma_n2 = 0;                 ///< σ_N² of the 2D tile (the variance that filtering removes)
    std::array<double, 3> sigma_m{};     ///< per decorrelated channel (eq. 2)
    double solid_gain = 1;               ///< sqrt(σ_N²(2D) / σ_N²(3D))
    std::array<std::vector<double>, 3> weight;               ///< [c][j]
    std::vector<double> scale;                               ///< [j]: texture units → lattice units
    std::array<std::vector<std::array<double, 3>>, 3> offset;  ///< [c][j]: lattice units (x, y, z)
    ShaderColourData colour;  ///< histogram maps, Gauss–Hermite rule, colour basis and mean
};

/// Throws Error if the description is invalid or it is not a wavelet texture.
WaveletShaderData wavelet_shader_data(const TextureDescription& description);

/// A periodic noise coefficient tile: width × height × depth floats, x fastest. Lattice cell
/// (i, j, k) of the band's B-spline reads coefficient (i mod width, j mod height, k mod depth);
/// the spline over cells first … first + 2 on each axis with first = floor(x − ½).
struct NoiseTile {
    int width = 0, height = 0, depth = 1;
    std::vector<float> coefficients;
};
NoiseTile wavelet_noise_tile_2d();
NoiseTile wavelet_noise_tile_3d();

}  // namespace stochtex
