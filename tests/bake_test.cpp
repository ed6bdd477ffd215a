// Baked maps (core/include/stochtex/bake.h, `stex bake`): the tiled MIP-mapped EXR holds exactly
// MipImage's levels; the solid map evaluates the solid texture at a position map's points.
#include "test_support.h"

#include <stochtex/analysis.h>
#include <stochtex/bake.h>
#include <stochtex/error.h>
#include <stochtex/mip_image.h>
#include <stochtex/render.h>
#include <stochtex/texture.h>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

namespace fs = std::filesystem;
using namespace stochtex;

namespace {

const TextureDescription& concrete()
{
    static const TextureDescription description = [] {
        AnalysisOptions options;
        options.histogram = HistogramMode::on;
        return analyze(read_image_linear(test::repo_exemplar("concrete_512.png")), options);
    }();
    return description;
}

std::vector<float> read_level(OIIO::ImageInput& input, int level, int& width, int& height)
{
    EXPECT_TRUE(input.seek_subimage(0, level)) << "level " << level;
    width = input.spec().width;
    height = input.spec().height;
    std::vector<float> pixels(std::size_t(width) * height * input.spec().nchannels);
    EXPECT_TRUE(input.read_image(0, level, 0, input.spec().nchannels, OIIO::TypeDesc::FLOAT, pixels.data()));
    return pixels;
}

TEST(Bake, LevelsAreMipImageLevelsBitForBit)
{
    const std::string path = test::temp_dir("bake-levels") + "/t.exr";
    BakeOptions options;
    options.width = options.height = 200;  // not a multiple of the tile size: edge tiles are partial
    options.tile_size = 32;
    const BakeSummary summary = bake_mip_image(concrete(), path, options);
    ImageLayout layout;
    layout.width = layout.height = 200;
    const MipImage reference(concrete(), layout, "reference");
    EXPECT_EQ(summary.levels, reference.level_count());
    EXPECT_FALSE(fs::exists(path + ".tmp"));

    auto input = OIIO::ImageInput::open(path);
    ASSERT_TRUE(input) << OIIO::geterror();
    EXPECT_EQ(input->spec().tile_width, 32);
    EXPECT_EQ(input->spec().get_string_attribute("wrapmodes"), "periodic,periodic");
    for (int level = 0; level < reference.level_count(); ++level) {
        int w = 0, h = 0;
        const std::vector<float> pixels = read_level(*input, level, w, h);
        ASSERT_EQ(w, reference.level_width(level));
        ASSERT_EQ(h, reference.level_height(level));
        std::vector<float> expected(std::size_t(w) * h * 3);
        reference.fill(level, 0, 0, w, h, expected.data());
        EXPECT_EQ(pixels, expected) << "level " << level;
    }
}

TEST(Bake, HalfFloatsStayWithinHalfPrecision)
{
    const std::string path = test::temp_dir("bake-half") + "/t.exr";
    BakeOptions options;
    options.width = options.height = 64;
    options.half = true;
    bake_mip_image(concrete(), path, options);
    auto input = OIIO::ImageInput::open(path);
    ASSERT_TRUE(input);
    EXPECT_EQ(input->spec().format, OIIO::TypeDesc::HALF);
    int w = 0, h = 0;
    const std::vector<float> pixels = read_level(*input, 0, w, h);
    ImageLayout layout;
    layout.width = layout.height = 64;
    std::vector<float> expected(std::size_t(w) * h * 3);
    MipImage(concrete(), layout, "reference").fill(0, 0, 0, w, h, expected.data());
    for (std::size_t i = 0; i < pixels.size(); ++i) ASSERT_NEAR(pixels[i], expected[i], std::abs(expected[i]) * 1e-3 + 1e-6);
}

TEST(Bake, BadLayoutsAndFormatsAreErrors)
{
    const std::string dir = test::temp_dir("bake-bad");
    BakeOptions options;
    options.tile_size = 100;
    EXPECT_THROW(bake_mip_image(concrete(), dir + "/t.exr", options), Error);
    options.tile_size = 64;
    EXPECT_THROW(bake_mip_image(concrete(), dir + "/t.png", options), Error);  // PNG: no tiles or MIP levels
    EXPECT_FALSE(fs::exists(dir + "/t.exr"));
}

/// A position map of the plane z = depth seen as a w × h raster: texel (x, y) holds
/// ((x + ½)·step, (y + ½)·step, depth) in "metres", alpha 1.
std::string write_plane_positions(const std::string& path, int w, int h, double step, double depth)
{
    std::vector<float> rgba(std::size_t(w) * h * 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float* t = &rgba[(std::size_t(y) * w + x) * 4];
            t[0] = float((x + 0.5) * step), t[1] = float((y + 0.5) * step), t[2] = float(depth), t[3] = 1;
        }
    auto output = OIIO::ImageOutput::create(path);
    OIIO::ImageSpec spec(w, h, 4, OIIO::TypeDesc::FLOAT);
    EXPECT_TRUE(output->open(path, spec) && output->write_image(OIIO::TypeDesc::FLOAT, rgba.data()) && output->close());
    return path;
}

TEST(Bake, SolidMapIsTheSolidTextureAtThePositions)
{
    const std::string dir = test::temp_dir("bake-solid");
    const int size = 96;
    // Positions in metres, 2 texture units per metre: texels 1/512 texture units apart (photo pixels).
    const double metres_per_texel = 1.0 / 1024, units_per_metre = 2.0;
    write_plane_positions(dir + "/positions.exr", size, size, metres_per_texel, 0.3);
    bake_solid_map(concrete(), dir + "/positions.exr", dir + "/solid.exr", units_per_metre);

    RenderSettings settings;
    settings.width = settings.height = size;
    settings.units_per_pixel = metres_per_texel * units_per_metre;
    settings.solid = true;
    settings.z = 0.3 * units_per_metre;
    const Image reference = render(*make_texture(concrete()), settings);
    auto input = OIIO::ImageInput::open(dir + "/solid.exr");
    ASSERT_TRUE(input);
    int w = 0, h = 0;
    const std::vector<float> pixels = read_level(*input, 0, w, h);
    ASSERT_EQ(input->spec().nchannels, 4);
    double worst = 0;
    for (int i = 0; i < size * size; ++i)
        for (int c = 0; c < 3; ++c) worst = std::max(worst, double(std::abs(pixels[i * 4 + c] - reference.pixels[i * 3 + c])));
    // Positions pass through float storage (~1e-7 m): the same points and footprints as the render.
    EXPECT_LT(worst, 1e-4);
}

TEST(Bake, SolidMapBadInputsAreErrors)
{
    const std::string dir = test::temp_dir("bake-solid-bad");
    EXPECT_THROW(bake_solid_map(concrete(), dir + "/missing.exr", dir + "/out.exr", 1.0), Error);
    write_plane_positions(dir + "/p.exr", 8, 8, 0.01, 0);
    EXPECT_THROW(bake_solid_map(concrete(), dir + "/p.exr", dir + "/out.exr", 0.0), Error);
}

TEST(Bake, CliBakeAndOsl)
{
    const std::string dir = test::temp_dir("bake-cli");
    const std::string stex = test::shell_quote(STOCHTEX_CLI);
    auto result = test::run_command(stex + " analyze " + test::shell_quote(test::repo_exemplar("concrete_512.png")) + " -o " +
                                    dir + "/t.stex --model wavelet");
    ASSERT_EQ(result.status, 0) << result.output;
    result = test::run_command(stex + " --progress-lines bake " + dir + "/t.stex -o " + dir + "/t.exr --size 128 --half");
    ASSERT_EQ(result.status, 0) << result.output;
    EXPECT_NE(result.output.find("progress 1.00 bake"), std::string::npos) << result.output;
    EXPECT_NE(result.output.find("8 MIP levels"), std::string::npos) << result.output;
    result = test::run_command(stex + " bake " + dir + "/t.stex -o " + dir + "/t.exr --tile 100");
    EXPECT_EQ(result.status, 1) << result.output;
    EXPECT_NE(result.output.find("tile"), std::string::npos) << result.output;
    result = test::run_command(stex + " osl " + dir + "/t.stex -o " + dir + "/t.osl");
    ASSERT_EQ(result.status, 0) << result.output;
    EXPECT_TRUE(fs::exists(dir + "/stochtex_noise_2d.exr") && fs::exists(dir + "/stochtex_noise_3d.exr"));
}

}  // namespace
