// stochtex — Tiling and blending: the parameters block of a tiling .stex (models/tiling/).
// The declaration of these fields (keys, ranges, defaults, docs) is the model's parameter schema,
// in core/src/models/tiling/; docs/stex-format.md lists it.
#pragma once

#include <stochtex/texture_description.h>

#include <string>

namespace stochtex {

/// What the blended channels of a tiling texture are (docs/models/tiling.md).
enum class TilingOutput {
    colour,      ///< 3 decorrelated colour channels: histogram maps, then rgb = mean + basis · y
    colour_map,  ///< 2 noises in [0, 1] indexing a 2D colour map (colour-mapped noise vector field)
    normal_map,  ///< 2 slopes (∂h/∂x, ∂h/∂y) per exemplar pixel: a normal map, LEAN-filtered
};
const char* to_string(TilingOutput output);
TilingOutput tiling_output_from_string(const std::string& name);  // throws Error

/// Tiling and blending of an exemplar (paper 002 §1: Heitz–Neyret 2018, Deliot–Heitz 2019).
struct TilingParameters {
    TilingOutput output = TilingOutput::colour;
    /// Edge of the triangle grid in exemplar widths (of the shorter side); 1/(2√3) is Deliot–Heitz's.
    double triangle_edge = 0.28867513459481287;
    /// The footprint estimator's taps per footprint axis (taps × taps on an isotropic footprint):
    /// 2, the default, halves the filtered mean's error of 1, the paper's single per-texel
    /// estimate, which renders ≈ 2.4× faster (docs/models/tiling.md, "Speed or accuracy").
    int filter_taps = default_filter_taps;
    static constexpr int default_filter_taps = 2, max_filter_taps = 4;
    /// Blend contrast γ: the tiles' weights are B^γ / ‖B^γ‖₂ (B barycentric), so Σ w² = 1 still
    /// holds; γ > 1 lets the nearest tile dominate and fewer tiles show through each other
    /// (Mikkelsen 2022's weight contrast). 1, the default, is Heitz–Neyret's blend
    /// (docs/models/tiling.md, "Blend contrast").
    double blend_contrast = 1;
    static constexpr double max_blend_contrast = 16;
    /// Periodic, sides powers of two. colour: 3 channels y (histogram-Gaussianised or centred);
    /// colour_map: 2 noises in [0, 1]; normal_map: 2 slopes.
    QuantisedImage exemplar;
    /// colour_map only (else empty): S as 3 channels of sRGB-encoded values in [0, 1]; x follows
    /// noise 0, y noise 1.
    QuantisedImage colour_map;
};

}  // namespace stochtex
