// The plugin's tile cache (plugin/tile_cache.h) on Cycles 5.2's read pattern: every tile of a
// square block of level 0, each followed by its 8 neighbours (Cycles reads them whole for a
// one-texel border), through ImageInput::read_tiles one tile at a time, as Cycles does. The same
// reads with the cache off (open hint stex:tile_cache_mb = 0) are the reference, in the same run.
//
//   tile_cache_bench [block_tiles=16] [repetitions=5]
//
// Prints, for each: the reads, the tiles made, the reads served from the cache (the plugin's own
// counts, STOCHTEX_TILE_STATS) and the median wall time; and that both gave the same bytes.
#include "median.h"
#include <stochtex/analysis.h>
#include <stochtex/image.h>
#include <stochtex/stex_file.h>

#include <OpenImageIO/imageio.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace OIIO;

namespace {

struct Run {
    double seconds = 0;
    long long reads = 0, made = 0, served = 0;
    std::vector<float> checksum_texels;  // the first read of every tile, concatenated
};

/// One pass of Cycles' pattern over a block × block region of level 0 (wrapping at the edges).
Run cycles_reads(const std::string& path, int block, long long cache_mb, const fs::path& stats)
{
    fs::remove(stats);
    setenv("STOCHTEX_TILE_STATS", stats.c_str(), 1);
    ImageSpec config;
    config.attribute("stex:tile_cache_mb", int(cache_mb));
    Run run;
    const auto start = std::chrono::steady_clock::now();
    {
        auto input = ImageInput::open(path, &config);
        if (!input) {
            std::fprintf(stderr, "tile_cache_bench: %s\n", OIIO::geterror().c_str());
            std::exit(1);
        }
        const ImageSpec& spec = input->spec();
        const int tw = spec.tile_width, th = spec.tile_height, across = spec.width / tw, down = spec.height / th;
        std::vector<float> tile(std::size_t(tw) * th * spec.nchannels);
        constexpr int offsets[9][2] = {{0, 0}, {-1, -1}, {0, -1}, {1, -1}, {-1, 0}, {1, 0}, {-1, 1}, {0, 1}, {1, 1}};
        for (int ty = 0; ty < block; ++ty)
            for (int tx = 0; tx < block; ++tx)
                for (const auto& o : offsets) {
                    const int x = ((tx + o[0] + across) % across) * tw, y = ((ty + o[1] + down) % down) * th;
                    if (!input->read_tiles(0, 0, x, x + tw, y, y + th, 0, 1, 0, spec.nchannels, TypeFloat, tile.data())) {
                        std::fprintf(stderr, "tile_cache_bench: %s\n", input->geterror().c_str());
                        std::exit(1);
                    }
                    ++run.reads;
                    if (o[0] == 0 && o[1] == 0) run.checksum_texels.insert(run.checksum_texels.end(), tile.begin(), tile.end());
                }
    }  // closed: the plugin writes its counts
    run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    unsetenv("STOCHTEX_TILE_STATS");
    std::ifstream in(stats);
    std::string line;
    std::getline(in, line);
    const nlohmann::json counts = nlohmann::json::parse(line);
    for (const auto& level : counts["levels"]) {
        run.made += level["made"].get<long long>();
        run.served += level["served"].get<long long>();
    }
    return run;
}

}  // namespace

int main(int argc, char** argv)
{
    const int block = argc > 1 ? std::atoi(argv[1]) : 16;
    const int repetitions = argc > 2 ? std::atoi(argv[2]) : 5;
    if (block < 1 || block > 64 || repetitions < 1) {
        std::fprintf(stderr, "usage: tile_cache_bench [block_tiles in 1..64] [repetitions>=1]\n");
        return 2;
    }
    OIIO::attribute("plugin_searchpath", STOCHTEX_PLUGIN_DIR);
    const fs::path dir = fs::temp_directory_path() / "stochtex-tile-cache-bench";
    fs::create_directories(dir);
    const std::string stex = (dir / "concrete.stex").string();
    stochtex::TextureDescription d = stochtex::analyze(
        stochtex::read_image_linear(std::string(STOCHTEX_SOURCE_DIR) + "/data/exemplars/concrete_512.png"), {});
    d.image = stochtex::ImageLayout{16384, 16384, 64, 64, 1.0, "RGB"};
    stochtex::write_stex(stex, d);
    std::printf("texture: concrete_512.png analysed (%s), virtual 16384² float RGB, 64² tiles; %d² tiles of level 0, "
                "each then its 8 neighbours, one read_tiles per tile; %d repetitions, medians\n",
                d.model.c_str(), block, repetitions);
    const long long default_mb = 64;
    struct Case {
        const char* name;
        long long cache_mb;
    };
    const Case cases[] = {{"no cache (reference)", 0}, {"tile cache, 64 MB (default)", default_mb}};
    std::vector<Run> results;
    for (const Case& c : cases) {
        std::vector<double> seconds;
        Run run;
        for (int r = 0; r < repetitions; ++r) {
            run = cycles_reads(stex, block, c.cache_mb, dir / "stats.jsonl");
            seconds.push_back(run.seconds);
        }
        run.seconds = median(seconds);
        std::printf("  %-30s %6lld reads  %6lld tiles made  %6lld served from cache (%5.1f %%)  %8.3f s\n", c.name,
                    run.reads, run.made, run.served, 100.0 * run.served / run.reads, run.seconds);
        results.push_back(std::move(run));
    }
    const bool same = results[0].checksum_texels == results[1].checksum_texels;
    std::printf("  same texels with and without the cache: %s; speed-up %.2fx\n", same ? "yes" : "NO",
                results[0].seconds / results[1].seconds);
    return same ? 0 : 1;
}
