// TextureSystem lookups on a .stex (through the stex.imageio plugin) versus the same texture
// baked by maketx (ImageBufAlgo::make_texture, what the maketx tool calls) to a tiled,
// MIP-mapped .tx on disk: same lookups, same filter, same thread count, in one run.
//
//   texture_system_bench [size=2048] [lookups=400000] [repetitions=5]
//
// cold: a fresh TextureSystem per repetition (the procedural file generates every tile it
//       touches; the baked file reads and decompresses them, from the OS page cache after the
//       first repetition — an optimistic "cold" for the baked file);
// warm: the same lookups again on that TextureSystem (tiles already cached).
// Prints the medians in M lookups/s, the ratio procedural / baked, and the bytes on disk.
#include "image/private_texture_system.h"
#include "median.h"

#include <stochtex/analysis.h>
#include <stochtex/image.h>
#include <stochtex/stex_file.h>
#include <stochtex/models/wavelet_parameters.h>

#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/texture.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;
using namespace OIIO;

namespace {

struct Lookup {
    float s, t, dsdx, dtdx, dsdy, dtdy;
};

/// Random positions; footprints log-uniform from a quarter texel to 64 texels of level 0, with
/// anisotropy up to 4:1 (what a renderer's camera rays produce on a receding plane).
std::vector<Lookup> make_lookups(int count, int size)
{
    std::mt19937 rng(2026);
    std::uniform_real_distribution<float> unit(0, 1), exponent(-2, 6), ratio(1, 4), angle(0, 6.2831853f);
    std::vector<Lookup> lookups(count);
    for (Lookup& l : lookups) {
        const float major = std::exp2(exponent(rng)) / size, minor = major / ratio(rng), a = angle(rng);
        l = {unit(rng), unit(rng), major * std::cos(a), major * std::sin(a), -minor * std::sin(a), minor * std::cos(a)};
    }
    return lookups;
}

/// Runs all lookups on `threads` threads (contiguous shares) and returns the wall time in s.
double run(TextureSystem& ts, ustring file, const std::vector<Lookup>& lookups, int threads)
{
    const auto start = std::chrono::steady_clock::now();
    std::vector<std::thread> workers;
    const std::size_t share = (lookups.size() + threads - 1) / threads;
    for (int t = 0; t < threads; ++t)
        workers.emplace_back([&, t] {
            TextureOpt options;
            options.swrap = options.twrap = TextureOpt::WrapPeriodic;
            TextureSystem::Perthread* thread = ts.get_perthread_info();
            TextureSystem::TextureHandle* handle = ts.get_texture_handle(file, thread);
            float result[3];
            const std::size_t end = std::min(lookups.size(), (t + 1) * share);
            for (std::size_t i = t * share; i < end; ++i) {
                const Lookup& l = lookups[i];
                ts.texture(handle, thread, options, l.s, l.t, l.dsdx, l.dtdx, l.dsdy, l.dtdy, 3, result);
            }
        });
    for (auto& worker : workers) worker.join();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv)
{
    const int size = argc > 1 ? std::atoi(argv[1]) : 2048;
    const int count = argc > 2 ? std::atoi(argv[2]) : 400000;
    const int repetitions = argc > 3 ? std::atoi(argv[3]) : 5;
    const int threads = int(std::max(1u, std::thread::hardware_concurrency()));
    if (size < 64 || count < 1000 || repetitions < 1) {
        std::fprintf(stderr, "usage: texture_system_bench [size>=64] [lookups>=1000] [repetitions>=1]\n");
        return 2;
    }
    OIIO::attribute("plugin_searchpath", STOCHTEX_PLUGIN_DIR);

    const fs::path dir = fs::temp_directory_path() / "stochtex-texture-system-bench";
    fs::create_directories(dir);
    const std::string stex = (dir / "concrete.stex").string(), baked = (dir / "concrete.tx").string();
    stochtex::TextureDescription d = stochtex::analyze(
        stochtex::read_image_linear(std::string(STOCHTEX_SOURCE_DIR) + "/data/exemplars/concrete_512.png"), {});
    d.image = stochtex::ImageLayout{size, size, 64, 64, 1.0, "RGB"};
    stochtex::write_stex(stex, d);

    std::printf("texture: concrete_512.png analysed (wavelet, %zu bands), virtual image %dx%d float RGB, 64² tiles\n",
                d.parameters.get<stochtex::WaveletParameters>().band_weights[0].size(), size, size);
    const auto bake_start = std::chrono::steady_clock::now();
    ImageSpec config;
    config.tile_width = config.tile_height = 64;
    config.attribute("wrapmodes", "periodic,periodic");
    if (!ImageBufAlgo::make_texture(ImageBufAlgo::MakeTxTexture, stex, baked, config)) {
        std::fprintf(stderr, "maketx failed: %s\n", OIIO::geterror().c_str());
        return 1;
    }
    std::printf("baked with maketx (float, zip, 64² tiles, box-filtered MIP levels) in %.1f s\n",
                std::chrono::duration<double>(std::chrono::steady_clock::now() - bake_start).count());

    const std::vector<Lookup> lookups = make_lookups(count, size);
    std::printf("%d lookups per run, anisotropic filter (TextureOpt defaults), %d threads, %d repetitions, medians:\n",
                count, threads, repetitions);
    struct Result {
        double cold, warm;
    };
    auto measure = [&](const std::string& file) {
        std::vector<double> cold, warm;
        for (int r = 0; r < repetitions; ++r) {
            const stochtex::PrivateTextureSystem ts = stochtex::make_private_texture_system();
            ts->attribute("max_memory_MB", 1024.0f);
            cold.push_back(count / run(*ts, ustring(file), lookups, threads) * 1e-6);
            warm.push_back(count / run(*ts, ustring(file), lookups, threads) * 1e-6);
        }
        return Result{median(cold), median(warm)};
    };
    const Result procedural = measure(stex), reference = measure(baked);
    const auto stex_bytes = fs::file_size(stex), baked_bytes = fs::file_size(baked);
    std::printf("  %-34s cold %7.3f M lookups/s   warm %7.3f M lookups/s   %10ju bytes\n", ".stex (procedural, plugin)",
                procedural.cold, procedural.warm, std::uintmax_t(stex_bytes));
    std::printf("  %-34s cold %7.3f M lookups/s   warm %7.3f M lookups/s   %10ju bytes\n", ".tx (maketx, baked)",
                reference.cold, reference.warm, std::uintmax_t(baked_bytes));
    std::printf("comparison: procedural / baked = %.2fx cold, %.2fx warm; size %.5f %% of the baked file\n",
                procedural.cold / reference.cold, procedural.warm / reference.warm, 100.0 * stex_bytes / baked_bytes);
    fs::remove_all(dir);
    return 0;
}
