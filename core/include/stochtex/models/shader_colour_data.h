// stochtex — the colour part of a texture (paper 000 §7 steps 2–4: histogram maps, colour basis,
// mean) reduced to plain numbers, for programs that re-implement the core's ColourMapping outside
// it: the OSL shaders written by `stex osl` (osl/stochtex_colour.h, docs/osl.md).
//
//   y_c = no histogram map: z_c · sigma_m[c]
//         else Σ_i gh_weight[i] · f_c(z_c + dropped_c · gh_node[i])   (one f_c(z_c) when dropped_c < 1e-4)
//   joint colour (chroma_given_brightness enabled), c = 1, 2:
//         y_c = L_c(z_0, dropped_0) + S_c(z_0, dropped_0) · y_c, where L_c (S_c) is location_c (scale_c)
//         at z_0, or Σ_i gh_weight[i] · location_c(z_0 + dropped_0 · gh_node[i]) when dropped_0 ≥ 1e-4
//   rgb = mean + basis · y
// f_c the monotone cubic Hermite through (z, value) with tangents `slope`, clamped to the end values;
// location_c and scale_c linear between uniform knots z, constant beyond the ends.
#pragma once

#include <stochtex/texture_description.h>

#include <array>
#include <vector>

namespace stochtex {

struct ShaderColourData {
    std::array<double, 3> mean{};
    std::array<std::array<double, 3>, 3> basis{};  ///< basis[row][column]
    struct HistogramCurve {
        std::vector<double> z, value, slope;  ///< empty: the channel stays Gaussian
    };
    std::array<HistogramCurve, 3> histogram;
    std::vector<double> gh_node, gh_weight;  ///< E[f(Z)] ≈ Σ weight_i f(node_i), Z ~ N(0, 1)
    ChromaGivenBrightness chroma_given_brightness;  ///< joint colour's curves; empty: independent channels
};

ShaderColourData shader_colour_data(const TextureDescription& description);

}  // namespace stochtex
