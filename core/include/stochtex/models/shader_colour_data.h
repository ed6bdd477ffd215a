// stochtex — the colour part of a texture (paper 000 §7 steps 2–4: histogram maps, colour basis,
// mean) reduced to plain numbers, for programs that re-implement the core's ColourMapping outside
// it: the OSL shaders written by `stex osl` (osl/stochtex_colour.h, docs/osl.md).
//
//   y_c = no histogram map: z_c · sigma_m[c]
//         else Σ_i gh_weight[i] · f_c(z_c + dropped_c · gh_node[i])   (one f_c(z_c) when dropped_c < 1e-4)
//   rgb = mean + basis · y
// f_c the monotone cubic Hermite through (z, value) with tangents `slope`, clamped to the end values.
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
};

ShaderColourData shader_colour_data(const TextureDescription& description);

}  // namespace stochtex
