// The OIIO plugin (stex.imageio.so) as OIIO's own consumers see it: ImageInput, oiiotool,
// the Python bindings and the TextureSystem. Each MIP level must be the core's filtered
// texels, lookups must match the core's direct evaluation, the TextureSystem must pick the
// level a derivative asks for, the periodic wrap must be seamless, and bad input must fail
// with a message naming the file.
#include "test_support.h"
#include "image/private_texture_system.h"

#include "models/wavelet/band_filter.h"
#include "models/wavelet/wavelet_noise.h"

#include <stochtex/analysis.h>
#include <stochtex/error.h>
#include <stochtex/image.h>
#include <stochtex/mip_image.h>
#include <stochtex/stex_file.h>
#include <stochtex/models/wavelet_parameters.h>

#include <OpenImageIO/imageio.h>
#include <OpenImageIO/texture.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <functional>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <thread>

namespace fs = std::filesystem;
using namespace OIIO;

namespace stochtex {
namespace {

/// Points OIIO at the freshly built plugin before any test opens a file (a cache that failed
/// to find a reader would otherwise stay failed).
class PluginEnvironment : public ::testing::Environment {
public:
    void SetUp() override
    {
        OIIO::attribute("plugin_searchpath", STOCHTEX_PLUGIN_DIR);
        setenv("OIIO_LIBRARY_PATH", STOCHTEX_PLUGIN_DIR, 1);  // for the OIIO programs the tests run
    }
};
const auto* const environment = ::testing::AddGlobalTestEnvironment(new PluginEnvironment);

/// The committed exemplar analysed once; histogram maps as the analysis chose, or none.
const TextureDescription& exemplar_texture(bool histogram)
{
    static const auto analyse = [](HistogramMode mode) {
        AnalysisOptions options;
        options.histogram = mode;
        return analyze(read_image_linear(test::repo_exemplar("concrete_512.png")), options);
    };
    static const TextureDescription with = analyse(HistogramMode::automatic), without = analyse(HistogramMode::off);
    return histogram ? with : without;
}

std::string write_texture(const std::string& dir, const std::string& name, ImageLayout layout, bool histogram = true,
                          std::uint32_t seed = 1)
{
    TextureDescription d = exemplar_texture(histogram);
    d.image = layout;
    d.seed = seed;
    const std::string path = (fs::path(dir) / name).string();
    write_stex(path, d);
    return path;
}

ImageLayout layout(int width, int height, int tile = 32, std::string channels = "RGB")
{
    ImageLayout l;
    l.width = width, l.height = height, l.tile_width = l.tile_height = tile, l.channels = std::move(channels);
    return l;
}

std::vector<float> read_level(const std::string& path, int level, int* width = nullptr, int* height = nullptr)
{
    auto input = ImageInput::open(path);
    EXPECT_TRUE(input) << OIIO::geterror();
    if (!input) return {};
    const ImageSpec spec = input->spec(0, level);
    std::vector<float> pixels(spec.image_pixels() * spec.nchannels);
    EXPECT_TRUE(input->read_image(0, level, 0, spec.nchannels, TypeFloat, pixels.data())) << input->geterror();
    if (width) *width = spec.width;
    if (height) *height = spec.height;
    return pixels;
}

std::vector<float> core_level(const TextureDescription& d, const ImageLayout& l, int level)
{
    const MipImage image(d, l, "test");
    std::vector<float> texels(std::size_t(image.level_width(level)) * image.level_height(level) * image.channel_count());
    image.fill(level, 0, 0, image.level_width(level), image.level_height(level), texels.data());
    return texels;
}

/// The error of ImageInput::open with the given hints (empty if it opened).
std::string open_error(const std::string& path, const ImageSpec& config = ImageSpec())
{
    auto input = ImageInput::open(path, &config);
    return input ? std::string() : OIIO::geterror();
}

// ---- ImageInput ---------------------------------------------------------------------------------

TEST(PluginImageInput, PresentsTheLayoutAndEveryMipLevelDownToOnePixel)
{
    const std::string dir = test::temp_dir("plugin-layout");
    const std::string path = write_texture(dir, "t.stex", layout(200, 48, 16));
    auto input = ImageInput::open(path);
    ASSERT_TRUE(input) << OIIO::geterror();
    EXPECT_STREQ(input->format_name(), "stex");
    const ImageSpec& spec = input->spec();
    EXPECT_EQ(spec.width, 200);
    EXPECT_EQ(spec.height, 48);
    EXPECT_EQ(spec.nchannels, 3);
    EXPECT_EQ(spec.format, TypeFloat);
    EXPECT_EQ(spec.tile_width, 16);
    EXPECT_EQ(spec.tile_height, 16);
    EXPECT_EQ(spec.get_string_attribute("textureformat"), "Plain Texture");
    EXPECT_EQ(spec.get_string_attribute("wrapmodes"), "periodic,periodic");
    EXPECT_FALSE(spec.get_string_attribute("oiio:ColorSpace").empty());
    const std::vector<std::pair<int, int>> expected = {{200, 48}, {100, 24}, {50, 12}, {25, 6},
                                                       {12, 3},   {6, 1},    {3, 1},   {1, 1}};
    for (int level = 0; level < int(expected.size()); ++level) {
        ASSERT_TRUE(input->seek_subimage(0, level)) << level;
        EXPECT_EQ(input->spec().width, expected[level].first) << level;
        EXPECT_EQ(input->spec().height, expected[level].second) << level;
    }
    EXPECT_FALSE(input->seek_subimage(0, int(expected.size())));
    EXPECT_FALSE(input->seek_subimage(1, 0));
}

TEST(PluginImageInput, LevelsAreTheModelsFilteredTexelsAndTheLastIsTheMean)
{
    const std::string dir = test::temp_dir("plugin-levels");
    const ImageLayout l = layout(96, 64, 32);
    const std::string path = write_texture(dir, "t.stex", l);
    const TextureDescription d = read_stex(path);
    const MipImage image(d, l, path);
    for (int level = 0; level < image.level_count(); ++level) {
        // Read through OIIO (tiles, edge tiles cut) and straight from the core: bit-identical.
        EXPECT_EQ(read_level(path, level), core_level(d, l, level)) << "level " << level;
    }
    const std::vector<float> last = read_level(path, image.level_count() - 1);
    const Rgb mean = image.texture().mean();
    ASSERT_EQ(last.size(), 3u);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(last[c], mean[c], 1e-6f) << c;
}

TEST(PluginImageInput, ChannelSetsYAndRgba)
{
    const std::string dir = test::temp_dir("plugin-channels");
    const std::vector<float> rgb = read_level(write_texture(dir, "rgb.stex", layout(64, 64)), 0);
    const std::vector<float> y = read_level(write_texture(dir, "y.stex", layout(64, 64, 32, "Y")), 0);
    const std::vector<float> rgba = read_level(write_texture(dir, "rgba.stex", layout(64, 64, 32, "RGBA")), 0);
    ASSERT_EQ(y.size() * 3, rgb.size());
    ASSERT_EQ(rgba.size(), y.size() * 4);
    for (std::size_t i = 0; i < y.size(); ++i) {
        EXPECT_NEAR(y[i], 0.2126f * rgb[3 * i] + 0.7152f * rgb[3 * i + 1] + 0.0722f * rgb[3 * i + 2], 1e-6f);
        for (int c = 0; c < 3; ++c) EXPECT_EQ(rgba[4 * i + c], rgb[3 * i + c]);
        EXPECT_EQ(rgba[4 * i + 3], 1.0f);
        if (HasFailure()) break;
    }
}

TEST(PluginImageInput, OpenHintsOverrideTheFileAndAreChecked)
{
    const std::string dir = test::temp_dir("plugin-hints");
    const std::string path = write_texture(dir, "t.stex", layout(64, 64));
    ImageSpec config;
    config.attribute("stex:width", 40);
    config.attribute("stex:height", "24");  // strings holding numbers are accepted (oiiotool --iconfig)
    config.attribute("stex:tile_width", 8);
    config.attribute("stex:scale", 2.0f);
    config.attribute("stex:seed", 9);
    auto input = ImageInput::open(path, &config);
    ASSERT_TRUE(input) << OIIO::geterror();
    EXPECT_EQ(input->spec().width, 40);
    EXPECT_EQ(input->spec().height, 24);
    EXPECT_EQ(input->spec().tile_width, 8);
    EXPECT_EQ(input->spec().get_int_attribute("stex:seed"), 9);
    EXPECT_EQ(input->spec().get_float_attribute("stex:scale"), 2.0f);

    auto hint_error = [&](const char* name, auto value) {
        ImageSpec bad;
        bad.attribute(name, value);
        return open_error(path, bad);
    };
    EXPECT_NE(hint_error("stex:width", 0).find("image.width: must be in [1, 1048576], got 0"), std::string::npos);
    EXPECT_NE(hint_error("stex:width", "wide").find("stex:width: expected an integer, got \"wide\""), std::string::npos);
    EXPECT_NE(hint_error("stex:widht", 64).find("unknown open hint \"stex:widht\""), std::string::npos);
    EXPECT_NE(hint_error("stex:tile_width", 100).find("image.tile_width: must be a power of two"), std::string::npos);
    EXPECT_NE(hint_error("stex:channels", "XYZ").find("image.channels"), std::string::npos);
    EXPECT_NE(hint_error("stex:scale", -1.0f).find("image.scale: must be positive"), std::string::npos);
    EXPECT_NE(hint_error("stex:seed", -1).find("stex:seed: must be in [0, 4294967295]"), std::string::npos);
    for (const char* name : {"stex:width", "stex:widht", "stex:scale"})
        EXPECT_NE(hint_error(name, 0).find(path), std::string::npos) << name << ": the message names the file";
}

// The hints are the .stex image block's fields as the core declares them (one list): each field
// is a hint, named in the unknown-hint message, and its declared default is accepted as a hint.
TEST(PluginImageInput, EveryImageBlockFieldIsAnOpenHint)
{
    const std::string dir = test::temp_dir("plugin-hint-fields");
    const std::string path = write_texture(dir, "t.stex", layout(64, 64));
    ImageSpec unknown;
    unknown.attribute("stex:nonsense", 1);
    const std::string message = open_error(path, unknown);
    ASSERT_FALSE(image_layout_fields().empty());
    for (const ParameterInfo& field : image_layout_fields()) {
        EXPECT_NE(message.find("stex:" + field.key), std::string::npos) << message;
        ImageSpec config;
        if (field.type == "integer") config.attribute("stex:" + field.key, std::stoi(field.default_value));
        else if (field.type == "number") config.attribute("stex:" + field.key, std::stof(field.default_value));
        else config.attribute("stex:" + field.key, field.default_value);
        EXPECT_EQ(open_error(path, config), "") << field.key << " = " << field.default_value;
    }
}

// Issue 16: stex:width/height 1048576 made `oiiotool -o` grow without bound, and 4096² tiles on
// a 64² image cost 1.5 GB (every MIP level a whole tile). Both are rejected at open, naming the
// field and the limit; the default layout, and the default tile on any image, stay valid.
TEST(PluginImageInput, VirtualImageAndTileSizesAreBounded)
{
    const std::string dir = test::temp_dir("plugin-bounds");
    const std::string path = write_texture(dir, "t.stex", layout(64, 64));
    auto open_with = [&](std::initializer_list<std::pair<const char*, int>> hints) {
        ImageSpec config;
        for (const auto& [name, value] : hints) config.attribute(name, value);
        return open_error(path, config);
    };
    const std::string huge = open_with({{"stex:width", 1 << 20}, {"stex:height", 1 << 20}});
    EXPECT_NE(huge.find("image: 1048576 x 1048576 pixels is too large (width × height at most 1073741824 = 2^30)"),
              std::string::npos)
        << huge;
    EXPECT_NE(huge.find(path), std::string::npos) << huge;
    const std::string big_tile = open_with({{"stex:tile_width", 4096}});
    EXPECT_NE(big_tile.find("image.tile_width: must be at most 64 for image.width 64 (its next power of two, or 64), "
                            "got 4096"),
              std::string::npos)
        << big_tile;
    EXPECT_NE(open_with({{"stex:height", 100}, {"stex:tile_height", 256}}).find("image.tile_height: must be at most 128"),
              std::string::npos);

    // At the limits, and the layouts that were valid before and stay so.
    EXPECT_EQ(open_with({{"stex:width", 32768}, {"stex:height", 32768}}), "");
    EXPECT_EQ(open_with({{"stex:width", 1 << 20}, {"stex:height", 1024}}), "");
    EXPECT_EQ(open_with({{"stex:width", 16384}, {"stex:height", 16384}, {"stex:tile_width", 4096}}), "");
    EXPECT_EQ(open_with({{"stex:width", 65}, {"stex:tile_width", 128}}), "");
    EXPECT_EQ(open_with({{"stex:width", 20}, {"stex:height", 10}}), "") << "the default 64² tile on a small image";
    ImageSpec defaults;  // the file's image block dropped: ImageLayout's defaults (16384², 64² tiles)
    TextureDescription d = exemplar_texture(true);
    d.image.reset();
    const std::string plain = (fs::path(dir) / "plain.stex").string();
    write_stex(plain, d);
    EXPECT_EQ(open_error(plain, defaults), "");

    // The same rules hold for a .stex file's own "image" block.
    d.image = layout(64, 64, 4096);
    try {
        write_stex((fs::path(dir) / "bad.stex").string(), d);
        ADD_FAILURE() << "a 4096² tile on a 64² image was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("bad.stex: image.tile_width: must be at most 64"), std::string::npos)
            << e.what();
    }
}

// Issue 16: `stex:scale -1` said "got 0" and `stex:channels ""` silently meant RGB.
TEST(PluginImageInput, HintErrorsGiveTheValueAsGiven)
{
    const std::string dir = test::temp_dir("plugin-hint-values");
    const std::string path = write_texture(dir, "t.stex", layout(64, 64));
    auto hint_error = [&](const char* name, auto value) {
        ImageSpec bad;
        bad.attribute(name, value);
        return open_error(path, bad);
    };
    EXPECT_NE(hint_error("stex:scale", -1).find("image.scale: must be positive, got -1"), std::string::npos)
        << hint_error("stex:scale", -1);
    EXPECT_NE(hint_error("stex:scale", "-1").find("image.scale: must be positive, got -1"), std::string::npos);
    EXPECT_NE(hint_error("stex:scale", -0.5f).find("image.scale: must be positive, got -0.5"), std::string::npos);
    // An int scale is a scale (it was read as 0, so `--iconfig stex:scale 2` was rejected too).
    ImageSpec int_scale;
    int_scale.attribute("stex:scale", 2);
    auto scaled = ImageInput::open(path, &int_scale);
    ASSERT_TRUE(scaled) << OIIO::geterror();
    EXPECT_EQ(scaled->spec().get_float_attribute("stex:scale"), 2.0f);
    const std::string empty = hint_error("stex:channels", "");
    EXPECT_NE(empty.find("stex:channels (image.channels): expected \"RGB\", \"RGBA\" or \"Y\", got \"\""), std::string::npos) << empty;
    EXPECT_NE(empty.find(path), std::string::npos) << empty;
    EXPECT_NE(hint_error("stex:channels", "XYZ").find("stex:channels (image.channels): expected \"RGB\", \"RGBA\" or \"Y\", got \"XYZ\""),
              std::string::npos);
    EXPECT_NE(hint_error("stex:channels", 3).find("stex:channels: expected a string (RGB, RGBA or Y)"), std::string::npos);

    // As oiiotool passes it (--iconfig makes "-1" an int). oiiotool drops an empty value
    // (`--iconfig stex:channels ""` removes the hint), so only the API can pass "".
    if (!test::on_path("oiiotool")) GTEST_SKIP() << "oiiotool is not installed";
    const test::ProgramResult scale =
        test::run_program({"oiiotool", "--iconfig", "stex:scale", "-1", "--info", path}, dir);
    EXPECT_FALSE(scale.succeeded()) << scale;
    EXPECT_TRUE(test::contains(scale.output(), "image.scale: must be positive, got -1")) << scale;
}

TEST(PluginImageInput, BadFilesFailWithTheFileAndTheProblem)
{
    const std::string dir = test::temp_dir("plugin-bad");
    auto write = [&](const std::string& name, const std::string& text) {
        const std::string path = (fs::path(dir) / name).string();
        std::ofstream(path) << text;
        return path;
    };
    const std::string stex = format_stex(exemplar_texture(true));
    struct Case {
        std::string path, expected;
    };
    const Case cases[] = {
        {write("empty.stex", ""), "empty.stex"},
        {write("garbage.stex", "not json at all"), "garbage.stex"},
        {write("truncated.stex", stex.substr(0, stex.size() / 2)), "truncated.stex"},
        {write("model.stex", std::string(stex).replace(stex.find("\"wavelet\""), 9, "\"plaid\"")), "unknown model 'plaid'"},
        {write("image.stex", stex.substr(0, stex.rfind('}')) + ", \"image\": {\"width\": -5}}"), "image.width"},
    };
    for (const Case& c : cases) {
        const std::string message = open_error(c.path);
        EXPECT_NE(message.find(c.expected), std::string::npos) << c.path << " gave: " << message;
    }
    EXPECT_FALSE(open_error(dir + "/missing.stex").empty());
}

// ---- The tile cache (plugin/tile_cache.h) -------------------------------------------------------

/// The JSON lines STOCHTEX_TILE_STATS collects while `reads` runs (every ImageInput it opens is
/// closed before it returns).
std::vector<nlohmann::json> tile_stats_of(const std::string& dir, const std::function<void()>& reads)
{
    const std::string log = (fs::path(dir) / "tile-stats.jsonl").string();
    fs::remove(log);
    setenv("STOCHTEX_TILE_STATS", log.c_str(), 1);
    reads();
    unsetenv("STOCHTEX_TILE_STATS");
    std::vector<nlohmann::json> lines;
    std::ifstream in(log);
    for (std::string line; std::getline(in, line);) lines.push_back(nlohmann::json::parse(line));
    return lines;
}

/// One tile (level, x, y) as Cycles 5.2 reads it: read_tiles of that one tile, as floats.
std::vector<float> read_one_tile(ImageInput& input, int level, int x, int y)
{
    const ImageSpec spec = input.spec(0, level);
    std::vector<float> tile(std::size_t(spec.tile_width) * spec.tile_height * spec.nchannels);
    EXPECT_TRUE(input.read_tiles(0, level, x, x + spec.tile_width, y, y + spec.tile_height, 0, 1, 0, spec.nchannels,
                                 TypeFloat, tile.data()))
        << input.geterror();
    return tile;
}

/// Cycles' pattern: each tile of a 4 x 4 block, then its 8 neighbours (a one-texel border).
/// Returns every tile read, in order.
std::vector<std::vector<float>> read_like_cycles(ImageInput& input, int level)
{
    const ImageSpec spec = input.spec(0, level);
    const int tw = spec.tile_width, th = spec.tile_height;
    // The tile itself first, then the 8 around it.
    constexpr int offsets[9][2] = {{0, 0}, {-1, -1}, {0, -1}, {1, -1}, {-1, 0}, {1, 0}, {-1, 1}, {0, 1}, {1, 1}};
    std::vector<std::vector<float>> tiles;
    for (int ty = 1; ty <= 4; ++ty)
        for (int tx = 1; tx <= 4; ++tx)
            for (const auto& offset : offsets)
                tiles.push_back(read_one_tile(input, level, (tx + offset[0]) * tw, (ty + offset[1]) * th));
    return tiles;
}

TEST(PluginTileCache, SameTexelsWithAndWithoutTheCacheAndNeighbourRereadsAreServed)
{
    const std::string dir = test::temp_dir("plugin-tile-cache");
    const std::string path = write_texture(dir, "cache.stex", layout(512, 512, 32));
    ImageSpec off;
    off.attribute("stex:tile_cache_mb", 0);
    std::vector<std::vector<float>> cached, uncached;
    const std::vector<nlohmann::json> stats = tile_stats_of(dir, [&] {
        auto with = ImageInput::open(path);
        auto without = ImageInput::open(path, &off);
        ASSERT_TRUE(with && without) << OIIO::geterror();
        for (int level : {0, 1}) {
            for (auto& tile : read_like_cycles(*with, level)) cached.push_back(std::move(tile));
            for (auto& tile : read_like_cycles(*without, level)) uncached.push_back(std::move(tile));
        }
    });
    ASSERT_EQ(cached.size(), uncached.size());
    for (std::size_t i = 0; i < cached.size(); ++i) EXPECT_EQ(cached[i], uncached[i]) << "read " << i;
    // And the texels are the core's: the first tile read of level 0 is at (32, 32).
    const std::vector<float> level0 = core_level(read_stex(path), layout(512, 512, 32), 0);
    for (int row = 0; row < 32; ++row)
        for (int i = 0; i < 32 * 3; ++i)
            ASSERT_EQ(cached[0][std::size_t(row) * 32 * 3 + i], level0[(std::size_t(32 + row) * 512 + 32) * 3 + i]);

    // 16 tiles and their neighbours: 36 distinct tiles of the 144 reads per level.
    ASSERT_EQ(stats.size(), 2u);
    const nlohmann::json& on = stats[0]["tile_cache_bytes"].get<long long>() > 0 ? stats[0] : stats[1];
    const nlohmann::json& zero = &on == &stats[0] ? stats[1] : stats[0];
    EXPECT_EQ(zero["tile_cache_bytes"], 0);
    EXPECT_EQ(on["tile_cache_bytes"], 64ll << 20);  // the documented default
    for (int level : {0, 1}) {
        EXPECT_EQ(on["levels"][level]["made"], 36) << on;
        EXPECT_EQ(on["levels"][level]["served"], 144 - 36) << on;
        EXPECT_EQ(zero["levels"][level]["made"], 144) << zero;
        EXPECT_EQ(zero["levels"][level]["served"], 0) << zero;
    }
    EXPECT_EQ(on["levels"][0]["tiles"], 16 * 16);
    EXPECT_EQ(on["levels"][2]["made"], 0);
    EXPECT_EQ(on["file"], path);
}

TEST(PluginTileCache, KeepsToItsBudgetLeastRecentlyUsedFirst)
{
    const std::string dir = test::temp_dir("plugin-tile-budget");
    // 64² RGB float tiles are 48 KiB: a 1 MB budget holds 21 of them.
    const std::string path = write_texture(dir, "budget.stex", layout(1024, 1024, 64));
    ImageSpec config;
    config.attribute("stex:tile_cache_mb", "1");
    const std::vector<nlohmann::json> stats = tile_stats_of(dir, [&] {
        auto input = ImageInput::open(path, &config);
        ASSERT_TRUE(input) << OIIO::geterror();
        for (int pass = 0; pass < 2; ++pass)  // 32 tiles in a row, twice: each evicted before its turn
            for (int i = 0; i < 32; ++i) read_one_tile(*input, 0, (i % 16) * 64, (i / 16) * 64);
        for (int i = 31; i >= 12; --i) read_one_tile(*input, 0, (i % 16) * 64, (i / 16) * 64);  // the last 20 kept
    });
    ASSERT_EQ(stats.size(), 1u);
    EXPECT_EQ(stats[0]["tile_cache_bytes"], 1 << 20);
    EXPECT_LE(stats[0]["peak_bytes"].get<long long>(), 1 << 20);
    EXPECT_EQ(stats[0]["peak_bytes"], 21 * 64 * 64 * 3 * 4);
    EXPECT_EQ(stats[0]["levels"][0]["made"], 64);
    EXPECT_EQ(stats[0]["levels"][0]["served"], 20);
}

TEST(PluginTileCache, BadBudgetsNameTheHintOrTheVariable)
{
    const std::string dir = test::temp_dir("plugin-tile-budget-bad");
    const std::string path = write_texture(dir, "bad.stex", layout(256, 256, 32));
    ImageSpec negative;
    negative.attribute("stex:tile_cache_mb", -1);
    EXPECT_TRUE(test::contains(open_error(path, negative), "stex:tile_cache_mb: must be in [0,")) << open_error(path, negative);
    setenv("STOCHTEX_TILE_CACHE_MB", "lots", 1);
    const std::string message = open_error(path);
    unsetenv("STOCHTEX_TILE_CACHE_MB");
    EXPECT_TRUE(test::contains(message, "bad.stex: STOCHTEX_TILE_CACHE_MB: expected an integer")) << message;
}

TEST(PluginTileCache, ConcurrentReadersThroughASmallCacheGetTheCoresTexels)
{
    const std::string dir = test::temp_dir("plugin-tile-threads");
    const std::string path = write_texture(dir, "threads.stex", layout(512, 512, 32));
    const std::vector<float> level0 = core_level(read_stex(path), layout(512, 512, 32), 0);
    ImageSpec config;
    config.attribute("stex:tile_cache_mb", 1);  // 85 of the 256 tiles: constant eviction
    auto input = ImageInput::open(path, &config);
    ASSERT_TRUE(input) << OIIO::geterror();
    std::atomic<int> wrong{0};
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back([&, t] {
            std::mt19937 rng(t);
            std::vector<float> tile(32 * 32 * 3);
            for (int i = 0; i < 600; ++i) {
                const int x = int(rng() % 16) * 32, y = int(rng() % 16) * 32;
                if (!input->read_native_tile(0, 0, x, y, 0, tile.data())) ++wrong;
                for (int row = 0; row < 32; ++row)
                    if (!std::equal(&tile[row * 96], &tile[row * 96] + 96, &level0[(std::size_t(y + row) * 512 + x) * 3]))
                        ++wrong;
            }
        });
    for (auto& thread : threads) thread.join();
    EXPECT_EQ(wrong, 0);
}

// ---- OIIO's tools -------------------------------------------------------------------------------

TEST(PluginTools, OiiotoolListsTheMipLevelsAndWritesLevelZero)
{
    if (!test::on_path("oiiotool")) GTEST_SKIP() << "oiiotool is not installed";
    const std::string dir = test::temp_dir("plugin-oiiotool");
    const std::string path = write_texture(dir, "t.stex", layout(64, 32, 16));
    const test::ProgramResult info = test::run_program({"oiiotool", "--info", "-v", path}, dir);
    ASSERT_TRUE(info.succeeded()) << info;
    EXPECT_TRUE(test::contains(info.out, ":   64 x   32, 3 channel, float stex")) << info;
    EXPECT_TRUE(test::contains(info.out, "MIP-map levels: 64x32 32x16 16x8 8x4 4x2 2x1 1x1")) << info;

    const std::string exr = dir + "/out.exr";
    const test::ProgramResult convert = test::run_program({"oiiotool", path, "-o", exr}, dir);
    ASSERT_TRUE(convert.succeeded()) << convert;
    int width = 0, height = 0;
    const std::vector<float> written = read_level(exr, 0, &width, &height);
    EXPECT_EQ(width, 64);
    EXPECT_EQ(height, 32);
    EXPECT_EQ(written, core_level(read_stex(path), layout(64, 32, 16), 0));

    // Open hints from the command line.
    const test::ProgramResult hinted = test::run_program(
        {"oiiotool", "--iconfig", "stex:width", "20", "--iconfig", "stex:height", "10", "--info", path}, dir);
    EXPECT_TRUE(test::contains(hinted.out, ":   20 x   10, 3 channel")) << hinted;
}

TEST(PluginTools, PythonBindingsReadIt)
{
    const std::string dir = test::temp_dir("plugin-python");
    if (!test::run_program({"/usr/bin/python3", "-c", "import OpenImageIO"}, dir).succeeded())
        GTEST_SKIP() << "python3-openimageio is not installed";
    const std::string path = write_texture(dir, "t.stex", layout(32, 16, 16));
    const std::string script = "import OpenImageIO as oiio\n"
                               "i = oiio.ImageInput.open('" + path + "')\n"
                               "assert i, oiio.geterror()\n"
                               "s = i.spec()\n"
                               "p = i.read_image(0, 0, 0, 3, 'float')\n"
                               "print(s.width, s.height, s.nchannels, '%.6f' % p[0][0][0])\n";
    std::ofstream(dir + "/read.py") << script;
    const test::ProgramResult result = test::run_program({"/usr/bin/python3", dir + "/read.py"}, dir);
    ASSERT_TRUE(result.succeeded()) << result;
    const std::vector<float> level = core_level(read_stex(path), layout(32, 16, 16), 0);
    char expected[64];
    std::snprintf(expected, sizeof expected, "32 16 3 %.6f", level[0]);
    EXPECT_TRUE(test::contains(result.out, expected)) << result << " (expected " << expected << ")";
}

// ---- TextureSystem ------------------------------------------------------------------------------

stochtex::PrivateTextureSystem private_texture_system()
{
    stochtex::PrivateTextureSystem ts = stochtex::make_private_texture_system();
    ts->attribute("plugin_searchpath", STOCHTEX_PLUGIN_DIR);
    return ts;
}

Rgb lookup(TextureSystem& ts, const std::string& path, TextureOpt& options, float s, float t, float ds, float dt)
{
    Rgb result{};
    EXPECT_TRUE(ts.texture(ustring(path), options, s, t, ds, 0, 0, dt, 3, result.data())) << ts.geterror();
    return result;
}

TextureOpt trilinear_options()
{
    TextureOpt options;
    options.mipmode = TextureOpt::MipModeTrilinear;
    options.interpmode = TextureOpt::InterpBilinear;
    return options;
}

TEST(PluginTextureSystem, ChoosesTheMipLevelADerivativeAsksFor)
{
    // In the spirit of OIIO's texture-filtersize test: a lookup at a level's texel centre with
    // that level's texel size as derivative must return exactly that level's texel. A table of
    // derivative → chosen level (the level whose texel it matches) goes to the test log.
    const std::string dir = test::temp_dir("plugin-mip-choice");
    const ImageLayout l = layout(256, 256, 32);
    const std::string path = write_texture(dir, "t.stex", l);
    const TextureDescription d = read_stex(path);
    const MipImage image(d, l, path);
    std::vector<std::vector<float>> levels;
    for (int level = 0; level < image.level_count(); ++level) levels.push_back(core_level(d, l, level));
    auto ts = private_texture_system();
    TextureOpt options = trilinear_options();
    std::mt19937 rng(5);
    for (int level = 0; level < image.level_count(); ++level) {
        const int size = image.level_width(level);
        const float texel = 1.0f / size;
        int matches[16] = {};
        for (int i = 0; i < 64; ++i) {
            const int x = int(rng() % size), y = int(rng() % size);
            const Rgb value = lookup(*ts, path, options, (x + 0.5f) * texel, (y + 0.5f) * texel, texel, texel);
            // Which level's texel at this point does the value equal? (This level first.)
            int chosen = -1;
            for (int k = 0; k < image.level_count() && chosen < 0; ++k) {
                const int other = k == 0 ? level : k <= level ? k - 1 : k;
                const int other_size = image.level_width(other);
                const int ox = int((x + 0.5) * other_size / size), oy = int((y + 0.5) * other_size / size);
                const float* texel_value = &levels[other][(std::size_t(oy) * other_size + ox) * 3];
                bool equal = true;
                for (int c = 0; c < 3; ++c) equal = equal && std::abs(value[c] - texel_value[c]) <= 2e-6f;
                if (equal) chosen = other;
            }
            ++matches[chosen < 0 ? 15 : chosen];
        }
        std::printf("derivative 1/%-4d → level %d chosen for %d of 64 lookups\n", size, level, matches[level]);
        EXPECT_EQ(matches[level], 64) << "level " << level << " (texel 1/" << size << ")";
    }
}

/// Per-channel variance of σ_N² Σ_j fade_j² w_j² (eq. 2 with the bands a footprint keeps),
/// mapped to RGB through the basis: what a Gaussian (histogram-free) texture predicts.
std::array<double, 3> predicted_rgb_variance(const TextureDescription& d, double footprint_px)
{
    std::array<double, 3> channel{};
    const auto& weights = d.parameters.get<WaveletParameters>().band_weights;
    for (int c = 0; c < 3; ++c)
        for (std::size_t j = 0; j < weights[c].size(); ++j) {
            const double fade = band_fade(int(j), footprint_px);
            channel[c] += WaveletNoise2D::shared().variance() * fade * fade * weights[c][j] * weights[c][j];
        }
    std::array<double, 3> rgb{};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) rgb[r] += d.basis[r][c] * d.basis[r][c] * channel[c];
    return rgb;
}

TEST(PluginTextureSystem, VarianceFallsWithTheFootprintAsTheModelPredicts)
{
    // Lookups at the texel centres of the level whose texels are `footprint` exemplar pixels
    // wide, on a histogram-free texture (so eq. 2 predicts the RGB variance exactly), averaged
    // over four seeds: each level's grid samples its finest kept band at one phase of the band's
    // lattice (up to ±20 % of that band's variance), and the seeds average the phases out.
    const std::string dir = test::temp_dir("plugin-variance");
    const int size = 2048;
    const ImageLayout l = layout(size, size, 8);  // small tiles: random lookups stay cheap
    std::vector<std::string> paths;
    for (std::uint32_t seed = 1; seed <= 4; ++seed)
        paths.push_back(write_texture(dir, "t" + std::to_string(seed) + ".stex", l, /*histogram=*/false, seed));
    const TextureDescription d = read_stex(paths[0]);
    auto ts = private_texture_system();
    TextureOpt options = trilinear_options();
    std::mt19937 rng(8);
    std::printf("footprint(px)  variance measured/predicted: R G B\n");
    for (int footprint = 1; footprint <= 64; footprint *= 2) {
        const int level_size = size / footprint, per_seed = std::min(4096, level_size * level_size);
        std::array<double, 3> sum{}, sum_sq{};
        for (const std::string& path : paths)
            for (int i = 0; i < per_seed; ++i) {
                const bool whole_level = per_seed == level_size * level_size;
                const int x = whole_level ? i % level_size : int(rng() % level_size);
                const int y = whole_level ? i / level_size : int(rng() % level_size);
                const float texel = 1.0f / level_size;
                const Rgb v = lookup(*ts, path, options, (x + 0.5f) * texel, (y + 0.5f) * texel, texel, texel);
                for (int c = 0; c < 3; ++c) sum[c] += v[c], sum_sq[c] += double(v[c]) * v[c];
            }
        const auto predicted = predicted_rgb_variance(d, footprint);
        const double n = 4.0 * per_seed;
        std::printf("%13d ", footprint);
        for (int c = 0; c < 3; ++c) {
            const double mean = sum[c] / n, variance = sum_sq[c] / n - mean * mean;
            std::printf(" %.3g/%.3g", variance, predicted[c]);
            // 15 %: the remaining phase and sampling error of a few thousand correlated samples.
            EXPECT_NEAR(variance, predicted[c], 0.15 * predicted[c]) << "footprint " << footprint << " px, channel " << c;
        }
        std::printf("\n");
    }
}

TEST(PluginTextureSystem, LookupsMatchTheCoresFilteredEvaluation)
{
    // Anywhere (not only at texel centres) and with small and large derivatives, a lookup is
    // the core's filtered value up to the texture system's bilinear and trilinear
    // interpolation. Tolerance: RMS difference below 15 % of the standard deviation of the
    // values at that footprint (interpolating between texels of a band-limited signal).
    const std::string dir = test::temp_dir("plugin-match");
    const ImageLayout l = layout(512, 512, 64);
    const std::string path = write_texture(dir, "t.stex", l);
    const TextureDescription d = read_stex(path);
    const MipImage image(d, l, path);
    auto ts = private_texture_system();
    TextureOpt options = trilinear_options();
    std::mt19937 rng(21);
    std::uniform_real_distribution<float> uniform(0, 1);
    for (float derivative_px : {0.5f, 1.0f, 3.0f, 16.0f, 100.0f}) {
        const float derivative = derivative_px / 512;
        double error_sq = 0, sum = 0, sum_sq = 0;
        constexpr int samples = 2000;
        for (int i = 0; i < samples; ++i) {
            const float s = uniform(rng), t = uniform(rng);
            const Rgb looked_up = lookup(*ts, path, options, s, t, derivative, derivative);
            const Rgb direct = image.texture().eval({s * image.period()[0], t * image.period()[1]},
                                                    Footprint2D::square(std::max(derivative_px, 1.0f) / d.pixels_per_unit));
            for (int c = 0; c < 3; ++c) {
                error_sq += (looked_up[c] - direct[c]) * (looked_up[c] - direct[c]);
                sum += direct[c], sum_sq += double(direct[c]) * direct[c];
            }
        }
        const double n = 3.0 * samples, sigma = std::sqrt(sum_sq / n - (sum / n) * (sum / n));
        const double rms = std::sqrt(error_sq / n);
        std::printf("derivative %6.1f px: RMS(lookup − core) = %.4f, σ = %.4f (%.1f %%)\n", derivative_px, rms, sigma,
                    100 * rms / sigma);
        EXPECT_LT(rms, 0.15 * sigma) << "derivative " << derivative_px << " px";
    }
}

TEST(PluginTextureSystem, PeriodicWrapHasNoSeam)
{
    // Neighbouring lookups across s = 1 (and t = 1) differ no more than neighbours inside.
    const std::string dir = test::temp_dir("plugin-seam");
    const int size = 300;  // not a power of two: bands are snapped to fit the period
    const std::string path = write_texture(dir, "t.stex", layout(size, size, 32));
    auto ts = private_texture_system();
    TextureOpt options = trilinear_options();
    options.swrap = options.twrap = TextureOpt::WrapPeriodic;
    const float texel = 1.0f / size, tiny = 0.25f * texel;
    double seam_sum = 0, interior_sum = 0, seam_max = 0, interior_max = 0;
    int interior_count = 0;
    for (int row = 0; row < size; ++row) {
        const float t = (row + 0.5f) * texel;
        auto step = [&](float s0, float s1, bool across_v) {
            const Rgb a = across_v ? lookup(*ts, path, options, t, s0, tiny, tiny) : lookup(*ts, path, options, s0, t, tiny, tiny);
            const Rgb b = across_v ? lookup(*ts, path, options, t, s1, tiny, tiny) : lookup(*ts, path, options, s1, t, tiny, tiny);
            double difference = 0;
            for (int c = 0; c < 3; ++c) difference += std::abs(a[c] - b[c]);
            return difference;
        };
        for (bool across_v : {false, true}) {
            const double seam = step(1 - 0.5f * texel, 1 + 0.5f * texel, across_v);
            seam_sum += seam, seam_max = std::max(seam_max, seam);
            for (int x = 0; x + 1 < size; x += 7) {
                const double inside = step((x + 0.5f) * texel, (x + 1.5f) * texel, across_v);
                interior_sum += inside, interior_max = std::max(interior_max, inside), ++interior_count;
            }
        }
    }
    const double seam_mean = seam_sum / (2 * size), interior_mean = interior_sum / interior_count;
    std::printf("mean |Δ| across the wrap %.5f, inside %.5f; max %.5f vs %.5f\n", seam_mean, interior_mean, seam_max,
                interior_max);
    // 600 seam pairs against ~25 000 interior pairs: the seam mean is within sampling error
    // (~5 %) of the interior mean when there is no seam; a seam would double it.
    EXPECT_LT(seam_mean, 1.2 * interior_mean);
    EXPECT_LE(seam_max, interior_max);
}

}  // namespace
}  // namespace stochtex
