// Tiling and blending (docs/models/tiling.md): the identities of the moment pyramid and the
// estimators, the error tables' claims in small (each improvement lowers ‖Ŝ − S̄‖ against the
// brute-force reference), flicker under zoom, LEAN, the periodic form, the .stex block's
// round trip and its strict validation.
#include "test_support.h"

#include "analysis/model_choice.h"
#include "schema/base64.h"
#include "models/tiling/colour_map_filter.h"
#include "models/tiling/colour_maps.h"
#include "models/tiling/moment_pyramid.h"
#include "models/tiling/normal_map_filter.h"
#include "schema/quantised_image.h"
#include "models/tiling/tiling_estimator_reference.h"
#include "models/tiling/tiling_exemplar.h"
#include "models/tiling/tiling_texture.h"

#include <stochtex/analysis.h>
#include <stochtex/error.h>
#include <stochtex/metrics.h>
#include <stochtex/render.h>
#include <stochtex/stex_file.h>
#include <stochtex/models/tiling.h>
#include <stochtex/models/tiling_parameters.h>
#include <stochtex/models/tiling_shader_data.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <functional>
#include <random>

namespace stochtex {
namespace {

// ---- Inputs ---------------------------------------------------------------------------------------

const Image& committed_photo()
{
    static const Image photo = read_image_linear(test::repo_exemplar("concrete_512.png"));
    return photo;
}

/// The committed photo's luminance and its transpose as a noise pair in [0, 1], side², periodic.
std::vector<std::vector<double>> noise_pair(int side)
{
    const Image& photo = committed_photo();
    std::vector<float> luma(photo.pixel_count());
    for (std::size_t i = 0; i < luma.size(); ++i)
        luma[i] = 0.2126f * photo.pixels[3 * i] + 0.7152f * photo.pixels[3 * i + 1] + 0.0722f * photo.pixels[3 * i + 2];
    const std::vector<float> p = periodic_crop(luma, photo.width, photo.height, side, side);
    double sum = 0, sum2 = 0;
    for (float v : p) sum += v, sum2 += double(v) * v;
    const double mean = sum / p.size(), sigma = std::sqrt(sum2 / p.size() - mean * mean);
    std::vector<std::vector<double>> planes(2, std::vector<double>(p.size()));
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x) {
            planes[0][std::size_t(y) * side + x] = std::clamp(0.5 + (p[std::size_t(y) * side + x] - mean) / (6 * sigma), 0.0, 1.0);
            planes[1][std::size_t(y) * side + x] = std::clamp(0.5 + (p[std::size_t(x) * side + y] - mean) / (6 * sigma), 0.0, 1.0);
        }
    return planes;
}

TilingNoise make_noise(const std::vector<std::vector<double>>& planes, int side, std::uint32_t seed = 1)
{
    return TilingNoise(std::make_shared<const MomentPyramid>(planes, side, side), TilingGrid(seed, side / (2 * std::sqrt(3.0))));
}

ColourMapFilter linear_map(const std::string& name)
{
    std::vector<float> map = named_colour_map(name, 64);
    for (float& v : map) v = v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
    return ColourMapFilter(map, 64);
}

TextureDescription colour_tiling()
{
    static const TextureDescription d = [] {
        AnalysisOptions options;
        options.model = "tiling";
        options.histogram = HistogramMode::on;
        options.model_options = {{"exemplar-size", "128"}};
        return analyze(committed_photo(), options);
    }();
    return d;
}

// ---- Moment pyramid and grid --------------------------------------------------------------------

TEST(MomentPyramid, CoarsestLevelIsTheExactMomentsAndLevelZeroHasNoVariance)
{
    const int side = 64;
    const auto planes = noise_pair(side);
    const MomentPyramid pyramid(planes, side, side);
    ASSERT_EQ(pyramid.level_count(), 7);
    double mean[2] = {0, 0};
    for (int a = 0; a < 2; ++a) {
        for (double v : planes[a]) mean[a] += v;
        mean[a] /= planes[a].size();
    }
    const Moments top = pyramid.global();
    for (int a = 0; a < 2; ++a) {
        EXPECT_NEAR(top.mean[a], mean[a], 1e-14);
        for (int b = 0; b < 2; ++b) {
            double cov = 0;
            for (std::size_t i = 0; i < planes[a].size(); ++i) cov += (planes[a][i] - mean[a]) * (planes[b][i] - mean[b]);
            EXPECT_NEAR(top.moment(a, b), cov / planes[a].size(), 1e-15) << a << b;
        }
    }
    // Level 2: the exact moments of each 4×4 block (law of total variance, never a mean of variances).
    const Moments block = pyramid.texel(2, 3, 5);
    double m = 0, m2 = 0;
    for (int y = 20; y < 24; ++y)
        for (int x = 12; x < 16; ++x) m += planes[0][std::size_t(y) * side + x] / 16;
    for (int y = 20; y < 24; ++y)
        for (int x = 12; x < 16; ++x) m2 += std::pow(planes[0][std::size_t(y) * side + x] - m, 2) / 16;
    EXPECT_NEAR(block.mean[0], m, 1e-15);
    EXPECT_NEAR(block.moment(0, 0), m2, 1e-15);
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x) ASSERT_EQ(pyramid.texel(0, x, y).moment(0, 0), 0.0);
    EXPECT_THROW(MomentPyramid(planes, 64, 32), Error);
}

