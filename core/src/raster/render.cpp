#include <stochtex/error.h>
#include <stochtex/render.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

namespace stochtex {

namespace {

/// The raster's positions stay where textures can be evaluated (max_position_pixels): its edges
/// and its depth. Pixel centres lie between the edges, so checking these covers every pixel.
void check_raster_positions(const Texture& texture, const RenderSettings& settings)
{
    const double ppu = texture.description().pixels_per_unit;
    const double du = settings.units_per_pixel, dv = settings.units_per_pixel_v > 0 ? settings.units_per_pixel_v : du;
    check_position(settings.origin_u, ppu, "render: origin_u");
    check_position(settings.origin_v, ppu, "render: origin_v");
    check_position(settings.origin_u + settings.width * du, ppu, "render: the right edge, origin_u + width × units_per_pixel");
    check_position(settings.origin_v + settings.height * dv, ppu, "render: the bottom edge, origin_v + height × units_per_pixel");
    if (settings.solid) check_position(settings.z, ppu, "render: z");
}

}  // namespace

void render_region(const Texture& texture, const RenderSettings& settings, int x0, int y0, int w, int h, float* rgb)
{
    check_raster_positions(texture, settings);
    RasterRegion region;
    region.origin_u = settings.origin_u, region.origin_v = settings.origin_v;
    region.du = settings.units_per_pixel;
    region.dv = settings.units_per_pixel_v > 0 ? settings.units_per_pixel_v : region.du;
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
    if (!(settings.units_per_pixel > 0) || !(settings.units_per_pixel_v >= 0))
        throw Error("render: units per pixel must be positive");
    check_raster_positions(texture, settings);
    // A whole-image render holds 12 bytes per pixel; beyond 2^28 pixels (3 GiB) use tiles.
    if (double(settings.width) * settings.height > double(1 << 28))
        throw Error("render: " + std::to_string(settings.width) + "x" + std::to_string(settings.height) +
                    " is too large for one image (at most 2^28 pixels); render it in tiles");
    Image image(settings.width, settings.height, 3);

    // Workers take bands of rows from a shared counter; each pixel depends only on its own
    // coordinates, so the image is bit-identical for any thread count and band height. Models
    // share work along a band (lrp's window terms and tables, gabor's cell caches, tiling's
    // shift tables), so taller bands redo less of it (lrp: 16 % less CPU at 64 rows than at 8);
    // four bands per worker at least keep the load balanced.
    const int wanted_threads =
        settings.threads > 0 ? settings.threads : int(std::max(1u, std::thread::hardware_concurrency()));
    const int rows_per_chunk = std::clamp(settings.height / (4 * wanted_threads), 8, 64);
    const int chunk_count = (settings.height + rows_per_chunk - 1) / rows_per_chunk;
    const int threads = std::max(1, std::min(chunk_count, wanted_threads));
    std::atomic<int> next_chunk{0}, done_chunks{0};
    std::exception_ptr failure;
    std::mutex mutex;
    std::condition_variable finished;
    auto work = [&] {
        try {
            for (int chunk; (chunk = next_chunk.fetch_add(1)) < chunk_count;) {
                const int y0 = chunk * rows_per_chunk;
                const int rows = std::min(rows_per_chunk, settings.height - y0);
                render_region(texture, settings, 0, y0, settings.width, rows,
                              &image.pixels[std::size_t(y0) * settings.width * 3]);
                done_chunks.fetch_add(1);
            }
        } catch (...) {
            std::lock_guard<std::mutex> lock(mutex);
            if (!failure) failure = std::current_exception();
            next_chunk = chunk_count;
        }
        finished.notify_all();
    };
    std::vector<std::thread> workers;
    for (int t = 0; t < threads; ++t) workers.emplace_back(work);
    if (progress) {
        // Progress is reported from this thread only, so callbacks need no locking.
        std::unique_lock<std::mutex> lock(mutex);
        while (done_chunks.load() < chunk_count && !failure) {
            progress(double(done_chunks.load()) / chunk_count, "render");
            finished.wait_for(lock, std::chrono::milliseconds(100));
        }
    }
    for (auto& worker : workers) worker.join();
    if (failure) std::rethrow_exception(failure);
    if (progress) progress(1.0, "render");
    return image;
}

}  // namespace stochtex
