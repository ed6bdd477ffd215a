// End-to-end tests of the `stex` command-line tool: each test runs the built binary and checks its
// exit status, its messages and the files it writes. Bad input must end in a clean exit (never a
// signal) with a message that names the offending file or option.
#include "test_support.h"

#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>


#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

// ---- Running the tool ---------------------------------------------------------------------------

using RunResult = stochtex::test::ProgramResult;
using stochtex::test::contains;

std::string read_file(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_file(const fs::path& path, const std::string& bytes)
{
    std::ofstream(path, std::ios::binary) << bytes;
}

/// Runs `stex args...` directly (no shell, so no quoting), stdout and stderr captured in files in
/// `dir`.
RunResult run_stex(const std::vector<std::string>& args, const fs::path& dir)
{
    std::vector<std::string> argv{STOCHTEX_CLI};
    argv.insert(argv.end(), args.begin(), args.end());
    return stochtex::test::run_program(argv, dir.string());
}


/// A stochtex::Error (bad file, bad value): exit code exactly 1, "stex: error:" and `name` on stderr.
void expect_error_naming(const RunResult& r, const std::string& name)
{
    ASSERT_TRUE(r.exited) << r;
    EXPECT_EQ(r.code, 1) << r;
    EXPECT_TRUE(contains(r.err, "stex: error:")) << r;
    EXPECT_TRUE(contains(r.err, name)) << "stderr does not name '" << name << "'\n" << r;
}

/// A command-line usage error (reported by CLI11): a clean non-zero exit naming `name`.
void expect_usage_error_naming(const RunResult& r, const std::string& name)
{
    ASSERT_TRUE(r.exited) << r;
    EXPECT_NE(r.code, 0) << r;
    EXPECT_TRUE(contains(r.err, name)) << "stderr does not name '" << name << "'\n" << r;
}

void expect_success(const RunResult& r)
{
    ASSERT_TRUE(r.exited) << r;
    EXPECT_EQ(r.code, 0) << r;
}

// ---- Images -------------------------------------------------------------------------------------

struct FloatImage {
    int width = 0, height = 0, channels = 0;
    std::vector<float> pixels;
};

FloatImage read_float_image(const fs::path& path)
{
    FloatImage image;
    auto input = OIIO::ImageInput::open(path.string());
    if (!input) {
        ADD_FAILURE() << "cannot open " << path << ": " << OIIO::geterror();
        return image;
    }
    const OIIO::ImageSpec& spec = input->spec();
    image.width = spec.width;
    image.height = spec.height;
    image.channels = spec.nchannels;
    image.pixels.resize(std::size_t(spec.width) * spec.height * spec.nchannels);
    if (!input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data()))
        ADD_FAILURE() << "cannot read " << path << ": " << input->geterror();
    return image;
}

/// Writes 8-bit RGB pixels (row-major) as a PNG.
void write_png(const fs::path& path, int width, int height, const std::vector<unsigned char>& rgb)
{
    auto output = OIIO::ImageOutput::create(path.string());
    ASSERT_TRUE(output) << OIIO::geterror();
    ASSERT_TRUE(output->open(path.string(), OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::UINT8)))
        << output->geterror();
    ASSERT_TRUE(output->write_image(OIIO::TypeDesc::UINT8, rgb.data())) << output->geterror();
    output->close();
}

/// A small photo: the top-left size×size crop of the shared dirt exemplar, or smoothed noise when
/// the shared folder is missing.
void write_small_photo(const fs::path& path, int size)
{
    std::vector<unsigned char> rgb(std::size_t(size) * size * 3);
    const std::string exemplar = stochtex::test::shared_exemplar("dirt.png");
    if (!exemplar.empty()) {
        auto input = OIIO::ImageInput::open(exemplar);
        ASSERT_TRUE(input) << OIIO::geterror();
        const OIIO::ImageSpec& spec = input->spec();
        ASSERT_GE(spec.width, size);
        ASSERT_GE(spec.height, size);
        std::vector<unsigned char> rows(std::size_t(spec.width) * size * 3);
        ASSERT_TRUE(input->read_scanlines(0, 0, 0, size, 0, 0, 3, OIIO::TypeDesc::UINT8, rows.data()))
            << input->geterror();
        for (int y = 0; y < size; ++y)
            std::memcpy(&rgb[std::size_t(y) * size * 3], &rows[std::size_t(y) * spec.width * 3], std::size_t(size) * 3);
    } else {
        std::mt19937 random(7);
        std::uniform_int_distribution<int> noise(0, 255);
        std::vector<int> white(rgb.size());
        for (int& v : white) v = noise(random);
        // A 3×3 box blur (wrapping) gives the noise some spatial structure.
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x)
                for (int c = 0; c < 3; ++c) {
                    int sum = 0;
                    for (int dy = -1; dy <= 1; ++dy)
                        for (int dx = -1; dx <= 1; ++dx)
                            sum += white[(std::size_t((y + dy + size) % size) * size + (x + dx + size) % size) * 3 + c];
                    rgb[(std::size_t(y) * size + x) * 3 + c] = static_cast<unsigned char>(sum / 9);
                }
    }
    write_png(path, size, size, rgb);
}

