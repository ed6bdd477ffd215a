// stochtex — baking a texture into a tiled, MIP-mapped image file (`stex bake`, the Blender
// add-on's baked route, any renderer that reads texture maps).
//
// The file holds exactly the levels of MipImage (mip_image.h): level 0 is one period of the
// texture made periodic, so the map repeats without a seam, and every level is the model's own
// filtered evaluation at that level's texel footprint, not a box-filtered copy of the level
// above. Renderers that MIP-map (OIIO's TextureSystem, RenderMan, Arnold) use those levels as
// they are; renderers that read level 0 only (Blender) still get a seamless, correctly
// filtered map at the baked resolution.
#pragma once

#include <stochtex/progress.h>
#include <stochtex/texture_description.h>

#include <string>

namespace stochtex {

struct BakeOptions {
    int width = 1024, height = 1024;  ///< level-0 size in texels
    /// Exemplar (photo) pixels per level-0 texel: 1 keeps the photo's pixel scale, so the map
    /// covers width / pixels_per_unit texture units.
    double scale = 1.0;
    int tile_size = 64;               ///< a power of two in [8, 4096]
    bool half = false;                ///< 16-bit half floats (half the bytes; ~3 decimal digits)
    int threads = 0;                  ///< 0: all cores; the file does not depend on it
};

/// What a bake wrote, for the caller's message.
struct BakeSummary {
    int levels = 0;
    double period_u = 0, period_v = 0;  ///< texture units covered by level 0
};

/// Writes a tiled, MIP-mapped OpenEXR (or any tiled MIP-capable format OIIO writes, by the
/// file's extension) to `path`, atomically: a temporary file beside it is renamed at the end,
/// so an interrupted bake never leaves a truncated map under the final name. Pixels are
/// scene-linear Rec.709 RGB, wrap mode periodic. Throws Error naming the file on failure.
BakeSummary bake_mip_image(const TextureDescription& description, const std::string& path, const BakeOptions& options,
                           const ProgressCallback& progress = {});

/// The solid (3D) texture baked onto a surface's UV layout. `positions_path` is a float image
/// whose texels hold surface positions (R, G, B = x, y, z; Blender's Cycles bakes it from object
/// coordinates) and whose alpha is > 0 where the surface covers the texel (Blender's bakes are
/// opaque: every texel). Each covered texel becomes eval_solid() at position ·
/// units_per_position (texture units), its footprint the distance to the neighbouring texels'
/// positions (the shorter side, so island borders do not blur), so the map is filtered at its
/// own resolution; uncovered texels are black with alpha 0. Because every texel is the solid
/// texture at its 3D point, UV seams and sharp edges show no discontinuity beyond a texel.
/// Writes a float EXR (RGBA, one level) atomically. Throws Error naming the files.
BakeSummary bake_solid_map(const TextureDescription& description, const std::string& positions_path,
                           const std::string& path, double units_per_position, int threads = 0,
                           const ProgressCallback& progress = {});

}  // namespace stochtex
