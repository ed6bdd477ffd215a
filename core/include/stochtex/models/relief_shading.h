// stochtex — test data for relightable textures: a height field with an albedo, lit by a
// directional light with a known model (Lambertian reflection and cast shadows), so that the
// truth under any light is known (docs/models/ptm.md, "Test data").
//
// Frame: x to the image's right, y to its top, z out of the surface, as for PTM light
// directions (ptm.h). One texel is one horizontal unit; heights are in texels.
#pragma once

#include <stochtex/footprint.h>
#include <stochtex/image.h>

#include <string>
#include <vector>

namespace stochtex {

struct ReliefSurface {
    int width = 0, height = 0;
    std::vector<float> heights;  ///< texels, rows top to bottom; the surface repeats periodically
    Image albedo;                ///< scene-linear RGB diffuse albedo
};

/// The surface of a grey height map (values used as data: never colour-converted), box-filtered
/// down by `downsample`, with heights value · depth texels. The albedo is a function of the
/// height: darker, browner in the hollows, lighter and greyer on the ridges, so lrgb and rgb
/// PTMs have a chroma to carry. Throws Error naming the file.
ReliefSurface make_relief_surface(const std::string& height_map_path, int downsample, double depth);

/// Unit normals from central differences (periodic): 3 channels (x, y, z).
Image relief_normals(const ReliefSurface& surface);

/// Radiance albedo · max(0, n·l) · visibility for a unit light direction l (z > 0), visibility
/// 0 where the height field blocks the light (a ray marched at ½ texel steps over the bilinear
/// height field, periodic). Light intensity 1 (radiance = albedo for a light along the normal).
Image shade_relief(const ReliefSurface& surface, const Vec3& light);

/// Pixels [x, x + width) × [y, y + height) of an image (periodic: the region may wrap).
Image crop_periodic(const Image& image, int x, int y, int width, int height);

}  // namespace stochtex
