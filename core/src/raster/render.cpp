#include <stochtex/error.h>
#include <stochtex/render.h>

#include "parallel/parallel_for.h"

#include <algorithm>

namespace stochtex {

namespace {

/// The raster's positions stay where textures can be evaluated (max_position_pixels): its edges
/// and its depth. Pixel centres lie between the edges, so checking these covers every pixel.
void check_raster_positions(const Texture& texture, const RenderSettings& settings)
{
    const double ppu = texture.description().pixels_per_unit;
    const double d = settings.units_per_pixel;
    check_position(settings.origin_u, ppu, "render: origin_u");
    check_position(settings.origin_v, ppu, "render: origin_v");
    check_position(settings.origin_u + settings.width * d, ppu, "render: the right edge, origin_u + width × units_per_pixel");
    check_position(settings.origin_v + settings.height * d, ppu, "render: the bottom edge, origin_v + height × units_per_pixel");
    if (settings.solid) check_position(settings.z, ppu, "render: z");
}

}  // namespace

void render_region(const Texture& texture, const RenderSettings& settings, int x0, int y0, int w, int h, float* rgb)
{
    check_raster_positions(texture, settings);
    RasterRegion region;
    region.origin_u = settings.origin_u, region.origin_v = settings.origin_v;
    region.du = region.dv = settings.units_per_pixel;
    region.x0 = x0, region.y0 = y0, region.width = w, region.height = h;
    // Filtered: each pixel's footprint is its spacing; unfiltered: point samples.
    region.footprint = settings.filter ? Footprint2D{region.du, 0, 0, region.dv} : Footprint2D::point();
    const RgbOutput out = RgbOutput::interleaved(rgb);
    if (settings.solid)
        texture.eval_solid_region({region, settings.z}, out);
    else
        texture.eval_region(region, out);
}

Image render(const Texture& texture, const RenderSettings& settings, const ProgressCallback& progress)
{
    if (settings.width <= 0 || settings.height <= 0)
        throw Error("render: size must be positive, got " + std::to_string(settings.width) + "x" +
                    std::to_string(settings.height));
    if (!(settings.units_per_pixel > 0))
        throw Error("render: units per pixel must be positive");
    check_raster_positions(texture, settings);
    // A whole-image render holds 12 bytes per pixel; beyond 2^28 pixels (3 GiB) use tiles.
    if (double(settings.width) * settings.height > double(1 << 28))
        throw Error("render: " + std::to_string(settings.width) + "x" + std::to_string(settings.height) +
                    " is too large for one image (at most 2^28 pixels); render it in tiles");
    Image image(settings.width, settings.height, 3);

    // Items are bands of rows; each pixel depends only on its own coordinates, so the image is
    // bit-identical for any thread count and band height. Models share work along a band (lrp's
    // window terms and tables, gabor's cell caches, tiling's shift tables), so taller bands
    // redo less of it (lrp: 16 % less CPU at 64 rows than at 8); four bands per thread at least
    // keep the load balanced.
    const int rows_per_band = std::clamp(settings.height / (4 * thread_count(settings.threads)), 8, 64);
    const int bands = (settings.height + rows_per_band - 1) / rows_per_band;
    parallel_for(bands, settings.threads, [&](int band) {
        const int y0 = band * rows_per_band;
        render_region(texture, settings, 0, y0, settings.width, std::min(rows_per_band, settings.height - y0),
                      &image.pixels[std::size_t(y0) * settings.width * 3]);
    }, {progress, "render"});
    return image;
}

}  // namespace stochtex
