// stochtex — filling images with a texture, on all cores.
#pragma once

#include <stochtex/image.h>
#include <stochtex/progress.h>
#include <stochtex/texture.h>

namespace stochtex {

/// A raster view of texture space: pixel (x, y) has its centre at
///   u = origin_u + (x + 0.5) * units_per_pixel,  v = origin_v + (y + 0.5) * units_per_pixel
/// (square pixels; rows go down in v). Solid renders evaluate the plane w = z with normal +w.
struct RenderSettings {
    int width = 512;
    int height = 512;
    double origin_u = 0;
    double origin_v = 0;
    double units_per_pixel = 1.0 / 512;
    bool solid = false;
    double z = 0;
    /// true: each pixel is filtered with its own footprint (units_per_pixel square);
    /// false: point samples (aliasing reference, tests).
    bool filter = true;
    /// Worker threads; 0 = all cores. The result does not depend on it.
    int threads = 0;
};

/// Renders the whole raster as scene-linear RGB.
Image render(const Texture& texture, const RenderSettings& settings, const ProgressCallback& progress = {});

/// Renders pixels [x0, x0+w) × [y0, y0+h) of the raster into `rgb` (w*h*3 floats, rows top to
/// bottom) on the calling thread: the entry point for tile-based consumers (the OIIO plugin).
void render_region(const Texture& texture, const RenderSettings& settings, int x0, int y0, int w, int h,
                   float* rgb);

}  // namespace stochtex