TEST(TilingGrid, WeightsPreserveVarianceAndThePeriodicLatticeRepeats)
{
    const TilingGrid plain(5, 30.0);
    const TilingGrid periodic(5, 30.0, {700.0, 410.0});
    for (int i = 0; i < 5000; ++i) {
        const double x = 1e4 * std::sin(i * 1.7), y = 1e4 * std::cos(i * 2.3);
        for (const TilingGrid* grid : {&plain, &periodic}) {
            const TileBlend b = grid->blend(x, y);
            double sum2 = 0;
            for (const TileVertex& v : b) {
                EXPECT_GE(v.weight, 0);
                sum2 += v.weight * v.weight;
            }
            ASSERT_NEAR(sum2, 1, 1e-12);
        }
        const TileBlend a = periodic.blend(x, y), b = periodic.blend(x + 700, y - 2 * 410);
        for (int k = 0; k < 3; ++k) {
            ASSERT_NEAR(a[k].weight, b[k].weight, 1e-9);
            ASSERT_EQ(a[k].offset, b[k].offset);
            ASSERT_NEAR(b[k].centre[0] - a[k].centre[0], 700, 1e-6);
            ASSERT_NEAR(b[k].centre[1] - a[k].centre[1], -820, 1e-6);
            ASSERT_NEAR(b[k].period_shift[0] - a[k].period_shift[0], 700, 1e-6);
            ASSERT_NEAR(b[k].period_shift[1] - a[k].period_shift[1], -820, 1e-6);
        }
    }
}

TEST(TilingNoise, EstimatorsReturnTheExemplarMomentsAtTheCoarsestLevelAndNoVarianceAtLevelZero)
{
    const int side = 64;
    const TilingNoise noise = make_noise(noise_pair(side), side);
    const Moments global = noise.global();
    for (int i = 0; i < 500; ++i) {
        const double x = 997.0 * std::sin(i), y = 991.0 * std::cos(3.0 * i);
        const Moments top = noise.texel_estimate(x, y, 99, TexelInterpolation::linear);
        const Moments wide = noise.footprint_estimate(x, y, Footprint2D::square(1e6), {});
        for (const Moments* m : {&top, &wide})
            for (int a = 0; a < 2; ++a) {
                ASSERT_NEAR(m->mean[a], global.mean[a], 1e-14);
                for (int b = 0; b < 2; ++b) ASSERT_NEAR(m->moment(a, b), global.moment(a, b), 1e-14);
            }
        const Moments point = noise.point(x, y);
        ASSERT_EQ(point.moment(0, 0), 0.0);
        ASSERT_EQ(point.moment(1, 1), 0.0);
        // The covariance over a footprint is positive semi-definite (a mixture of PSD parts).
        const Moments f = noise.footprint_estimate(x, y, Footprint2D{7, 3, -2, 9}, {});
        ASSERT_GE(f.moment(0, 0) * f.moment(1, 1) - f.moment(0, 1) * f.moment(0, 1), -1e-15);
    }
}

TEST(TilingNoise, BlendingKeepsTheExemplarVariance)
{
    // Σ w² = 1 with mean-centred tiles: the blended noise has the exemplar's variance (up to the
    // sampling error of a window holding ~30 tiles), not the ~0.6× a plain linear blend gives.
    const int side = 128;
    const TilingNoise noise = make_noise(noise_pair(side), side);
    const NoiseRaster raster = sample_noise(noise, 1000, -500, 512);
    const std::vector<NoiseBlock> all = noise_blocks(raster, 512, [](const Moments&) { return Rgb{}; });
    for (int a = 0; a < 2; ++a) EXPECT_NEAR(all[0].exact.moment(a, a) / noise.global().moment(a, a), 1.0, 0.12) << a;
}

// ---- Colour-map filtering -------------------------------------------------------------------------

TEST(ColourMapFilter, CovarianceAndInterpolationApproachTheGaussianExpectation)
{
    // Ŝ(μ, Σ) against the quadrature oracle E[S(N)], N ~ 𝒩(μ, Σ), over correlated and
    // uncorrelated spreads: each improvement must lower the mean error.
    const ColourMapFilter map = linear_map("rgb");
    double error[3] = {0, 0, 0};
    int count = 0;
    for (double sigma : {0.01, 0.03, 0.08, 0.15})
        for (double rho : {0.0, 0.6, -0.9})
            for (double ma : {0.35, 0.5, 0.62}) {
                const PairCovariance c{sigma * sigma, rho * sigma * sigma * 0.8, sigma * sigma * 0.64};
                const Rgb truth = map.expected(ma, 0.45, c);
                int m = 0;
                for (ColourMapMethod method : {ColourMapMethod::reference, ColourMapMethod::interpolated, ColourMapMethod::covariance})
                    error[m++] += colour_distance(map.filtered(ma, 0.45, c, method), truth);
                ++count;
            }
    EXPECT_LT(error[1], 0.8 * error[0]) << "interpolated " << error[1] / count << " vs reference " << error[0] / count;
    EXPECT_LT(error[2], 0.8 * error[1]) << "covariance " << error[2] / count << " vs interpolated " << error[1] / count;
    // No spread: the map itself.
    const Rgb exact = map.point(0.3, 0.7);
    for (ColourMapMethod method : {ColourMapMethod::reference, ColourMapMethod::interpolated, ColourMapMethod::covariance})
        EXPECT_LT(colour_distance(map.filtered(0.3, 0.7, {}, method), exact), 1e-6);
}

