// The tiling OSL shader (osl/stochtex_tiling.h, docs/osl.md): its vertex offsets and tile shifts
// against the core's bit for bit, its maths compiled as C++ (osl_shim.h, texture() reading the
// moment atlas `stex osl` writes) against TilingTexture::eval at thousands of points,
// point-sampled and filtered (isotropic and anisotropic footprints), for the colour and
// normal_map outputs, and oslc / testshade where OSL is installed.
#include "test_support.h"

#include <stochtex/analysis.h>
#include <stochtex/error.h>
#include <stochtex/image.h>
#include <stochtex/models/tiling.h>
#include <stochtex/models/tiling_parameters.h>
#include <stochtex/osl/osl_shader.h>
#include <stochtex/render.h>
#include <stochtex/texture.h>

#include "blending/tiling_grid.h"
#include "osl_shim.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>

namespace osl_shim {
#include "../osl/stochtex_tiling.h"
}  // namespace osl_shim

namespace {

using namespace stochtex;

const Image& photo()
{
    static const Image image = read_image_linear(test::repo_exemplar("concrete_512.png"));
    return image;
}

TextureDescription colour_tiling(HistogramMode histogram)
{
    AnalysisOptions options;
    options.model = "tiling";
    options.histogram = histogram;
    options.model_options = {{"exemplar-size", "128"}};
    return analyze(photo(), options);
}

TextureDescription normal_map_tiling()
{
    TilingSourceOptions options;
    options.exemplar_size = 64;
    return normal_map_texture(photo(), 8, options);
}

/// A generated shader evaluated through the shim.
class TilingShim {
public:
    TilingShim(const TextureDescription& description, const std::string& dir)
    {
        osl::OslShaderOptions options;
        options.shader_name = "stochtex_test";
        options.images = osl::osl_image_paths(description, dir, "test");
        text = osl::make_osl_shader(description, options);
        osl::write_osl_images(description, options.images);
        p = osl_test::parse_parameters(text);
        osl_shim::load_image(p.s("moments"));
        osl_shim::load_image(p.s("rows_probe"));
    }

    /// As the shader: the row probe read first (rows_bottom_up < 0), then the texture; or with
    /// the row flag given (a shader that ignored the probe would pass 0).
    Rgb eval(double u, double v, const Footprint2D& f, int rows_bottom_up = -1)
    {
        if (rows_bottom_up < 0) rows_bottom_up = osl_shim::stochtex_rows_bottom_up(p.s("rows_probe"));
        float r = 0, g = 0, b = 0;
        osl_shim::stochtex_tiling(float(u), float(v), float(f.dudx), float(f.dvdx), float(f.dudy), float(f.dvdy),
                                  p.f("pixels_per_unit"), p.n("output_kind"), p.n("taps"), p.n("max_taps"), p.s("moments"),
                                  p.n("width"), p.n("height"), p.n("atlas_height"), rows_bottom_up, p.n("level_count"),
                                  p.i("seed"), p.f("edge_x"), p.f("edge_y"), p.f("centre_x_hi"), p.f("centre_x_lo"),
                                  p.f("centre_y_hi"), p.f("centre_y_lo"), p.a("global_mean"), p.i("knot_count"), p.a("knot_z"),
                                  p.a("knot_value"), p.a("knot_slope"), p.a("gh_node"), p.a("gh_weight"), p.a("mean"),
                                  p.a("basis"), r, g, b);
        return {r, g, b};
    }