/// Replaces the first `from` in `text` by `to` (the test fails if there is none).
std::string replaced(std::string text, const std::string& from, const std::string& to)
{
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << "'" << from << "' not found in\n" << text;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

// ---- Fixture: one small photo and its texture, shared by the tests --------------------------------

constexpr int photo_size = 64;

class Cli : public ::testing::Test {
protected:
    static void SetUpTestSuite()
    {
        shared_dir = stochtex::test::temp_dir("cli-shared");
        photo = shared_dir / "photo.png";
        texture = shared_dir / "photo.stex";
        write_small_photo(photo, photo_size);
        const RunResult r = run_stex({"analyze", photo.string(), "-o", texture.string(), "--model", "wavelet"}, shared_dir);
        ASSERT_TRUE(r.exited && r.code == 0) << "analyze failed: " << r;
    }

    void SetUp() override
    {
        ASSERT_TRUE(fs::exists(texture)) << "the shared texture could not be analysed";
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir = stochtex::test::temp_dir(std::string("cli-") + info->name());
    }

    RunResult stex(const std::vector<std::string>& args) const { return run_stex(args, dir); }

    /// A copy of the shared texture with `from` replaced by `to` in its JSON text.
    fs::path edited_texture(const std::string& name, const std::string& from, const std::string& to) const
    {
        const fs::path path = dir / name;
        write_file(path, replaced(read_file(texture), from, to));
        return path;
    }

    static fs::path shared_dir, photo, texture;
    fs::path dir;
};

fs::path Cli::shared_dir, Cli::photo, Cli::texture;

// ---- Bad photos ---------------------------------------------------------------------------------

TEST_F(Cli, MissingPhotoIsAnError)
{
    const fs::path missing = dir / "no-such-photo.png";
    const RunResult r = stex({"analyze", missing.string(), "-o", (dir / "out.stex").string()});
    expect_error_naming(r, "no-such-photo.png");
    EXPECT_FALSE(fs::exists(dir / "out.stex"));
}

TEST_F(Cli, TruncatedPngIsAnError)
{
    const fs::path truncated = dir / "truncated.png";
    fs::copy_file(photo, truncated);
    fs::resize_file(truncated, fs::file_size(truncated) / 2);
    const RunResult r = stex({"analyze", truncated.string(), "-o", (dir / "out.stex").string()});
    expect_error_naming(r, "truncated.png");
    EXPECT_FALSE(fs::exists(dir / "out.stex"));
}

TEST_F(Cli, OnePixelPngIsAnError)
{
    const fs::path tiny = dir / "tiny.png";
    write_png(tiny, 1, 1, {128, 128, 128});
    const RunResult r = stex({"analyze", tiny.string(), "-o", (dir / "out.stex").string()});
    expect_error_naming(r, "tiny.png");
    EXPECT_TRUE(contains(r.err, "1x1")) << r;
}

TEST_F(Cli, ExrWithNanIsAnError)
{
    const fs::path exr = dir / "nan.exr";
    constexpr int size = 32;
    std::vector<float> pixels(std::size_t(size) * size * 3, 0.25f);
    pixels[(std::size_t(5) * size + 7) * 3 + 1] = std::numeric_limits<float>::quiet_NaN();
    {
        auto output = OIIO::ImageOutput::create(exr.string());
        ASSERT_TRUE(output) << OIIO::geterror();
        ASSERT_TRUE(output->open(exr.string(), OIIO::ImageSpec(size, size, 3, OIIO::TypeDesc::FLOAT)))
            << output->geterror();
        ASSERT_TRUE(output->write_image(OIIO::TypeDesc::FLOAT, pixels.data())) << output->geterror();
        output->close();
    }
    const RunResult r = stex({"analyze", exr.string(), "-o", (dir / "out.stex").string()});
    expect_error_naming(r, "nan.exr");
    EXPECT_FALSE(fs::exists(dir / "out.stex"));
}

// ---- Bad textures -------------------------------------------------------------------------------

TEST_F(Cli, BenchMeasuresEveryRouteAgainstTheBakedReference)
{
    const RunResult r = stex({"bench", texture.string(), "--size", "32", "--repetitions", "1", "--threads", "2", "--tile", "16"});
    ASSERT_TRUE(r.exited && r.code == 0) << r;
    for (const char* route : {"model wavelet", "2D raster", "solid slice", "plugin tiles", "baked lookup (cold)", "baked lookup (warm)",
                              "x baked warm", "MipImage::fill", "2 thread(s)"})
        EXPECT_TRUE(contains(r.out, route)) << "'" << route << "' missing from\n" << r;
}

TEST_F(Cli, BenchOfABadTextureNamesIt)
{
    const fs::path garbage = dir / "garbage.stex";
    write_file(garbage, "not json");
    expect_error_naming(stex({"bench", garbage.string(), "--size", "32"}), "garbage.stex");
    const RunResult r = stex({"bench", texture.string(), "--size", "8"});
    ASSERT_TRUE(r.exited) << r;
    EXPECT_NE(r.code, 0) << r;
    EXPECT_TRUE(contains(r.err, "--size")) << r;
}

TEST_F(Cli, GarbageStexIsAnError)
{
    const fs::path garbage = dir / "garbage.stex";
    std::mt19937 random(3);
    std::string bytes(512, '\0');
    for (char& c : bytes) c = static_cast<char>(random() & 0xff);
    write_file(garbage, bytes);
    expect_error_naming(stex({"info", garbage.string()}), "garbage.stex");
    expect_error_naming(stex({"render", garbage.string(), "-o", (dir / "out.exr").string()}), "garbage.stex");
    EXPECT_FALSE(fs::exists(dir / "out.exr"));
}

TEST_F(Cli, EmptyStexIsAnError)
{
    const fs::path empty = dir / "empty.stex";
    write_file(empty, "");
    expect_error_naming(stex({"info", empty.string()}), "empty.stex");
    // morph reads two textures: the message names the bad one.
    const RunResult r = stex({"morph", texture.string(), empty.string(), "-o", (dir / "out.stex").string()});
    expect_error_naming(r, "empty.stex");
    EXPECT_FALSE(fs::exists(dir / "out.stex"));
}

TEST_F(Cli, UnknownModelIsAnError)
{
    const fs::path path = edited_texture("unknown-model.stex", "\"model\": \"wavelet\"", "\"model\": \"perlin\"");
    const RunResult r = stex({"info", path.string()});
    expect_error_naming(r, "unknown-model.stex");
    EXPECT_TRUE(contains(r.err, "perlin")) << r;
}

TEST_F(Cli, NonFiniteOrWrongTypeFieldIsAnError)
{
    const std::string pixels_per_unit = "\"pixels_per_unit\": " + std::to_string(photo_size);
    struct Edit {
        std::string file, from, to, reported;  ///< `reported`: what the message must also name
    };
    const std::vector<Edit> edits{
        {"nan.stex", pixels_per_unit, "\"pixels_per_unit\": NaN", "line"},  // NaN is not JSON
        {"overflow.stex", "\"mean\": [", "\"mean\": [1e999, ", "colour.mean"},
        {"string.stex", pixels_per_unit, "\"pixels_per_unit\": \"NaN\"", "scale.pixels_per_unit"},
        {"array.stex", "\"seed\": 1,", "\"seed\": [1],", "seed"},
    };
    for (const Edit& edit : edits) {
        SCOPED_TRACE(edit.file);
        const fs::path path = edited_texture(edit.file, edit.from, edit.to);
        const RunResult r = stex({"info", path.string()});
        expect_error_naming(r, edit.file);
        EXPECT_TRUE(contains(r.err, edit.reported)) << r;
    }
    expect_error_naming(stex({"render", (dir / "overflow.stex").string(), "-o", (dir / "out.exr").string()}),
                        "overflow.stex");
    EXPECT_FALSE(fs::exists(dir / "out.exr"));
}

// ---- Bad options --------------------------------------------------------------------------------

TEST_F(Cli, RenderSizeZeroIsAnError)
{
    const RunResult r = stex({"render", texture.string(), "-o", (dir / "out.exr").string(), "--size", "0x5"});
    expect_error_naming(r, "--size");
    EXPECT_TRUE(contains(r.err, "0x5")) << r;
    EXPECT_FALSE(fs::exists(dir / "out.exr"));
}

TEST_F(Cli, RenderSizeBananaIsAnError)
{
    const RunResult r = stex({"render", texture.string(), "-o", (dir / "out.exr").string(), "--size", "banana"});
    expect_error_naming(r, "--size");
    EXPECT_TRUE(contains(r.err, "banana")) << r;
    EXPECT_FALSE(fs::exists(dir / "out.exr"));
}

TEST_F(Cli, MorphParameterOutOfRangeIsAnError)
{
    const RunResult r =
        stex({"morph", texture.string(), texture.string(), "--t", "2", "-o", (dir / "out.stex").string()});
    expect_usage_error_naming(r, "--t");
    EXPECT_FALSE(fs::exists(dir / "out.stex"));
}

TEST_F(Cli, UnknownSubcommandIsAnError)
{
    expect_usage_error_naming(stex({"frobnicate"}), "frobnicate");
}

TEST_F(Cli, MissingSubcommandIsAnError)
{
    const RunResult r = stex({});
    ASSERT_TRUE(r.exited) << r;
    EXPECT_NE(r.code, 0) << r;
    EXPECT_FALSE(r.err.empty()) << r;
}

TEST_F(Cli, UnknownOptionIsAnError)
{
    expect_usage_error_naming(stex({"info", texture.string(), "--bogus"}), "--bogus");
    expect_usage_error_naming(stex({"--bogus", "info", texture.string()}), "--bogus");
}

// ---- Help ---------------------------------------------------------------------------------------

TEST_F(Cli, HelpListsSubcommandsAndOptions)
{
    const RunResult app = stex({"--help"});
    expect_success(app);
    for (const char* word : {"Usage", "analyze", "render", "info", "compare", "morph", "--version"})
        EXPECT_TRUE(contains(app.out, word)) << "stex --help lacks " << word << "\n" << app;

    const std::vector<std::pair<std::string, std::vector<std::string>>> options{
        {"analyze", {"photo", "--output", "--model", "--colour", "--histogram", "--knots", "--psd", "--bands",
                     "--seed", "--colourspace", "--unit-size", "--gabor-kind", "--impulses", "--bandwidth"}},
        {"render", {"texture", "--output", "--size", "--scale", "--u", "--v", "--solid", "--z", "--no-filter",
                    "--threads", "--seed"}},
        {"info", {"texture"}},
        {"compare", {"photo", "texture", "--output", "--colourspace"}},
        {"morph", {"--t", "--output"}},
    };
    for (const auto& [command, words] : options) {
        const RunResult r = stex({command, "--help"});
        expect_success(r);
        EXPECT_TRUE(contains(r.out, "Usage")) << r;
        for (const std::string& word : words)
            EXPECT_TRUE(contains(r.out, word)) << "stex " << command << " --help lacks " << word << "\n" << r;
    }

    const RunResult version = stex({"--version"});
    expect_success(version);
    EXPECT_TRUE(contains(version.out, "stochtex")) << version;
}

// ---- Happy path ---------------------------------------------------------------------------------

TEST_F(Cli, AnalyzeChoosesTheModelByDefaultAndSaysHow)
{
    const fs::path chosen = dir / "chosen.stex";
    const RunResult r = stex({"analyze", photo.string(), "-o", chosen.string()});
    expect_success(r);
    // The score table: a row per analysable model, the choice marked, the rule stated.
    for (const char* part : {"penalty", "wavelet", "gabor", "tiling", "lrp", "← chosen", "rule: lowest penalty"})
        EXPECT_TRUE(contains(r.out, part)) << part << " in\n" << r.out;
    const RunResult info = stex({"info", chosen.string()});
    expect_success(info);
    EXPECT_TRUE(contains(info.out, "chosen by    auto (fidelity penalty: wavelet ")) << info.out;
    // A model's own option goes to the models that declare it; one no model has is an error.
    expect_success(stex({"analyze", photo.string(), "-o", chosen.string(), "--impulses", "8"}));
    // --help names auto as the default.
    EXPECT_TRUE(contains(stex({"analyze", "--help"}).out, "auto: fit each model")) << "help";
}

TEST_F(Cli, AnalyzeRenderInfoCompareMorph)
{
    // analyze (again, into this test's folder, with non-default options)
    const fs::path stex_path = dir / "texture.stex";
    expect_success(stex({"analyze", photo.string(), "-o", stex_path.string(), "--model", "wavelet", "--colour", "rgb", "--seed", "5"}));
    ASSERT_TRUE(fs::exists(stex_path));
    EXPECT_GT(fs::file_size(stex_path), 0u);

    // render to EXR at a requested size
    const fs::path exr = dir / "render.exr";
    expect_success(stex({"render", stex_path.string(), "-o", exr.string(), "--size", "40x24"}));
    ASSERT_TRUE(fs::exists(exr));
    const FloatImage image = read_float_image(exr);
    EXPECT_EQ(image.width, 40);
    EXPECT_EQ(image.height, 24);
    EXPECT_EQ(image.channels, 3);
    for (float value : image.pixels) ASSERT_TRUE(std::isfinite(value));

    // render to PNG
    const fs::path png = dir / "render.png";
    expect_success(stex({"render", stex_path.string(), "-o", png.string(), "--size", "32x32"}));
    ASSERT_TRUE(fs::exists(png));
    EXPECT_EQ(read_float_image(png).width, 32);

    // info
    const RunResult info = stex({"info", stex_path.string()});
    expect_success(info);
    EXPECT_TRUE(contains(info.out, "wavelet")) << info;
    EXPECT_TRUE(contains(info.out, "photo.png")) << info;

    // compare, with a figure
    const fs::path figure = dir / "figure.png";
    const RunResult compare = stex({"compare", photo.string(), stex_path.string(), "-o", figure.string()});
    expect_success(compare);
    ASSERT_TRUE(fs::exists(figure));
    EXPECT_GT(read_float_image(figure).width, 0);
    for (const char* row : {"2D log-PSD distance", "gradient orientation W1", "false-colour rate", "structure distance"})
        EXPECT_TRUE(contains(compare.out, row)) << row << " missing:\n" << compare;
    // Two 512-pixel columns whatever the photo's size (a 64² photo is enlarged 8×, so the labels
    // fit): photo | synthesis, the charts, the two spectra, the structure bars below.
    const FloatImage figure_image = read_float_image(figure);
    EXPECT_EQ(figure_image.width, 1024);
    EXPECT_GT(figure_image.height, 512 + 2 * 320);

    // compare with an image in the texture's place: scored as it is (the photo with itself is 0
    // on every metric).
    const RunResult itself = stex({"compare", photo.string(), photo.string()});
    expect_success(itself);
    EXPECT_TRUE(contains(itself.out, "as it is")) << itself;
    EXPECT_TRUE(contains(itself.out, "structure distance (Portilla-Simoncelli statistics; 0 = the photo's, 1 = its "
                                     "random-phase noise's): 0\n"))
        << itself;

    // morph with itself
    const fs::path morphed = dir / "morphed.stex";
    expect_success(stex({"morph", stex_path.string(), stex_path.string(), "--t", "0.5", "-o", morphed.string()}));
    ASSERT_TRUE(fs::exists(morphed));
    expect_success(stex({"info", morphed.string()}));
}

TEST_F(Cli, RenderDefaultsToThePhotoSize)
{
    const fs::path exr = dir / "render.exr";
    expect_success(stex({"render", texture.string(), "-o", exr.string()}));
    const FloatImage image = read_float_image(exr);
    EXPECT_EQ(image.width, photo_size);
    EXPECT_EQ(image.height, photo_size);
}

TEST_F(Cli, RenderIsIdenticalForAnyThreadCount)
{
    auto render = [&](const std::string& threads) {
        const fs::path exr = dir / ("threads-" + threads + ".exr");
        expect_success(stex({"render", texture.string(), "-o", exr.string(), "--size", "97x61", "--threads", threads}));
        return read_float_image(exr);
    };
    const FloatImage one = render("1"), two = render("2");
    ASSERT_EQ(one.pixels.size(), std::size_t(97) * 61 * 3);
    ASSERT_EQ(one.pixels.size(), two.pixels.size());
    EXPECT_EQ(std::memcmp(one.pixels.data(), two.pixels.data(), one.pixels.size() * sizeof(float)), 0)
        << "--threads 1 and --threads 2 rendered different pixels";
    // Not trivially equal: the texture varies.
    EXPECT_NE(std::memcmp(one.pixels.data(), one.pixels.data() + 3, sizeof(float) * 3), 0);
}

}  // namespace