TEST(ColourMapFilter, APerfectCorrelationIsTheLimitOfNearlyPerfectOnes)
{
    // A pair indexing the map by one noise twice (var_a = var_b = |cov|) has no axis-aligned
    // blur left: the lookup reads the unblurred table alone. Where the split's rounding used to
    // leave d ~ 1e-16 var (a blur level ~1e-8 read from four tables), the result must be what a
    // correlation short of perfect by that much gives: within 1e-6 in linear RGB.
    const ColourMapFilter map = linear_map("rgb");
    double worst = 0;
    for (double sigma : {0.002, 0.01, 0.05, 0.15})
        for (double sign : {1.0, -1.0})
            for (double ma : {0.2, 0.5, 0.71})
                for (double mb : {0.3, 0.55}) {
                    const double v = sigma * sigma;
                    const PairCovariance perfect{v, sign * v, v}, nearly{v, sign * v * (1 - 1e-15), v};
                    const ColourMapMethod method = ColourMapMethod::covariance;
                    const Rgb a = map.lookup(ma, mb, perfect, method), b = map.lookup(ma, mb, nearly, method);
                    worst = std::max(worst, double(colour_distance(a, b)));
                    EXPECT_LT(colour_distance(a, map.filtered(ma, mb, perfect, method)), 1e-6);
                }
    EXPECT_LT(worst, 1e-6);
    std::printf("perfect vs nearly perfect correlation: max %.3g (linear RGB)\n", worst);
}

/// Mean ‖Ŝ(μ̂, σ̂) − S̄‖ over k×k blocks for one estimator and lookup method.
double colour_error(const TilingNoise& noise, const NoiseRaster& raster, const ColourMapFilter& map, int k,
                    const FootprintSampling& sampling, ColourMapMethod method, bool exact_moments = false)
{
    const auto blocks = noise_blocks(raster, k, [&](const Moments& m) { return map.point(m.mean[0], m.mean[1]); });
    std::vector<double> errors;
    for (const NoiseBlock& b : blocks) {
        const Moments m = exact_moments ? b.exact : noise.footprint_estimate(b.x, b.y, Footprint2D::square(k), sampling);
        errors.push_back(colour_distance(map.filtered(m.mean[0], m.mean[1], {m.moment(0, 0), m.moment(0, 1), m.moment(1, 1)}, method),
                                         b.box_colour));
    }
    return summarise(errors).mean;
}

TEST(TilingEstimators, ImprovementsLowerTheColourErrorAgainstBruteForce)
{
    // The acceptance tables in small (docs/models/tiling.md has the 1024² ones): a 128² noise
    // pair, a 256² brute-force window. The paper's method (one texel, rounded blur level, no
    // covariance) versus stochtex's default (2×2 taps, interpolated levels, covariance).
    const int side = 128;
    const TilingNoise noise = make_noise(noise_pair(side), side);
    const NoiseRaster raster = sample_noise(noise, 37, 11, 256);
    const FootprintSampling paper{1, 1, TexelInterpolation::linear}, ours;
    for (const char* name : {"green", "rgb"}) {
        const ColourMapFilter map = linear_map(name);
        for (int k : {4, 16}) {
            const double before = colour_error(noise, raster, map, k, paper, ColourMapMethod::reference);
            const double after = colour_error(noise, raster, map, k, ours, ColourMapMethod::covariance);
            EXPECT_LT(after, 0.75 * before) << name << ", k = " << k;
            // With the exact moments, the lookup improvements alone.
            const double reference = colour_error(noise, raster, map, k, ours, ColourMapMethod::reference, true);
            const double interpolated = colour_error(noise, raster, map, k, ours, ColourMapMethod::interpolated, true);
            const double covariance = colour_error(noise, raster, map, k, ours, ColourMapMethod::covariance, true);
            EXPECT_LT(interpolated, reference) << name << ", k = " << k;
            EXPECT_LE(covariance, interpolated * 1.001) << name << ", k = " << k;
        }
    }
}

TEST(TilingEstimators, PrefilteringFlickersLessUnderZoom)
{
    const int side = 128;
    const TilingNoise noise = make_noise(noise_pair(side), side);
    const ColourMapFilter map = linear_map("rgb");
    auto flicker = [&](const std::function<Rgb(double, double, double)>& render_pixel) {
        const std::vector<double> change = zoom_flicker(render_pixel, 40, 70, 24, 40, 2, 32);
        double sum = 0;
        for (double c : change) sum += c;
        return sum / change.size();
    };
    const double point = flicker([&](double x, double y, double) { const Moments m = noise.point(x, y); return map.point(m.mean[0], m.mean[1]); });
    const double filtered = flicker([&](double x, double y, double px) {
        const Moments m = noise.footprint_estimate(x, y, Footprint2D::square(px), {});
        return map.filtered(m.mean[0], m.mean[1], {m.moment(0, 0), m.moment(0, 1), m.moment(1, 1)}, ColourMapMethod::covariance);
    });
    EXPECT_LT(filtered, 0.5 * point) << "flicker filtered " << filtered << ", point-sampled " << point;
}

TEST(TilingEstimators, LeanBeatsTheMeanNormalAtTheLobeCentre)
{
    const int side = 128;
    auto planes = noise_pair(side);
    for (auto& plane : planes)
        for (double& v : plane) v = (v - 0.5) * 2;  // slopes of σ ≈ 0.33
    const TilingNoise slopes = make_noise(planes, side);
    const NoiseRaster raster = sample_noise(slopes, 0, 0, 256);
    const Direction half{0, 0, 1};
    const double base = 0.05 * 0.05;
    for (int k : {4, 16}) {
        const auto blocks = noise_blocks(raster, k, [&](const Moments& m) {
            const float d = float(facet_ndf(m.mean[0], m.mean[1], base, half));
            return Rgb{d, d, d};
        });
        double lean = 0, naive = 0;
        for (const NoiseBlock& b : blocks) {
            const Moments m = slopes.footprint_estimate(b.x, b.y, Footprint2D::square(k), {});
            lean += std::abs(lean_ndf(m, base, half) - b.box_colour[0]);
            naive += std::abs(facet_ndf(m.mean[0], m.mean[1], base, half) - b.box_colour[0]);
        }
        EXPECT_LT(lean, 0.5 * naive) << "k = " << k;
    }
}

