// Baked maps (core/include/stochtex/bake.h, `stex bake`): the tiled MIP-mapped EXR holds exactly
// MipImage's levels; the solid map evaluates the solid texture at a position map's points.
#include "test_support.h"

#include "models/model.h"

#include <stochtex/analysis.h>
#include <stochtex/bake.h>
#include <stochtex/error.h>
#include <stochtex/mip_image.h>
#include <stochtex/render.h>
#include <stochtex/texture.h>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

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

// A model whose texture fails at some positions: eval() throws for u ≥ fail_from_u, eval_solid()
// for x ≥ fail_from_u (texture units). Registered in this program only, so that a bake's worker
// throws part-way through, as a model's error (or a bad_alloc) would.
struct FailingParameters {
    double fail_from_u = 0.5;
};

class FailingTexture final : public Texture {
public:
    explicit FailingTexture(const TextureDescription& d) : Texture(d), fail_from_(d.parameters.get<FailingParameters>().fail_from_u) {}
    FailingTexture(const TextureDescription& d, const Vec2&) : FailingTexture(d) {}
    Rgb eval(const Vec2& uv, const Footprint2D&) const override { return at(uv[0]); }
    Rgb eval_solid(const SurfacePoint& point) const override { return at(point.p[0]); }
    Rgb mean() const override { return {0.5f, 0.5f, 0.5f}; }

private:
    Rgb at(double u) const
    {
        if (u >= fail_from_) throw Error("failing model: no value at u = " + std::to_string(u));
        return mean();
    }
    double fail_from_;
};

ParameterSchema<FailingParameters> failing_schema()
{
    ParameterSchema<FailingParameters> s;
    s.number("fail_from_u", &FailingParameters::fail_from_u, {-1e6, 1e6, ""}, {"0.5", "texture units", "where eval throws"});
    return s;
}

class FailingModel final : public TextureModelOf<FailingParameters, FailingTexture> {
public:
    FailingModel() : TextureModelOf({"test_failing", "throws while evaluated, for the bake tests", "tests/bake_test.cpp", {}, {}, {}}, failing_schema()) {}
    std::string describe(const TextureDescription&) const override { return "fails\n"; }
    TextureDescription example() const override
    {
        TextureDescription d;
        d.model = name();
        d.pixels_per_unit = 64;
        d.mean = {0.5, 0.5, 0.5};
        d.parameters = FailingParameters{};
        return d;
    }
};

const FailingModel failing_model;
const ModelRegistration failing_registration(failing_model);

std::string file_bytes(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Whether `dir` holds only the files named (no temporary left behind).
std::vector<std::string> files_in(const std::string& dir)
{
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

TEST(Bake, AThrowingWorkerIsACleanErrorAndKeepsTheOldFile)
{
    const std::string dir = test::temp_dir("bake-worker-throws");
    const std::string path = dir + "/t.exr";
    BakeOptions options;
    options.width = options.height = 256;
    options.tile_size = 32;
    options.threads = 4;
    bake_mip_image(concrete(), path, options);  // the old output
    const std::string old_bytes = file_bytes(path);
    ASSERT_FALSE(old_bytes.empty());

    // The period is 256 / 64 = 4 units wide: every strip of level 0 has tiles that fail (u ≥ 2.5)
    // and tiles that do not, spread over 4 threads.
    TextureDescription failing = failing_model.example();
    failing.parameters = FailingParameters{2.5};
    try {
        bake_mip_image(failing, path, options);
        FAIL() << "the bake did not fail";
    } catch (const Error& e) {
        // The usual error: the output file, then the model's message.
        EXPECT_EQ(std::string(e.what()).rfind(path + ": failing model: no value at u = ", 0), 0u) << e.what();
    }
    EXPECT_EQ(file_bytes(path), old_bytes);
    EXPECT_EQ(files_in(dir), std::vector<std::string>{"t.exr"});

    // The solid bake: rows are the items; x ≥ 2.5 fails on every row.
    write_plane_positions(dir + "/positions.exr", 64, 48, 0.0625, 0);
    const std::string solid = dir + "/solid.exr";
    bake_solid_map(concrete(), dir + "/positions.exr", solid, 1.0, 4);
    const std::string old_solid = file_bytes(solid);
    try {
        bake_solid_map(failing, dir + "/positions.exr", solid, 1.0, 4);
        FAIL() << "the solid bake did not fail";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()).rfind("failing model: no value at u = ", 0), 0u) << e.what();
    }
    EXPECT_EQ(file_bytes(solid), old_solid);
    EXPECT_EQ(files_in(dir), (std::vector<std::string>{"positions.exr", "solid.exr", "t.exr"}));
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
