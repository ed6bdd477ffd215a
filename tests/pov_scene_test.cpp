// POV-Ray scene tests (CTest label "scene"): `stex pov` includes rendered by POV-Ray itself and
// compared with the core's own render of the same texture and region (docs/pov.md).
//
// The measurement scene, scenes/pov/test_plane.pov, shows a plane through an orthographic camera
// with emission only, so each pixel is the texture at its centre, written as linear EXR (+FE: not
// gamma-encoded, not clamped). The comparisons use the shared metrics (stochtex/metrics.h).
// Tests that need POV-Ray skip when `povray` is not on PATH; the CLI tests run anyway.
#include "analysis/colour_statistics.h"
#include "test_support.h"

#include <stochtex/error.h>
#include <stochtex/image.h>
#include <stochtex/metrics.h>
#include <stochtex/pov/pov_include.h>
#include <stochtex/render.h>
#include <stochtex/stex_file.h>
#include <stochtex/texture.h>

#include <gtest/gtest.h>


#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace stochtex;

namespace {

// ---- Running programs ----------------------------------------------------------------------------

using RunResult = test::ProgramResult;
using test::contains;

std::string read_text(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Runs argv[0] (a path, or a name looked up on PATH) without a shell; output captured in dir.
RunResult run(const std::vector<std::string>& args, const fs::path& dir) { return test::run_program(args, dir.string()); }

RunResult stex(const std::vector<std::string>& args, const fs::path& dir)
{
    std::vector<std::string> all{STOCHTEX_CLI};
    all.insert(all.end(), args.begin(), args.end());
    return run(all, dir);
}

const fs::path scenes_dir = fs::path(STOCHTEX_SOURCE_DIR) / "scenes" / "pov";

// ---- Measuring -----------------------------------------------------------------------------------

constexpr int plane_size = 512;  // pixels; at the photo's pixel scale: one texture unit
constexpr double plane_depth = 0.25;  // the solid texture's slice w (texture units)

/// POV-Ray's render of the test plane: fixed size, no anti-aliasing (each pixel is the texture
/// at the pixel centre, as the core's render at the photo's scale), linear EXR.
Image render_test_plane(const fs::path& dir, const std::string& name, double extent, const std::vector<std::string>& declares)
{
    std::vector<std::string> args{"povray", "-D", "-A", "+FE", "+W" + std::to_string(plane_size),
                                  "+H" + std::to_string(plane_size), "+L" + dir.string(),
                                  "+I" + (scenes_dir / "test_plane.pov").string(), "+O" + (dir / (name + ".exr")).string(),
                                  "Declare=Extent_U=" + std::to_string(extent), "Declare=Depth=" + std::to_string(plane_depth)};
    args.insert(args.end(), declares.begin(), declares.end());
    const RunResult r = run(args, dir);
    EXPECT_TRUE(r.exited && r.code == 0) << "povray failed: " << r;
    return read_image_linear((dir / (name + ".exr")).string(), {"linear"});
}

/// The core's render of the same region: pixel (x, y) at u = (x + ½)/ppu, v = (y + ½)/ppu.
Image core_render(const Texture& texture, bool solid)
{
    RenderSettings settings;
    settings.width = settings.height = plane_size;
    settings.units_per_pixel = 1.0 / texture.description().pixels_per_unit;
    settings.solid = solid;
    settings.z = plane_depth;
    return render(texture, settings);
}

/// The metrics of compare_images, pooled over several renders per side: the mean and W1 over all
/// their pixels, the log-PSD distance between spectra averaged over the renders. A single 512²
/// render holds the coarsest bands only a few cycles, so one render's low-frequency bins vary by
/// several dB between seeds; pooling four renders halves that noise.
struct PooledComparison {
    std::array<double, 3> mean_shift{};   ///< (mean test − mean reference) / σ reference
    std::array<double, 3> stddev_ratio{};  ///< σ test / σ reference
    std::array<double, 3> w1{};           ///< W1 / σ reference
    std::array<double, 3> log_psd_db{};
};

std::ostream& operator<<(std::ostream& os, const PooledComparison& p)
{
    for (int c = 0; c < 3; ++c)
        os << "\n  channel " << "RGB"[c] << ": mean shift " << p.mean_shift[c] << " sigma, stddev ratio "
           << p.stddev_ratio[c] << ", W1 " << p.w1[c] << " sigma, log-PSD " << p.log_psd_db[c] << " dB";
    return os;
}

std::string to_text(const PooledComparison& p)
{
    std::ostringstream text;
    text << p;
    return text.str();
}

PooledComparison compare_pooled(const std::vector<Image>& reference, const std::vector<Image>& test)
{
    PooledComparison result;
    for (int c = 0; c < 3; ++c) {
        std::vector<float> pooled_reference, pooled_test;
        RadialPsd psd_reference, psd_test;
        auto accumulate = [c](const std::vector<Image>& images, std::vector<float>& pooled, RadialPsd& psd) {
            for (std::size_t i = 0; i < images.size(); ++i) {
                const std::vector<float> plane = images[i].channel(c);
                pooled.insert(pooled.end(), plane.begin(), plane.end());
                const RadialPsd one = radial_psd(plane, images[i].width, images[i].height);
                if (i == 0) {
                    psd = one;
                } else {
                    for (std::size_t b = 0; b < one.power.size(); ++b)
                        psd.power[b] += one.power[b], psd.samples[b] += one.samples[b];
                }
            }
        };
        accumulate(reference, pooled_reference, psd_reference);
        accumulate(test, pooled_test, psd_test);
        auto moments = [](const std::vector<float>& v) {
            double sum = 0, sum_squares = 0;
            for (float x : v) sum += x, sum_squares += double(x) * x;
            const double mean = sum / double(v.size());
            return std::array<double, 2>{mean, std::sqrt(std::max(0.0, sum_squares / double(v.size()) - mean * mean))};
        };
        const auto [mean_reference, sigma_reference] = moments(pooled_reference);
        const auto [mean_test, sigma_test] = moments(pooled_test);
        result.mean_shift[c] = (mean_test - mean_reference) / sigma_reference;
        result.stddev_ratio[c] = sigma_test / sigma_reference;
        result.w1[c] = wasserstein1(pooled_reference, pooled_test) / sigma_reference;
        result.log_psd_db[c] = log_psd_distance_db(psd_reference, psd_test);  // sums: same scale both sides
    }
    return result;
}

// ---- Fixture: the committed concrete exemplar, analysed once ------------------------------------

class PovScene : public ::testing::Test {
protected:
    static void SetUpTestSuite()
    {
        shared_dir = test::temp_dir("pov-scene-shared");
        texture_path = shared_dir / "concrete.stex";
        const RunResult r = stex({"analyze", test::repo_exemplar("concrete_512.png"), "-o", texture_path.string(), "--model", "wavelet"}, shared_dir);
        ASSERT_TRUE(r.exited && r.code == 0) << "analyze failed: " << r;
    }

    void SetUp() override
    {
        if (!test::on_path("povray")) GTEST_SKIP() << "povray is not on PATH (apt-get install povray)";
        ASSERT_TRUE(fs::exists(texture_path)) << "the shared texture could not be analysed";
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir = test::temp_dir(std::string("pov-scene-") + info->name());
    }

    static fs::path shared_dir, texture_path;
    fs::path dir;
};

fs::path PovScene::shared_dir, PovScene::texture_path;

constexpr int realisations = 4;

TEST_F(PovScene, ProceduralPlaneHasTheCoreStatistics)
{
    const RunResult generated = stex({"pov", texture_path.string(), "-o", (dir / "plane_texture.inc").string(), "--name",
                                      "Plane_Texture", "--mode", "procedural"},
                                     dir);
    ASSERT_TRUE(generated.exited && generated.code == 0) << generated;

    // Four realisations per side: POV-Ray with the include's seed knob set on its command line
    // (Declare= defines it before the #include, which then keeps it), the core with the
    // description's seed. Procedural POV-Ray noise is not the core's noise: only statistics can
    // agree, never pixels.
    TextureDescription description = read_stex(texture_path.string());
    std::vector<Image> pov, core_solid, core_2d;
    const auto start = std::chrono::steady_clock::now();
    for (int seed = 1; seed <= realisations; ++seed)
        pov.push_back(render_test_plane(dir, "procedural-" + std::to_string(seed), 1.0,
                                        {"Declare=Plane_Texture_Seed=" + std::to_string(seed)}));
    const double pov_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    for (int seed = 1; seed <= realisations; ++seed) {
        description.seed = std::uint32_t(seed);
        const auto texture = make_texture(description);
        core_solid.push_back(core_render(*texture, true));
        core_2d.push_back(core_render(*texture, false));
    }
    ASSERT_EQ(pov.front().width, plane_size);

    // Thresholds. Measured (POV-Ray 3.7.0.10, 2 seed sets of four 512² renders each):
    //   core vs core, other seeds:  |mean shift| ≤ 0.04 σ, W1 ≤ 0.04 σ, log-PSD 0.8–1.9 dB (solid)
    //   POV-Ray vs core solid:      |mean shift| ≤ 0.11 σ, W1 ≤ 0.11 σ, log-PSD 1.2–1.5 dB
    //   POV-Ray vs core 2D:         |mean shift| ≤ 0.07 σ, W1 ≤ 0.07 σ, log-PSD 0.9–1.2 dB
    // POV-Ray's mean wanders more between realisations: its noise is broader than a wavelet band
    // and its octaves put some variance below the lowest frequency the analysis measured. The
    // limits leave ~2× margin over that, and still catch real faults: a variance off by 30 %
    // (stddev ratio), an octave fitted one octave off (≥ 3 dB), a colour channel mapped
    // wrongly (mean and W1 ≫ 0.2 σ).
    const PooledComparison solid = compare_pooled(core_solid, pov), flat = compare_pooled(core_2d, pov);
    std::printf("procedural POV-Ray vs core solid slice:%s\n", to_text(solid).c_str());
    std::printf("procedural POV-Ray vs core 2D:%s\n", to_text(flat).c_str());
    std::printf("POV-Ray procedural render time: %.2f s per 512² image (including ~0.65 s start-up)\n",
                pov_seconds / realisations);
    for (const PooledComparison* p : {&solid, &flat})
        for (int c = 0; c < 3; ++c) {
            SCOPED_TRACE(p == &solid ? "vs the core's solid slice" : "vs the core's 2D render");
            EXPECT_LT(std::abs(p->mean_shift[c]), 0.2) << *p;
            EXPECT_LT(p->w1[c], 0.2) << *p;
            EXPECT_NEAR(p->stddev_ratio[c], 1.0, 0.15) << *p;
            EXPECT_LT(p->log_psd_db[c], p == &solid ? 2.5 : 2.0) << *p;
        }
}

TEST_F(PovScene, BakedPlaneIsTheCoreRender)
{
    const RunResult generated = stex({"pov", texture_path.string(), "-o", (dir / "plane_texture.inc").string(), "--name",
                                      "Plane_Texture", "--mode", "baked"},
                                     dir);
    ASSERT_TRUE(generated.exited && generated.code == 0) << generated;
    ASSERT_TRUE(fs::exists(dir / "plane_texture.exr")) << generated;

    // The baked period is the core's render of the periodic texture, one texel per exemplar pixel.
    const TextureDescription description = read_stex(texture_path.string());
    const auto periodic = make_periodic_texture(description, {1.0, 1.0});
    const Image core = core_render(*periodic, false);
    const Image baked = read_image_linear((dir / "plane_texture.exr").string(), {"linear"});
    ASSERT_EQ(baked.width, plane_size);
    double baked_difference = 0;
    for (std::size_t i = 0; i < core.pixels.size(); ++i)
        baked_difference = std::max(baked_difference, double(std::abs(core.pixels[i] - baked.pixels[i])));
    EXPECT_LE(baked_difference, 1e-6) << "the EXR is float: it must hold the core's values";

    // POV-Ray renders the plane with pixel centres on texel centres, where bilinear interpolation
    // returns the texels themselves. What remains is POV-Ray's EXR output, which is half float:
    // 11 significant bits, a rounding error ≤ 2^-12 relative (≤ 1.2e-4 for these values < 0.5).
    const auto start = std::chrono::steady_clock::now();
    const Image pov = render_test_plane(dir, "baked", 1.0, {});
    std::printf("POV-Ray baked render time: %.2f s per 512² image (including ~0.65 s start-up)\n",
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    double largest = 0, largest_value = 0;
    for (std::size_t i = 0; i < core.pixels.size(); ++i) {
        largest = std::max(largest, double(std::abs(core.pixels[i] - pov.pixels[i])));
        largest_value = std::max(largest_value, double(std::abs(core.pixels[i])));
    }
    EXPECT_LE(largest, std::ldexp(std::max(largest_value, 0.5), -11)) << "largest value " << largest_value;

    // The same, in the shared metrics: exact to half-float rounding.
    const ComparisonReport report = compare_images(core, pov);
    std::printf("baked POV-Ray vs core (periodic texture, same region):\n%s", format_report(report).c_str());
    for (int c = 0; c < 3; ++c) {
        EXPECT_LT(std::abs(report.mean_test[c] - report.mean_reference[c]), 1e-3 * report.stddev_reference[c]);
        EXPECT_LT(report.w1_relative[c], 0.005);
        EXPECT_LT(report.log_psd_db[c], 0.01);
    }

    // And against the plain (non-periodic) texture, which the periodic one re-draws on a tile
    // that fits the period: another realisation, so statistics only, with the limits of the
    // procedural test (measured here: mean shift ≤ 0.05 σ, W1 ≤ 0.05 σ, log-PSD ≤ 2.8 dB on one render).
    const auto plain = make_texture(description);
    const PooledComparison statistics = compare_pooled({core_render(*plain, false)}, {pov});
    std::printf("baked POV-Ray vs core 2D (plain texture):%s\n", to_text(statistics).c_str());
    for (int c = 0; c < 3; ++c) {
        EXPECT_LT(std::abs(statistics.mean_shift[c]), 0.2) << statistics;
        EXPECT_LT(statistics.w1[c], 0.2) << statistics;
        EXPECT_NEAR(statistics.stddev_ratio[c], 1.0, 0.15) << statistics;
        // One render per side here, not four: the single-render spread of the lowest bins.
        EXPECT_LT(statistics.log_psd_db[c], 3.5) << statistics;
    }
}

TEST_F(PovScene, ShowcaseRendersWithoutWarnings)
{
    for (const auto& [mode, name] : {std::pair<std::string, std::string>{"procedural", "Showcase_Procedural"},
                                     {"baked", "Showcase_Baked"}}) {
        std::string file = name;
        for (char& c : file) c = char(std::tolower(static_cast<unsigned char>(c)));
        std::vector<std::string> args{"pov", texture_path.string(), "-o", (dir / (file + ".inc")).string(),
                                      "--name", name, "--mode", mode};
        if (mode == "baked") args.insert(args.end(), {"--bake-size", "256"});  // small: the scene is tiny
        const RunResult r = stex(args, dir);
        ASSERT_TRUE(r.exited && r.code == 0) << r;
    }
    const RunResult r = run({"povray", "-D", "+A0.1", "+W160", "+H90", "+L" + dir.string(),
                             "+I" + (scenes_dir / "showcase.pov").string(), "+O" + (dir / "showcase.png").string()},
                            dir);
    ASSERT_TRUE(r.exited && r.code == 0) << r;
    // POV-Ray prints its option summary ("Warning Stream to console...On"); a warning itself
    // reads "… Warning: …".
    EXPECT_FALSE(contains(r.output(), "Warning:")) << r;
    EXPECT_FALSE(contains(r.output(), "Possible Parse Error")) << r;
    const Image image = read_image_linear((dir / "showcase.png").string());
    EXPECT_EQ(image.width, 160);
    const auto mean = channel_means(image);
    EXPECT_GT(mean[0], 0.05) << "the showcase is black";
    EXPECT_LT(mean[0], 0.95) << "the showcase is white";
}

// ---- Bad inputs (need no POV-Ray) ----------------------------------------------------------------

class PovCli : public ::testing::Test {
protected:
    void SetUp() override
    {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir = test::temp_dir(std::string("pov-cli-") + info->name());
        texture = dir / "t.stex";
        const RunResult r = stex({"analyze", test::repo_exemplar("concrete_512.png"), "-o", texture.string(), "--model", "wavelet", "--bands", "4"}, dir);
        ASSERT_TRUE(r.exited && r.code == 0) << r;
    }
    fs::path dir, texture;
};

void expect_error(const RunResult& r, const std::vector<std::string>& named)
{
    ASSERT_TRUE(r.exited) << r;
    EXPECT_EQ(r.code, 1) << r;
    for (const std::string& word : named) EXPECT_TRUE(contains(r.output(), word)) << "no '" << word << "' in\n" << r;
}

TEST_F(PovCli, MissingTextureIsAnError)
{
    const RunResult r = stex({"pov", (dir / "no-such.stex").string(), "-o", (dir / "out.inc").string()}, dir);
    expect_error(r, {"stex: error:", "no-such.stex"});
    EXPECT_FALSE(fs::exists(dir / "out.inc"));
}

TEST_F(PovCli, BadNameIsAnError)
{
    // A digit first, a POV-Ray keyword (lower case), a character outside identifiers, too long.
    for (const std::string name : {"3D_Concrete", "box", "Con-crete", "Concrete_With_A_Very_Long_Name"}) {
        SCOPED_TRACE(name);
        const RunResult r = stex({"pov", texture.string(), "-o", (dir / "out.inc").string(), "--name", name}, dir);
        expect_error(r, {"--name", name});
        EXPECT_FALSE(fs::exists(dir / "out.inc"));
    }
}

TEST_F(PovCli, BadModeIsAnError)
{
    const RunResult r = stex({"pov", texture.string(), "-o", (dir / "out.inc").string(), "--mode", "wireframe"}, dir);
    ASSERT_TRUE(r.exited) << r;
    EXPECT_NE(r.code, 0) << r;
    EXPECT_TRUE(contains(r.output(), "--mode")) << r;
    EXPECT_FALSE(fs::exists(dir / "out.inc"));
}

TEST_F(PovCli, HelpListsOptions)
{
    const RunResult r = stex({"pov", "--help"}, dir);
    ASSERT_TRUE(r.exited && r.code == 0) << r;
    for (const char* word : {"texture", "--output", "--name", "--mode", "procedural", "baked", "--bake-size"})
        EXPECT_TRUE(contains(r.output(), word)) << "stex pov --help lacks " << word << "\n" << r;
    const RunResult missing = stex({}, dir);
    EXPECT_TRUE(contains(missing.output(), "pov")) << "the sub-command list lacks pov\n" << missing;
}

TEST_F(PovCli, ModelWithoutProceduralFormSuggestsBakedMode)
{
    // Every model the reader knows today has a procedural form, so ask the generator directly
    // with a description of a model that has none.
    TextureDescription description = read_stex(texture.string());
    description.model = "gabor";
    pov::PovIncludeOptions options;
    options.name = "Gabor";
    options.mode = pov::PovMode::procedural;
    try {
        pov::make_pov_include(description, options);
        FAIL() << "a model without a procedural form was accepted";
    } catch (const Error& e) {
        EXPECT_TRUE(contains(e.what(), "gabor")) << e.what();
        EXPECT_TRUE(contains(e.what(), "--mode baked")) << e.what();
    }
    EXPECT_FALSE(pov::has_procedural_form("gabor"));
    EXPECT_TRUE(pov::has_procedural_form("wavelet"));
}

TEST_F(PovCli, IncludeDeclaresItsNamesAndKnobs)
{
    const RunResult r = stex({"pov", texture.string(), "-o", (dir / "concrete.inc").string()}, dir);
    ASSERT_TRUE(r.exited && r.code == 0) << r;
    const std::string text = read_text(dir / "concrete.inc");
    // Name from the file name; guard; knobs overridable; the two public declarations.
    for (const char* part : {"#ifndef (Concrete_Inc_Temp)", "#version Concrete_Inc_Temp;", "#ifndef (Concrete_Scale)",
                             "#ifndef (Concrete_Seed)", "#ifndef (Concrete_Clamp)", "#declare Concrete_Pigment =",
                             "#declare Concrete = texture", "#declare Concrete_Mean ="})
        EXPECT_TRUE(contains(text, part)) << "no '" << part << "'";
    // Self-contained: no other include file (Debian's povray does not even install functions.inc).
    EXPECT_FALSE(contains(text, "\n#include")) << text;
}

}  // namespace