// ---- The texture ------------------------------------------------------------------------------------

TEST(TilingTexture, MinificationConvergesToTheMeanAndTheSolidFormMatchesTheTexturePlane)
{
    const TextureDescription d = colour_tiling();
    const auto texture = make_texture(d);
    const Rgb mean = texture->mean();
    const Rgb far = texture->eval({0.3, 0.7}, Footprint2D::square(1e4));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(far[c], mean[c], 1e-6);
    // A surface facing +w is the 2D texture (plane 0 of the solid blend has weight 1).
    for (int i = 0; i < 50; ++i) {
        SurfacePoint p;
        p.p = {0.1 * i, 0.37 * i, 5.0};
        p.dpdx = {2.0 / d.pixels_per_unit, 0, 0};
        p.dpdy = {0, 2.0 / d.pixels_per_unit, 0};
        const Rgb solid = texture->eval_solid(p), flat = texture->eval({p.p[0], p.p[1]}, Footprint2D::square(2.0 / d.pixels_per_unit));
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(solid[c], flat[c], 1e-6);
        p.n = {0.6, 0.0, 0.8};
        const Rgb tilted = texture->eval_solid(p);
        for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(tilted[c]));
    }
}

TEST(TilingTexture, RenderKeepsThePhotoStatistics)
{
    // Histogram-preserving blending: the synthesis's per-channel distribution is the photo's
    // (W1 in units of the photo's σ), its mean too. The exemplar is the whole photo (a crop
    // would have the crop's statistics, measurably darker here).
    AnalysisOptions options;
    options.model = "tiling";
    options.histogram = HistogramMode::on;
    options.model_options = {{"exemplar-size", "512"}};
    const TextureDescription d = analyze(committed_photo(), options);
    RenderSettings settings;
    settings.width = settings.height = 512;
    settings.units_per_pixel = 1.0 / d.pixels_per_unit;
    const Image synthesis = render(*make_texture(d), settings);
    const ComparisonReport report = compare_images(committed_photo(), synthesis);
    for (int c = 0; c < 3; ++c) {
        EXPECT_LT(report.w1_relative[c], 0.12) << c;
        EXPECT_NEAR(report.mean_test[c], report.mean_reference[c], 0.2 * report.stddev_reference[c]) << c;
        EXPECT_NEAR(report.stddev_test[c], report.stddev_reference[c], 0.1 * report.stddev_reference[c]) << c;
    }
}

TEST(TilingTexture, PeriodicFormRepeatsAtAnyPeriod)
{
    const TextureDescription d = colour_tiling();
    const Vec2 period{300 / d.pixels_per_unit, 170 / d.pixels_per_unit};
    const auto texture = make_periodic_texture(d, period);
    for (int i = 0; i < 500; ++i) {
        const Vec2 uv{std::sin(i * 0.7), std::cos(i * 1.3)};
        const Footprint2D f = Footprint2D::square(std::ldexp(1.0, i % 8) / d.pixels_per_unit);
        const Rgb a = texture->eval(uv, f), b = texture->eval({uv[0] - 2 * period[0], uv[1] + period[1]}, f);
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(a[c], b[c], 2e-5) << i;
    }
}

TEST(TilingTexture, ColourMappedAndNormalMapSourcesRender)
{
    TilingSourceOptions options;
    options.exemplar_size = 64;
    const TextureDescription phasor = phasor_texture("phasor-sine", 1.0 / 8, options);
    const TextureDescription pair = colour_mapped_texture(committed_photo(), committed_photo(), "green", options);
    const TextureDescription normals = normal_map_texture(committed_photo(), 8, options);
    for (const TextureDescription* d : {&phasor, &pair, &normals}) {
        const auto texture = make_texture(*d);
        const Rgb v = texture->eval({0.2, 0.4}, Footprint2D::square(3 / d->pixels_per_unit));
        for (float c : v) EXPECT_TRUE(c >= 0 && c <= 1) << d->provenance.options[1].second;
        EXPECT_EQ(format_stex(parse_stex(format_stex(*d), "t.stex")), format_stex(*d));
    }
    NormalMapShading shading;
    const auto shaded = make_shaded_normal_map(normals, shading);
    EXPECT_GT(shaded->eval({0.1, 0.1}, Footprint2D::square(0.1))[0], 0);
    EXPECT_THROW(make_shaded_normal_map(phasor, shading), Error);
    EXPECT_THROW(phasor_texture("green-ish", 0.1, options), Error);
}

// ---- The .stex block --------------------------------------------------------------------------------

using Json = nlohmann::ordered_json;

using stochtex::test::error_of;

/// The error of parsing the committed texture's JSON after `edit`.
std::string edited_error(const std::function<void(Json&)>& edit)
{
    Json json = Json::parse(format_stex(colour_tiling()));
    edit(json);
    return error_of([&] { parse_stex(json.dump(), "t.stex"); });
}

