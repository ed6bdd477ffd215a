#include <stochtex/bake.h>
#include <stochtex/error.h>
#include <stochtex/mip_image.h>
#include <stochtex/render.h>
#include <stochtex/texture.h>
#include <stochtex/throughput.h>

#include "image/image_codec.h"
#include "parallel/parallel_for.h"
#include "schema/parameter_schema.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <unistd.h>
#include <vector>

namespace stochtex {

namespace {

namespace fs = std::filesystem;

/// `repetitions` timings of run() (each returning its item count) → median, min, max rate.
ThroughputResult timed(const std::string& route, const std::string& detail, int repetitions,
                       const std::function<double()>& run)
{
    std::vector<double> rates;
    for (int r = 0; r < repetitions; ++r) {
        const auto start = std::chrono::steady_clock::now();
        const double items = run();
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        rates.push_back(items / std::max(seconds, 1e-9) * 1e-6);
    }
    std::sort(rates.begin(), rates.end());
    const std::size_t n = rates.size();
    const double median = n % 2 ? rates[n / 2] : 0.5 * (rates[n / 2 - 1] + rates[n / 2]);
    return {route, detail, median, rates.front(), rates.back()};
}

/// A temporary folder removed when the measurement ends (even by an exception).
struct TemporaryFolder {
    fs::path path;
    TemporaryFolder() : path(fs::temp_directory_path() / ("stochtex-bench-" + std::to_string(::getpid())))
    {
        fs::create_directories(path);
    }
    ~TemporaryFolder()
    {
        std::error_code ignored;
        fs::remove_all(path, ignored);
    }
};

}  // namespace

std::vector<ThroughputResult> measure_throughput(const TextureDescription& description, const ThroughputSettings& s)
{
    if (s.size < 16 || s.size > 8192) throw Error("bench: --size must be in [16, 8192], got " + std::to_string(s.size));
    if (!(s.scale > 0)) throw Error("bench: --scale must be positive");
    if (s.threads < 0) throw Error("bench: --threads must be ≥ 0 (0: all cores)");
    if (s.repetitions < 1 || s.repetitions > 100) throw Error("bench: --repetitions must be in [1, 100]");
    const int threads = thread_count(s.threads);
    const std::unique_ptr<Texture> texture = make_texture(description);
    // Built first, so that a bad tile size is reported before anything is timed.
    const ImageLayout layout{s.size, s.size, s.tile, s.tile, s.scale, "RGB"};
    const MipImage image(description, layout, "bench");
    const double pixels = double(s.size) * s.size;
    const std::string raster = std::to_string(s.size) + "², " + number_text(s.scale) + " exemplar px per pixel, filtered, " +
                               std::to_string(threads) + " thread(s)";
    std::vector<ThroughputResult> results;

    RenderSettings render_settings;
    render_settings.width = render_settings.height = s.size;
    render_settings.units_per_pixel = s.scale / description.pixels_per_unit;
    render_settings.threads = threads;
    results.push_back(timed("2D raster", "render(): eval_region, " + raster, s.repetitions, [&] {
        render(*texture, render_settings);
        return pixels;
    }));
    render_settings.solid = true;
    results.push_back(timed("solid slice", "render --solid: eval_solid_region on w = 0, " + raster, s.repetitions, [&] {
        render(*texture, render_settings);
        return pixels;
    }));

    // The plugin's route: one period as a MipImage, level 0 filled tile by tile.
    const int tiles_x = (s.size + s.tile - 1) / s.tile, tiles = tiles_x * tiles_x;
    results.push_back(timed("plugin tiles",
                            "MipImage::fill (the OIIO plugin's tile path), level 0 in " + std::to_string(s.tile) + "² tiles, " +
                                raster,
                            s.repetitions, [&] {
                                parallel_for(tiles, threads, [&](int t) {
                                    std::vector<float> tile(std::size_t(s.tile) * s.tile * 3);
                                    const int x0 = t % tiles_x * s.tile, y0 = t / tiles_x * s.tile;
                                    image.fill(0, x0, y0, std::min(s.tile, s.size - x0), std::min(s.tile, s.size - y0),
                                               tile.data());
                                });
                                return pixels;
                            }));

    // The reference: the same period baked to a tiled MIP-mapped EXR, read by the TextureSystem.
    const TemporaryFolder folder;
    const std::string baked = (folder.path / "baked.exr").string();
    BakeOptions bake;
    bake.width = bake.height = s.size;
    bake.scale = s.scale;
    bake.tile_size = s.tile;
    bake.threads = threads;
    bake_mip_image(description, baked, bake);
    // OIIO's TextureSystem lives in the OpenImageIO module (image_codec.h).
    codec::ImageCodec& oiio = codec::oiio_codec("bench: the TextureSystem reference");
    auto lookups = [&](codec::TextureLookups& system) {
        const std::string error = system.run(baked, s.size, threads);
        if (!error.empty()) throw Error("bench: " + error);
        return pixels;
    };
    const std::string lookup_detail =
        "OIIO TextureSystem on the texture baked to a " + std::to_string(s.size) + "² tiled MIP-mapped EXR, one lookup per texel, " +
        "one-texel footprint, " + std::to_string(threads) + " thread(s)";
    results.push_back(timed("baked lookup (cold)", lookup_detail + ", a fresh TextureSystem per run", s.repetitions, [&] {
        return lookups(*oiio.texture_lookups());
    }));
    const std::unique_ptr<codec::TextureLookups> system = oiio.texture_lookups();
    lookups(*system);
    results.push_back(timed("baked lookup (warm)", lookup_detail + ", tiles cached", s.repetitions, [&] { return lookups(*system); }));
    return results;
}

}  // namespace stochtex
