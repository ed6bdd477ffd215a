// OSL shaders (docs/osl.md): the generated wavelet shader's maths against the core, and
// oslc/testshade when they are installed (osl_gabor_test.cpp, osl_tiling_test.cpp: the others).
//
// Debian 12 packages no OSL, so the shader's maths is checked here without oslc: osl/stochtex_wavelet.h
// is written in the common subset of OSL and C++, and this file compiles it as C++ (osl_shim.h:
// a texture() that reads the noise tile files `stex osl` writes, closest texel, periodic), feeding
// it the parameter values parsed back from a generated .osl file. That checks the generator, the
// tiles and the transcription together against Texture::eval / eval_solid. What it cannot check
// is OSL's own syntax and runtime: the oslc/testshade tests do, and skip where oslc is absent.
#include "test_support.h"

#include <stochtex/analysis.h>
#include <stochtex/error.h>
#include <stochtex/image.h>
#include <stochtex/metrics.h>
#include <stochtex/osl/osl_shader.h>
#include <stochtex/render.h>
#include <stochtex/stex_file.h>
#include <stochtex/texture.h>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <regex>
#include <sstream>

namespace fs = std::filesystem;

#include "osl_shim.h"

namespace osl_shim {
#include "../osl/stochtex_wavelet.h"
}  // namespace osl_shim

namespace {

using namespace stochtex;
using osl_test::parse_parameters;
using osl_test::ShaderParameters;

/// A generated shader evaluated through the shim.
class ShimShader {
public:
    ShimShader(const TextureDescription& description, const std::string& dir)
    {
        osl::OslShaderOptions options;
        options.shader_name = "stochtex_test";
        options.images = osl::osl_image_paths(description, dir, "unused");
        text = osl::make_osl_shader(description, options);
        osl::write_osl_images(description, options.images);
        p_ = parse_parameters(text);
        for (const char* name : {"tile_2d", "tile_3d", "rows_probe"}) osl_shim::load_image(p_.strings.at(name));
    }