TEST(TilingStex, RoundTripIsByteIdenticalAndKeepsTheSamples)
{
    const TextureDescription d = colour_tiling();
    const std::string text = format_stex(d);
    const TextureDescription back = parse_stex(text, "t.stex");
    EXPECT_EQ(back.parameters.get<TilingParameters>().exemplar.samples, d.parameters.get<TilingParameters>().exemplar.samples);
    EXPECT_EQ(format_stex(back), text);
    EXPECT_LT(text.size(), std::size_t(80000)) << "a 128² 8-bit exemplar";
}

TEST(TilingStex, BadBlocksAreErrorsNamingTheField)
{
    EXPECT_EQ(edited_error([](Json& j) { j["parameters"]["output"] = "colours"; }),
              "t.stex: parameters.output: unknown tiling output 'colours' (valid: colour, colour_map, normal_map)");
    EXPECT_EQ(edited_error([](Json& j) { j["parameters"]["triangle_edge"] = 2; }),
              "t.stex: parameters.triangle_edge: must be in [0.015625, 1] exemplar widths, got 2");
    EXPECT_EQ(edited_error([](Json& j) { j["parameters"]["exemplar"]["png"] = "abc"; }),
              "t.stex: parameters.exemplar.png: base64 text length 3 is not a multiple of 4");
    EXPECT_EQ(edited_error([](Json& j) { j["parameters"]["exemplar"]["png"] = "ab!d"; }),
              "t.stex: parameters.exemplar.png: invalid base64 character at offset 2");
    EXPECT_EQ(edited_error([](Json& j) { j["parameters"]["exemplar"]["png"] = base64_encode({1, 2, 3, 4, 5, 6, 7, 8, 9}); }),
              "t.stex: parameters.exemplar.png: not a PNG image");
    EXPECT_EQ(edited_error([](Json& j) { j["parameters"]["exemplar"]["width"] = 64; }),
              "t.stex: parameters.exemplar.png: PNG is 128x384 with 1 channel(s); expected 64x384 grey (the planes stacked)");
    EXPECT_EQ(edited_error([](Json& j) { j["parameters"]["exemplar"]["width"] = 100; }),
              "t.stex: parameters.exemplar.width: must be a power of two no larger than 1024, got 100");
    EXPECT_EQ(edited_error([](Json& j) { j["parameters"]["exemplar"]["bits"] = 16; }),
              "t.stex: parameters.exemplar.png: PNG has 8-bit samples; bits says 16");
    EXPECT_EQ(edited_error([](Json& j) { j["parameters"]["exemplar"]["bits"] = 12; }),
              "t.stex: parameters.exemplar.bits: expected 8 or 16, got 12");
    EXPECT_EQ(edited_error([](Json& j) { j["parameters"]["exemplar"]["ranges"][1] = {1, -1}; }),
              "t.stex: parameters.exemplar.ranges[1]: minimum 1 exceeds maximum -1");
    EXPECT_EQ(edited_error([](Json& j) { j["parameters"]["exemplar"]["ranges"].erase(2); }),
              "t.stex: parameters.exemplar.ranges: expected 3 channel ranges, got 2");
    EXPECT_EQ(edited_error([](Json& j) { j["parameters"]["colour_map"] = j["parameters"]["exemplar"]; }),
              "t.stex: parameters.colour_map: must be null for output colour");
    EXPECT_EQ(edited_error([](Json& j) { j["parameters"]["output"] = "colour_map"; }),
              "t.stex: parameters.exemplar.channels: expected 2 for this output, got 3");
    EXPECT_EQ(edited_error([](Json& j) { j["parameters"]["exemplar"]["size"] = 3; }),
              "t.stex: parameters.exemplar.size: unknown field (expected one of: width, height, channels, bits, ranges, png)");
    EXPECT_EQ(edited_error([](Json& j) { j["parameters"].erase("colour_map"); }),
              "t.stex: parameters.colour_map: missing required field");
}

TEST(TilingStex, NonColourOutputsRequireTheirColourMapAndRgbMode)
{
    TilingSourceOptions options;
    options.exemplar_size = 32;
    TextureDescription d = phasor_texture("phasor-square", 1.0 / 8, options);
    TextureDescription bad = d;
    bad.parameters.get<TilingParameters>().colour_map = {};
    EXPECT_EQ(error_of([&] { validate(bad, "t.stex"); }), "t.stex: parameters.colour_map: missing: output colour_map needs a colour map");
    bad = d;
    bad.colour_mode = ColourMode::pca;
    EXPECT_EQ(error_of([&] { validate(bad, "t.stex"); }), "t.stex: colour.mode: must be \"rgb\" for tiling output colour_map");
    bad = d;
    bad.parameters.get<TilingParameters>().colour_map = quantise(std::vector<std::vector<float>>(3, std::vector<float>(16 * 32, 0.5f)), 16, 32, 8);
    EXPECT_EQ(error_of([&] { validate(bad, "t.stex"); }), "t.stex: parameters.colour_map: must be square, got 16x32");
    bad = d;
    bad.parameters.get<TilingParameters>().exemplar.samples[5] = 300;
    EXPECT_EQ(error_of([&] { validate(bad, "t.stex"); }), "t.stex: parameters.exemplar.png: sample 300 exceeds 255");
    bad = d;
    bad.model = "wavelet";
    EXPECT_EQ(error_of([&] { validate(bad, "t.stex"); }), "t.stex: parameters: missing for model 'wavelet'");
}

