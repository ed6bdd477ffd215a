// stochtex — Polynomial texture maps: the parameters block of a ptm .stex (models/ptm/).
// The declaration of these fields (keys, ranges, defaults, docs) is the model's parameter schema,
// in core/src/models/ptm/; docs/stex-format.md lists it.
#pragma once

#include <array>
#include <memory>
#include <string>

namespace stochtex {

/// How a PTM models colour (paper 004 builds on Malzbender et al.'s PTMs, which have both).
enum class PtmColour {
    lrgb,  ///< one luminance function per texel times a per-texel chroma (9 numbers per texel)
    rgb,   ///< one function per colour channel (18 numbers per texel)
};
const char* to_string(PtmColour colour);
PtmColour ptm_colour_from_string(const std::string& name);  // throws Error

struct PtmMaps;  // stochtex/models/ptm.h

/// A polynomial texture map (paper 004): per texel a reflectance function of the light
/// direction, evaluated for `light`. The coefficient maps live in a float EXR beside the .stex
/// (docs/stex-format.md, section ptm); read_stex loads them, write_stex writes them.
struct PtmParameters {
    PtmColour colour = PtmColour::lrgb;
    /// File name of the coefficient maps beside the .stex (no directories). write_stex names
    /// it after the .stex it writes: "<stem>.ptm.exr".
    std::string coefficient_file;
    /// Unit light direction the texture is evaluated for: x to the image's right, y to its top,
    /// z out of the surface (z > 0). Open-time hint: stex:light (stochtex/lighting.h).
    std::array<double, 3> light{0, 0, 1};
    /// The maps (shared by copies of the description; never modified once loaded).
    std::shared_ptr<const PtmMaps> maps;
    /// Unbounded (docs/models/ptm.md, "Unbounded"): the maps — periodic — tiled and blended over
    /// a triangle grid (the tiling model's, seeded by the description's seed), all coefficient
    /// fields with the same tiles; false: the maps repeat.
    bool unbounded = false;
    /// The grid's triangle edge in maps widths (of the shorter side), unbounded only.
    double triangle_edge = 0.28867513459481287;
};

}  // namespace stochtex