    std::string text;
    osl_test::ShaderParameters p;
};

TEST(OslTilingShader, VertexOffsetsAndTileShiftsMatchTheCoreBitForBit)
{
    const TextureDescription description = colour_tiling(HistogramMode::on);
    TilingShim shim(description, test::temp_dir("osltilingbits"));
    const int width = shim.p.n("width"), height = shim.p.n("height");
    // The texture's 2D grid (tiling_texture.cpp: plane 0 keeps the description's seed).
    const TilingParameters& tiling = description.parameters.get<TilingParameters>();
    const TilingGrid grid(description.seed, tiling.triangle_edge * std::min(tiling.exemplar.width, tiling.exemplar.height));
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> position(-60000.0, 60000.0);
    const double row = grid.edges()[1] * std::sqrt(3.0) / 2;
    for (int n = 0; n < 3000; ++n) {
        const TileBlend blend = grid.blend(position(rng), position(rng));
        for (const TileVertex& vertex : blend) {
            const int vj = int(std::lround(vertex.centre[1] / row));
            const int vi = int(std::lround(vertex.centre[0] / grid.edges()[0] - 0.5 * vj));
            int hi[2], lo[2];
            osl_shim::stochtex_tiling_offset(shim.p.i("seed"), vi, vj, hi, lo);
            for (int axis = 0; axis < 2; ++axis)
                ASSERT_EQ(std::uint64_t(hi[axis]) << 24 | std::uint64_t(lo[axis]),
                          std::uint64_t(std::ldexp(vertex.offset[axis], 48)))
                    << "vertex (" << vi << ", " << vj << ") axis " << axis;
            const auto shift = tile_position(vertex, 0, 0, width, height);
            ASSERT_EQ(osl_shim::stochtex_tiling_shift(hi[0], lo[0], int(std::log2(width)), shim.p.f("centre_x_hi"),
                                                      shim.p.f("centre_x_lo"), float(vi + 0.5 * vj)),
                      shift[0]);
            ASSERT_EQ(osl_shim::stochtex_tiling_shift(hi[1], lo[1], int(std::log2(height)), shim.p.f("centre_y_hi"),
                                                      shim.p.f("centre_y_lo"), float(vj)),
                      shift[1]);
        }
    }
}

// ---- The shader against the core ----------------------------------------------------------------

// The footprint estimator picks its tap counts and level from the footprint's axis lengths: an
// axis of at most 1 exemplar pixel gets 1 tap, a longer one 2 or more (tiling_noise.cpp). At an
// axis of 1 px ± float rounding the shader (float lengths) and the core (double) may take
// different sides of that step; `threshold` marks the class that sits on it on purpose (a
// rotated 1-px minor axis), which is measured, not held to the tolerances below: a random
// footprint lands within float rounding of the step with a probability of ~1e-7.
struct FootprintClass {
    const char* name;
    double size_px, anisotropy;
    bool threshold = false;
};
const FootprintClass footprint_classes[] = {
    {"point", 0, 1},          {"iso 0.7px", 0.7, 1},  {"iso 3px", 3, 1},      {"iso 12px", 12, 1},
    {"iso 100px", 100, 1},    {"aniso 1.3px x4", 1.3, 4}, {"aniso 2px x8", 2, 8}, {"aniso 5px x16", 5, 16},
    {"aniso 1px x4 (step)", 1, 4, true},
};

struct Agreement {
    double max_sigma = 0, rms_sigma = 0;
};

std::vector<Agreement> compare(const TextureDescription& description, int points_per_class, const std::string& label)
{
    TilingShim shim(description, test::temp_dir("osltiling"));
    const auto texture = make_texture(description);
    const double ppu = description.pixels_per_unit;
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> position(-3.0, 3.0), angle(0, 2 * M_PI);
    auto f32 = [](double v) { return double(float(v)); };

    const std::array<double, 3> sigma = osl_test::channel_sigmas(*texture);

    std::vector<Agreement> result;
    for (const FootprintClass& fc : footprint_classes) {
        Agreement agreement;
        double squares = 0;
        int samples = 0;
        for (int n = 0; n < points_per_class; ++n) {
            const double u = f32(position(rng)), v = f32(position(rng)), a = angle(rng);
            const double major = fc.size_px * fc.anisotropy / ppu, minor = fc.size_px / ppu;
            const Footprint2D f{f32(std::cos(a) * major), f32(std::sin(a) * major), f32(-std::sin(a) * minor),
                                f32(std::cos(a) * minor)};
            const Rgb core = texture->eval({u, v}, f), osl = shim.eval(u, v, f);
            for (int c = 0; c < 3; ++c) {
                const double e = std::abs(double(osl[c]) - core[c]) / sigma[c];
                agreement.max_sigma = std::max(agreement.max_sigma, e);
                squares += e * e;
                ++samples;
            }
        }
        agreement.rms_sigma = std::sqrt(squares / samples);
        std::printf("tiling OSL vs core  %-22s %-14s max %.2e sigma  rms %.2e sigma  (%d channel samples)\n", label.c_str(),
                    fc.name, agreement.max_sigma, agreement.rms_sigma, samples);
        result.push_back(agreement);
    }
    return result;
}

// Tolerances in units of the channel's σ. The shader's texels are the core's moments as floats,
// its interpolation weights and moment sums run in float: measured max ~1e-5 σ. A wrong offset,
// shift, level, tap count or blend weight moves values by ~0.1–1 σ.
constexpr double max_tolerance = 1e-3, rms_tolerance = 1e-4;

void expect_agreement(const std::vector<Agreement>& agreements)
{
    for (std::size_t k = 0; k < agreements.size(); ++k) {
        if (footprint_classes[k].threshold) continue;
        EXPECT_LT(agreements[k].max_sigma, max_tolerance) << footprint_classes[k].name;
        EXPECT_LT(agreements[k].rms_sigma, rms_tolerance) << footprint_classes[k].name;
    }
}

TEST(OslTilingShader, ColourOutputMatchesCore)
{
    expect_agreement(compare(colour_tiling(HistogramMode::on), 500, "colour, histograms"));
    expect_agreement(compare(colour_tiling(HistogramMode::off), 250, "colour, Gaussian"));
    // A file's filter_taps reaches the shader as its `taps` parameter.
    TextureDescription one_tap = colour_tiling(HistogramMode::on);
    one_tap.parameters.get<TilingParameters>().filter_taps = 1;
    expect_agreement(compare(one_tap, 250, "colour, filter_taps 1"));
}

TEST(OslTilingShader, NormalMapOutputMatchesCore)
{
    expect_agreement(compare(normal_map_tiling(), 250, "normal map"));
}

// A host whose texture() runs rows bottom-up (Cycles 5.2) gets the same texture through the row
// probe, bit for bit, at every footprint class (each pyramid level's rows); the shader without it
// (flag 0 there) reads the atlas mirrored: other texels, other levels' rows.
TEST(OslTilingShader, MirroringHostGivesTheSameTextureThroughTheRowProbe)
{
    const TextureDescription description = colour_tiling(HistogramMode::on);
    TilingShim shim(description, test::temp_dir("osltilingrows"));
    const double ppu = description.pixels_per_unit;
    const std::array<double, 3> sigma = osl_test::channel_sigmas(*make_texture(description));
    std::mt19937 rng(23);
    std::uniform_real_distribution<double> position(-3.0, 3.0), angle(0, 2 * M_PI);
    double unprobed = 0;  // in σ: the largest difference a shader ignoring the probe would show
    for (const FootprintClass& fc : footprint_classes) {
        for (int n = 0; n < 40; ++n) {
            const double u = position(rng), v = position(rng), a = angle(rng);
            const double major = fc.size_px * fc.anisotropy / ppu, minor = fc.size_px / ppu;
            const Footprint2D f{std::cos(a) * major, std::sin(a) * major, -std::sin(a) * minor, std::cos(a) * minor};
            const auto shade = [&](int rows) { return shim.eval(u, v, f, rows); };
            unprobed = std::max(unprobed, osl_test::mirroring_host_difference(shade, sigma, fc.name));
        }
    }
    EXPECT_GT(unprobed, 0.5) << "the mirrored host must read other texels";
}

TEST(OslTilingShader, ColourMapOutputIsRefusedWithAReason)
{
    TilingSourceOptions options;
    options.exemplar_size = 64;
    const TextureDescription pair = colour_mapped_texture(photo(), photo(), "green", options);
    osl::OslShaderOptions shader;
    shader.shader_name = "stochtex_test";
    try {
        osl::make_osl_shader(pair, shader);
        FAIL() << "a colour-mapped tiling texture has no OSL form";
    } catch (const Error& e) {
        EXPECT_TRUE(test::contains(e.what(), "colour_map")) << e.what();
        EXPECT_TRUE(test::contains(e.what(), "stochtex_texture.osl")) << e.what();
    }
}

TEST(OslTilingShader, GeneratedShaderIsSelfContained)
{
    osl_test::expect_self_contained(TilingShim(colour_tiling(HistogramMode::automatic), test::temp_dir("osltilingself")).text);
}

// ---- With OSL installed ---------------------------------------------------------------------------

TEST(OslTilingCompiler, GeneratedShaderCompilesAndTestshadeMatchesCore)
{
    if (!test::on_path("oslc") || !test::on_path("testshade")) GTEST_SKIP() << "oslc/testshade not on PATH (Debian packages no OSL): not run";
    const std::string dir = test::temp_dir("osltilingtestshade");
    const TextureDescription description = colour_tiling(HistogramMode::on);
    EXPECT_LT(osl_test::testshade_rms("tiling", TilingShim(description, dir).text, *make_texture(description), dir, 128, 0.25), 0.01);
}

}  // namespace