TEST(TilingCli, AnalyzeInfoRenderAndPhasor)
{
    const std::string dir = test::temp_dir("tiling_cli");
    const std::string stex = dir + "/t.stex", phasor = dir + "/p.stex";
    const auto analyze = test::run_program({STOCHTEX_CLI, "analyze", test::repo_exemplar("concrete_512.png"), "-o", stex,
                                            "--model", "tiling", "--exemplar-size", "64"}, dir);
    ASSERT_TRUE(analyze.succeeded()) << analyze;
    const auto info = test::run_program({STOCHTEX_CLI, "info", stex}, dir);
    ASSERT_TRUE(info.succeeded()) << info;
    EXPECT_TRUE(test::contains(info.out, "exemplar 64x64, 3 channels, 8 bits")) << info.out;
    const auto render = test::run_program({STOCHTEX_CLI, "render", stex, "-o", dir + "/t.png", "--size", "64x64", "--tileable"}, dir);
    EXPECT_TRUE(render.succeeded()) << render;
    const auto made = test::run_program({STOCHTEX_CLI, "tiling", "phasor", "--profile", "square", "-o", phasor, "--exemplar-size", "32"}, dir);
    EXPECT_TRUE(made.succeeded()) << made;
    const auto bad = test::run_program({STOCHTEX_CLI, "tiling", "shade", phasor, "-o", dir + "/s.png"}, dir);
    EXPECT_EQ(bad.code, 1) << bad;
    EXPECT_TRUE(test::contains(bad.err, "needs a tiling texture with output normal_map")) << bad;
}

TEST(TilingFilterTaps, DefaultFilesOmitTheFieldAndOtherCountsRoundTrip)
{
    // Absent means 2 (files written before the field existed read as they rendered), and a
    // default texture does not write it, so its file stays byte for byte what it was.
    const TextureDescription d = colour_tiling();
    EXPECT_EQ(d.parameters.get<TilingParameters>().filter_taps, 2);
    const std::string text = format_stex(d);
    EXPECT_FALSE(test::contains(text, "filter_taps"));
    TextureDescription one = d;
    one.parameters.get<TilingParameters>().filter_taps = 1;
    const std::string one_text = format_stex(one);
    EXPECT_TRUE(test::contains(one_text, "\"filter_taps\": 1")) << one_text.substr(0, 400);
    EXPECT_EQ(parse_stex(one_text, "t.stex").parameters.get<TilingParameters>().filter_taps, 1);
    EXPECT_EQ(format_stex(parse_stex(one_text, "t.stex")), one_text);
}

TEST(TilingFilterTaps, OutOfRangeCountsAreErrorsNamingTheField)
{
    EXPECT_EQ(edited_error([](Json& j) { j["parameters"]["filter_taps"] = 0; }),
              "t.stex: parameters.filter_taps: expected an integer in [1, 4], got 0");
    EXPECT_EQ(edited_error([](Json& j) { j["parameters"]["filter_taps"] = 5; }),
              "t.stex: parameters.filter_taps: expected an integer in [1, 4], got 5");
    EXPECT_FALSE(edited_error([](Json& j) { j["parameters"]["filter_taps"] = 1.5; }).empty());
    EXPECT_FALSE(edited_error([](Json& j) { j["parameters"]["filter_taps"] = "1"; }).empty());
    TextureDescription bad = colour_tiling();
    bad.parameters.get<TilingParameters>().filter_taps = 9;
    EXPECT_EQ(error_of([&] { validate(bad, "t.stex"); }), "t.stex: parameters.filter_taps: must be in [1, 4], got 9");
    TilingSourceOptions options;
    options.exemplar_size = 32;
    options.filter_taps = 0;
    EXPECT_EQ(error_of([&] { phasor_texture("phasor-square", 1.0 / 8, options); }), "filter taps must be in [1, 4], got 0");
}

TEST(TilingFilterTaps, TheFilesCountIsTheEstimatorsTaps)
{
    // make_texture (what the plugin, render and bake use) filters with the file's taps: a
    // filter_taps 1 file gives the one-tap estimator's values bit for bit, on the raster path and
    // per point, and not the default's.
    TextureDescription one = colour_tiling();
    one.parameters.get<TilingParameters>().filter_taps = 1;
    TilingFilterOptions one_tap;
    one_tap.sampling.taps = 1;
    const std::unique_ptr<Texture> from_file = make_texture(one);
    const TilingTexture ablation(colour_tiling(), one_tap);
    const std::unique_ptr<Texture> default_taps = make_texture(colour_tiling());
    RenderSettings settings;
    settings.width = settings.height = 48;
    settings.units_per_pixel = 4.0 / one.pixels_per_unit;  // 4 exemplar pixels: several taps by default
    settings.filter = true;
    const Image file_render = render(*from_file, settings), ablation_render = render(ablation, settings);
    EXPECT_EQ(file_render.pixels, ablation_render.pixels);
    EXPECT_NE(file_render.pixels, render(*default_taps, settings).pixels);
    const Footprint2D footprint = Footprint2D::square(settings.units_per_pixel);
    for (int k = 0; k < 16; ++k) {
        const Vec2 uv{0.013 + 0.071 * k, 0.4 - 0.023 * k};
        EXPECT_EQ(from_file->eval(uv, footprint), ablation.eval(uv, footprint)) << k;
    }
}