    /// As the shader: the row probe read first (rows_bottom_up < 0), then the texture; or with
    /// the row flag given (a shader that ignored the probe would pass 0).
    Rgb eval(bool solid, double x, double y, double z, double footprint_px, int rows_bottom_up = -1)
    {
        if (rows_bottom_up < 0) rows_bottom_up = osl_shim::stochtex_rows_bottom_up(p_.s("rows_probe"));
        std::vector<int> knot_count;
        for (float c : p_.arrays.at("knot_count")) knot_count.push_back(int(c));
        float r = 0, g = 0, b = 0;
        osl_shim::stochtex_wavelet(solid, float(x), float(y), float(z), float(footprint_px), int(p_.scalars.at("band_count")),
                                   a("scale"), a("weight"), a("offset"), a("sigma_m"), p_.scalars.at("sigma_n2"),
                                   p_.scalars.at("solid_gain"), knot_count.data(), a("knot_z"), a("knot_value"),
                                   a("knot_slope"), a("gh_node"), a("gh_weight"), int(p_.scalars.at("joint_count")),
                                   p_.scalars.at("joint_first"), p_.scalars.at("joint_inverse_step"), a("joint_curve"),
                                   a("mean"), a("basis"),
                                   p_.strings.at("tile_2d").c_str(), int(p_.scalars.at("size_2d")),
                                   p_.strings.at("tile_3d").c_str(), int(p_.scalars.at("size_3d")),
                                   int(p_.scalars.at("per_row_3d")), rows_bottom_up, r, g, b);
        return {r, g, b};
    }
    float ppu() const { return p_.scalars.at("pixels_per_unit"); }
    std::string text;

private:
    float* a(const std::string& name) { return p_.arrays.at(name).data(); }
    ShaderParameters p_;
};

TextureDescription concrete(HistogramMode histogram, ColourMode colour = ColourMode::pca, bool joint_colour = false)
{
    AnalysisOptions options;
    options.histogram = histogram;
    options.colour_mode = colour;
    options.joint_colour = joint_colour;
    return analyze(read_image_linear(test::repo_exemplar("concrete_512.png")), options);
}

/// Largest |shader − core| of each RGB channel over random points and footprints (1/8 … 512
/// exemplar pixels).
std::array<double, 3> max_differences(const TextureDescription& description, bool solid, const std::string& dir)
{
    ShimShader shader(description, dir);
    const auto texture = make_texture(description);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> position(-3.0, 3.0), log_footprint(-3.0, 9.0);
    std::array<double, 3> worst{};
    for (int i = 0; i < 400; ++i) {
        const double x = position(rng), y = position(rng), z = position(rng);
        const double footprint_px = std::exp2(log_footprint(rng));
        const double units = footprint_px / description.pixels_per_unit;
        Rgb core;
        if (solid) {
            SurfacePoint point;
            point.p = {x, y, z};
            point.dpdx = {units, 0, 0};
            point.dpdy = {0, units, 0};
            core = texture->eval_solid(point);
        } else {
            core = texture->eval({x, y}, Footprint2D::square(units));
        }
        const Rgb osl = shader.eval(solid, x, y, z, footprint_px);
        for (int c = 0; c < 3; ++c) worst[c] = std::max(worst[c], double(std::abs(osl[c] - core[c])));
    }
    return worst;
}

double max_difference(const TextureDescription& description, bool solid, const std::string& dir)
{
    const std::array<double, 3> worst = max_differences(description, solid, dir);
    return std::max({worst[0], worst[1], worst[2]});
}

double colour_scale(const TextureDescription& description)
{
    return std::max({description.mean[0], description.mean[1], description.mean[2]});
}

// Float rounding of lattice positions (|x · scale + offset| up to ~2000 cells: ulp 1e-4 cell)
// moves the spline by ~1e-4 of a coefficient: measured 2.5e-5 of the mean colour at most.
// A wrong offset, weight, fade or histogram knot moves values by ~0.1 of the mean or more.
constexpr double tolerance = 2e-4;
// Joint colour, in units of each RGB channel's σ: measured 2.2e-4 σ (2D) and 1.1e-4 σ (solid), the
// float rounding above; evaluating the curves unfiltered where brightness detail is dropped
// measured 8e-2 σ.
constexpr double joint_tolerance_sigma = 1e-3;

TEST(OslShader, TwoDimensionalShaderMatchesCore)
{
    const std::string dir = test::temp_dir("osl2d");
    for (const auto histogram : {HistogramMode::off, HistogramMode::on}) {
        const TextureDescription description = concrete(histogram);
        const double diff = max_difference(description, false, dir);
        EXPECT_LT(diff / colour_scale(description), tolerance) << "histogram " << int(histogram) << ": max |osl - core| " << diff;
    }
}

TEST(OslShader, SolidShaderMatchesCore)
{
    const std::string dir = test::temp_dir("osl3d");
    const TextureDescription description = concrete(HistogramMode::on);
    const double diff = max_difference(description, true, dir);
    EXPECT_LT(diff / colour_scale(description), tolerance) << "max |osl - core| " << diff;
}

TEST(OslShader, RgbColourModeMatchesCore)
{
    const std::string dir = test::temp_dir("oslrgb");
    const TextureDescription description = concrete(HistogramMode::automatic, ColourMode::rgb);
    EXPECT_LT(max_difference(description, false, dir) / colour_scale(description), tolerance);
}

TEST(OslShader, JointColourMatchesCore)
{
    // Joint colour: chroma = location(z_0) + scale(z_0) · residual, the curves filtered by
    // Gauss–Hermite where brightness detail is dropped (footprints 1/8 … 512 px cover both forms).
    const std::string dir = test::temp_dir("ostjoint");
    const TextureDescription description = concrete(HistogramMode::on, ColourMode::pca, true);
    ASSERT_TRUE(description.chroma_given_brightness.enabled());
    const std::array<double, 3> sigma = osl_test::channel_sigmas(*make_texture(description));
    // What the curves change: the same texture read as independent channels, in σ. A shader that
    // ignored them (or swapped location and scale) would be off by about this much.
    TextureDescription independent = description;
    independent.chroma_given_brightness = {};
    double effect = 0;
    {
        const auto joint = make_texture(description), without = make_texture(independent);
        std::mt19937 rng(3);
        std::uniform_real_distribution<double> position(-3.0, 3.0);
        for (int i = 0; i < 200; ++i) {
            const Vec2 p{position(rng), position(rng)};
            const Rgb a = joint->eval(p, Footprint2D{}), b = without->eval(p, Footprint2D{});
            for (int c = 0; c < 3; ++c) effect = std::max(effect, std::abs(double(a[c]) - b[c]) / sigma[c]);
        }
    }
    for (const bool solid : {false, true}) {
        const std::array<double, 3> worst = max_differences(description, solid, dir);
        double worst_sigma = 0;
        for (int c = 0; c < 3; ++c) worst_sigma = std::max(worst_sigma, worst[c] / sigma[c]);
        std::printf("wavelet OSL vs core, joint colour, %s: max %.2e sigma (the curves' effect: %.2f sigma)\n",
                    solid ? "solid" : "2D", worst_sigma, effect);
        EXPECT_LT(worst_sigma, joint_tolerance_sigma) << (solid ? "solid" : "2D");
    }
    EXPECT_GT(effect, 100 * joint_tolerance_sigma) << "the test texture's joint colour should matter";
}

// A host whose texture() runs rows bottom-up (Cycles 5.2) gets the same texture through the row
// probe, bit for bit, 2D and solid; the shader without it (flag 0 there) reads other coefficients.
TEST(OslShader, MirroringHostGivesTheSameTextureThroughTheRowProbe)
{
    const TextureDescription description = concrete(HistogramMode::on);
    ShimShader shader(description, test::temp_dir("oslrows"));
    const std::array<double, 3> sigma = osl_test::channel_sigmas(*make_texture(description));
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> position(-3.0, 3.0), log_footprint(-3.0, 6.0);
    for (const bool solid : {false, true}) {
        double unprobed = 0;  // in σ: the largest difference a shader ignoring the probe would show
        for (int i = 0; i < 100; ++i) {
            const double x = position(rng), y = position(rng), z = position(rng), footprint = std::exp2(log_footprint(rng));
            const auto shade = [&](int rows) { return shader.eval(solid, x, y, z, footprint, rows); };
            unprobed = std::max(unprobed, osl_test::mirroring_host_difference(shade, sigma, "point " + std::to_string(i)));
        }
        EXPECT_GT(unprobed, 0.5) << (solid ? "solid" : "2D") << ": the mirrored host must read other texels";
    }
}

TEST(OslShader, GeneratedShaderIsSelfContained)
{
    const std::string dir = test::temp_dir("oslself");
    osl_test::expect_self_contained(ShimShader(concrete(HistogramMode::automatic), dir).text);
}

TEST(OslShader, BadNamesAndModelsAreErrors)
{
    osl::OslShaderOptions options;
    options.shader_name = "3d shader";
    EXPECT_THROW(osl::make_osl_shader(concrete(HistogramMode::off), options), Error);
    EXPECT_EQ(osl::osl_shader_name_from_path("out/rust 2.osl"), "stochtex_rust_2");
}

TEST(OslShader, ModelsWithoutATranscriptionAreRefusedWithTheAlternatives)
{
    // lrp and ptm have no OSL form (their capability `osl` is off): the message names the routes.
    for (const char* model : {"lrp", "ptm"}) {
        ASSERT_FALSE(osl::has_osl_form(model)) << model;
        TextureDescription description = concrete(HistogramMode::off);
        description.model = model;
        osl::OslShaderOptions options;
        options.shader_name = "stochtex_test";
        try {
            osl::make_osl_shader(description, options);
            FAIL() << model << " has no OSL form";
        } catch (const Error& e) {
            EXPECT_TRUE(test::contains(e.what(), model)) << e.what();
            EXPECT_TRUE(test::contains(e.what(), "stochtex_texture.osl")) << e.what();
        }
    }
    for (const char* model : {"wavelet", "gabor", "tiling"}) EXPECT_TRUE(osl::has_osl_form(model)) << model;
}

// ---- With OSL installed: compile every shader, and compare testshade's output statistically -----

TEST(OslCompiler, ShadersCompileWithOslc)
{
    if (!test::on_path("oslc")) GTEST_SKIP() << "oslc not on PATH (Debian 12 packages no OSL): shaders not compiled";
    const std::string dir = test::temp_dir("oslc");
    const std::string source = STOCHTEX_SOURCE_DIR "/osl";
    for (const char* shader : {"stochtex_wavelet.osl", "stochtex_gabor.osl", "stochtex_tiling.osl", "stochtex_texture.osl"}) {
        const auto result = test::run_command("cd " + test::shell_quote(dir) + " && oslc -I" + test::shell_quote(source) + " " +
                                              test::shell_quote(source + "/" + shader));
        EXPECT_EQ(result.status, 0) << shader << ":\n" << result.output;
    }
    const std::string generated = dir + "/generated.osl";
    std::ofstream(generated) << ShimShader(concrete(HistogramMode::on), dir).text;
    const auto result = test::run_command("cd " + test::shell_quote(dir) + " && oslc generated.osl");
    EXPECT_EQ(result.status, 0) << result.output;
}

TEST(OslCompiler, TestshadeMatchesCore)
{
    if (!test::on_path("oslc") || !test::on_path("testshade")) GTEST_SKIP() << "oslc/testshade not on PATH: not run";
    const std::string dir = test::temp_dir("testshade");
    const TextureDescription description = concrete(HistogramMode::on);
    // testshade --center shades pixel centres, P = ((x + ½)/w, (y + ½)/h, 1); Scale maps it to
    // 0.5 texture units, so 256 px cover 256 exemplar pixels at 512 px per unit (the photo's own
    // pixel scale). The shader's (u, v) = (x, −y): its image is the core's render of
    // v ∈ [−0.5, 0] with rows flipped (docs/osl.md, "Coordinates").
    Image core_image, osl_image;
    std::string log;
    ASSERT_TRUE(osl_test::run_testshade(ShimShader(description, dir).text, *make_texture(description), dir, 256, 0.5,
                                        core_image, osl_image, log))
        << log;
    const ComparisonReport report = compare_images(core_image, osl_image);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(report.mean_test[c], report.mean_reference[c], 0.05 * report.stddev_reference[c] + 1e-3) << format_report(report);
        EXPECT_LT(report.w1_relative[c], 0.1) << format_report(report);
    }
    // Pixel by pixel: measured once with OSL 1.13 at 7e-5 sigma RMS (FACTS.md).
    const double rms = osl_test::testshade_rms_sigma(core_image, osl_image);
    std::printf("wavelet testshade vs stex render: rms %.2e sigma\n", rms);
    EXPECT_LT(rms, 1e-3);
}

}  // namespace