TEST(TilingFilterTaps, TheCommandsStoreTheCount)
{
    const std::string dir = test::temp_dir("tiling_filter_taps");
    const std::string stex = dir + "/t.stex", phasor = dir + "/p.stex";
    const auto analyze = test::run_program({STOCHTEX_CLI, "analyze", test::repo_exemplar("concrete_512.png"), "-o", stex,
                                            "--model", "tiling", "--exemplar-size", "32", "--filter-taps", "1"}, dir);
    ASSERT_TRUE(analyze.succeeded()) << analyze;
    EXPECT_EQ(read_stex(stex).parameters.get<TilingParameters>().filter_taps, 1);
    const auto made = test::run_program(
        {STOCHTEX_CLI, "tiling", "phasor", "-o", phasor, "--exemplar-size", "32", "--filter-taps", "3"}, dir);
    ASSERT_TRUE(made.succeeded()) << made;
    EXPECT_EQ(read_stex(phasor).parameters.get<TilingParameters>().filter_taps, 3);
    const auto bad = test::run_program({STOCHTEX_CLI, "analyze", test::repo_exemplar("concrete_512.png"), "-o", dir + "/b.stex",
                                        "--model", "tiling", "--filter-taps", "5"}, dir);
    EXPECT_EQ(bad.code, 1) << bad;
    EXPECT_TRUE(test::contains(bad.err, "--filter-taps: must be an integer in [1, 4], got '5'")) << bad;
}

// ---- Blend contrast ----------------------------------------------------------------------------------

TextureDescription sharpened_tiling(double contrast)
{
    TextureDescription d = colour_tiling();
    d.parameters.get<TilingParameters>().blend_contrast = contrast;
    return d;
}

TEST(TilingBlendContrast, SharperWeightsKeepTheSumOfSquaresAndFavourTheDominantTile)
{
    // A whole contrast (repeated squaring) and one that is not (std::pow).
    const TilingGrid plain(5, 30.0), whole(5, 30.0, 4.0), fractional(5, 30.0, 2.5);
    for (int i = 0; i < 5000; ++i) {
        const double x = 1e4 * std::sin(i * 1.7), y = 1e4 * std::cos(i * 2.3);
        const TileBlend a = plain.blend(x, y);
        for (const TilingGrid* sharp : {&whole, &fractional}) {
            const TileBlend b = sharp->blend(x, y);
            double sum2 = 0;
            int dominant = 0;
            for (int k = 0; k < 3; ++k) {
                ASSERT_EQ(a[k].offset, b[k].offset);  // the same tiles, weighted differently
                sum2 += b[k].weight * b[k].weight;
                if (a[k].weight > a[dominant].weight) dominant = k;
            }
            ASSERT_NEAR(sum2, 1, 1e-12);
            ASSERT_GE(b[dominant].weight, a[dominant].weight - 1e-12);
        }
    }
    EXPECT_THROW(TilingGrid(5, 30.0, 0.5), Error);
}

TEST(TilingBlendContrast, SharpenedBlendingKeepsTheExemplarVariance)
{
    // Σ w² = 1 still: uncorrelated tiles keep the exemplar's variance at any contrast.
    const int side = 128;
    const TilingNoise noise(std::make_shared<const MomentPyramid>(noise_pair(side), side, side),
                            TilingGrid(1, side / (2 * std::sqrt(3.0)), 8.0));
    const NoiseRaster raster = sample_noise(noise, 1000, -500, 512);
    const std::vector<NoiseBlock> all = noise_blocks(raster, 512, [](const Moments&) { return Rgb{}; });
    for (int a = 0; a < 2; ++a) EXPECT_NEAR(all[0].exact.moment(a, a) / noise.global().moment(a, a), 1.0, 0.12) << a;
}

TEST(TilingBlendContrast, MinificationStillConvergesToTheMean)
{
    // The conformance suite's check (HugeFootprintConvergesToTheMean) at a non-default contrast,
    // the periodic form (the OIIO plugin's) included.
    for (const bool periodic : {false, true}) {
        const auto texture = periodic ? make_periodic_texture(sharpened_tiling(4), {3, 2}) : make_texture(sharpened_tiling(4));
        const Rgb mean = texture->mean();
        for (double huge : {1e3, 1e5})
            for (const Vec2& uv : {Vec2{0.1, 0.2}, Vec2{-3.7, 11.3}, Vec2{250.5, -80.25}}) {
                const Rgb value = texture->eval(uv, Footprint2D::square(huge));
                for (int c = 0; c < 3; ++c) EXPECT_NEAR(value[c], mean[c], 2e-3) << huge << (periodic ? " periodic" : "");
            }
    }
}

TEST(TilingBlendContrast, TheFilesContrastIsTheRendersAndDefaultFilesOmitIt)
{
    const TextureDescription d = colour_tiling();
    EXPECT_EQ(d.parameters.get<TilingParameters>().blend_contrast, 1);
    EXPECT_FALSE(test::contains(format_stex(d), "blend_contrast"));
    const TextureDescription sharp = sharpened_tiling(4);
    const std::string text = format_stex(sharp);
    EXPECT_TRUE(test::contains(text, "\"blend_contrast\": 4")) << text.substr(0, 400);
    EXPECT_EQ(format_stex(parse_stex(text, "t.stex")), text);
    RenderSettings settings;
    settings.width = settings.height = 48;
    settings.units_per_pixel = 1.0 / d.pixels_per_unit;
    EXPECT_NE(render(*make_texture(d), settings).pixels, render(*make_texture(sharp), settings).pixels);
    EXPECT_EQ(edited_error([](Json& j) { j["parameters"]["blend_contrast"] = 0.5; }),
              "t.stex: parameters.blend_contrast: must be in [1, 16], got 0.5");
    EXPECT_EQ(edited_error([](Json& j) { j["parameters"]["blend_contrast"] = 17; }),
              "t.stex: parameters.blend_contrast: must be in [1, 16], got 17");
    // The OSL transcription blends with contrast 1: it refuses rather than render another texture.
    EXPECT_TRUE(test::contains(error_of([&] { tiling_shader_data(sharp); }), "parameters.blend_contrast 4"));
}

TEST(TilingBlendContrast, AnalyzeStoresTheOption)
{
    const std::string dir = test::temp_dir("tiling_blend_contrast");
    const std::string stex = dir + "/t.stex";
    const auto analyze = test::run_program({STOCHTEX_CLI, "analyze", test::repo_exemplar("concrete_512.png"), "-o", stex,
                                            "--model", "tiling", "--exemplar-size", "32", "--blend-contrast", "4"}, dir);
    ASSERT_TRUE(analyze.succeeded()) << analyze;
    EXPECT_EQ(read_stex(stex).parameters.get<TilingParameters>().blend_contrast, 4);
    const auto osl = test::run_program({STOCHTEX_CLI, "osl", stex, "-o", dir + "/t.osl"}, dir);
    EXPECT_EQ(osl.code, 1) << osl;
    EXPECT_TRUE(test::contains(osl.err, "blend_contrast")) << osl;
}

TEST(TilingSharedExemplars, GravelKeepsItsHistogram)
{
    const std::string path = test::shared_exemplar("gravel.png");
    if (path.empty()) GTEST_SKIP() << "../shared/exemplars not found";
    const Image photo = read_image_linear(path);
    AnalysisOptions options;
    options.model = "tiling";
    options.model_options = {{"exemplar-size", "512"}};
    const TextureDescription d = analyze(photo, options);
    RenderSettings settings;
    settings.width = settings.height = 512;
    settings.units_per_pixel = 1.0 / d.pixels_per_unit;
    const ComparisonReport report = compare_images(photo, render(*make_texture(d), settings));
    for (int c = 0; c < 3; ++c) EXPECT_LT(report.w1_relative[c], 0.25) << c;
}

// ---- Automatic exemplar size --------------------------------------------------------------------

/// Decorrelated channels of a size² photo: white noise, plus (ramp) a brightness ramp across it
/// that no crop smaller than the photo holds the histogram of.
std::array<std::vector<float>, 3> noise_channels(int size, bool ramp)
{
    std::mt19937 random(3);
    std::normal_distribution<float> noise(0.0f, 0.1f);
    std::array<std::vector<float>, 3> channels;
    for (int c = 0; c < 3; ++c) {
        channels[c].resize(std::size_t(size) * size);
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x)
                channels[c][std::size_t(y) * size + x] = noise(random) + (ramp && c == 0 ? float(x) / size : 0.0f);
    }
    return channels;
}

std::vector<int> candidate_sides(const std::array<std::vector<float>, 3>& channels, int size)
{
    std::vector<int> sides;
    for (const SizedCrop& candidate : automatic_exemplar_candidates(channels, size, size)) {
        EXPECT_EQ(candidate.width, candidate.height);
        sides.push_back(candidate.width);
    }
    return sides;
}

TEST(TilingExemplarSize, LargerCandidatesOnlyWhereTheSmallerCropsMissThePhotosStatistics)
{
    // White noise: the 256² crop stands for the photo, no larger one is rendered.
    EXPECT_EQ(candidate_sides(noise_channels(1024, false), 1024), std::vector<int>({256}));
    // The ramp: 256² misses the histogram, so 512² is tried; 1024² is the whole photo.
    EXPECT_EQ(candidate_sides(noise_channels(1024, true), 1024), std::vector<int>({256, 512}));
    // A 512² photo holds 512² only once: 256² alone.
    EXPECT_EQ(candidate_sides(noise_channels(512, true), 512), std::vector<int>({256}));
}

TEST(TilingExemplarSize, TheCandidatesRendersAreScoredAndTheModelChoiceRuleKeepsOne)
{
    const auto channels = noise_channels(1024, true);
    const std::array<HistogramMap, 3> no_maps{};
    // A scorer standing in for the render: the 512² candidate `gain` times closer to the photo,
    // the file growing with the exemplar.
    const auto chosen_side = [&](double gain) {
        std::vector<int> scored;
        const TilingCandidateScore score = [&](const ModelParameters& parameters, int max_side) {
            EXPECT_EQ(max_side, 1024) << "the photo's size, up to 1024²";
            const int side = parameters.get<TilingParameters>().exemplar.width;
            scored.push_back(side);
            ModelScore s;
            s.penalty = side == 512 ? 1.0 / gain : 1.0;
            s.bytes = (long long)side * side;
            return s;
        };
        const TilingParameters fitted = fit_tiling_exemplar(channels, 1024, 1024, no_maps, automatic_exemplar_side, 8, score,
                                                            chosen_by_rule);
        EXPECT_EQ(scored, std::vector<int>({256, 512}));
        return fitted.exemplar.width;
    };
    EXPECT_EQ(chosen_side(2.0), 512);   // clearly closer: the larger exemplar
    EXPECT_EQ(chosen_side(1.05), 256);  // within the tolerance: the smaller file
    // A single candidate is not rendered.
    const TilingCandidateScore unused = [](const ModelParameters&, int) -> ModelScore {
        ADD_FAILURE() << "a single candidate was scored";
        return {};
    };
    EXPECT_EQ(fit_tiling_exemplar(noise_channels(512, true), 512, 512, no_maps, automatic_exemplar_side, 8, unused, chosen_by_rule).exemplar.width, 256);
}

}  // namespace
}  // namespace stochtex
