// The wavelet model against what paper 000 predicts: band variance, band support, weight
// recovery (Fig. 5), the variance invariant (eq. 2), colour (Fig. 7), histogram matching
// (Fig. 6), anti-aliasing by band clamping, determinism.
#include "test_support.h"

#include "analysis/colour_statistics.h"
#include "spectra/band_power.h"
#include "colour/colour_basis.h"
#include "numerics/random.h"
#include "models/wavelet/wavelet_noise.h"
#include "models/wavelet/wavelet_texture.h"

#include <stochtex/analysis.h>
#include <stochtex/metrics.h>
#include <stochtex/render.h>
#include <stochtex/stex_file.h>
#include <stochtex/models/wavelet_parameters.h>

#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <cmath>
#include <cstdio>

namespace stochtex {
namespace {

/// An RGB-mode texture whose red channel has the given band weights and whose G, B are flat.
TextureDescription red_channel_texture(const std::vector<double>& weights, std::uint32_t seed, double ppu = 512)
{
    TextureDescription d;
    d.model = "wavelet";
    d.seed = seed;
    d.pixels_per_unit = ppu;
    d.colour_mode = ColourMode::rgb;
    d.mean = {0.5, 0.5, 0.5};
    WaveletParameters parameters;
    parameters.band_weights = {weights, std::vector<double>(weights.size(), 0.0), std::vector<double>(weights.size(), 0.0)};
    d.parameters = parameters;
    return d;
}

Image render_at_exemplar_scale(const TextureDescription& d, int size, int threads = 0)
{
    RenderSettings settings;
    settings.width = settings.height = size;
    settings.units_per_pixel = 1.0 / d.pixels_per_unit;
    settings.threads = threads;
    return render(*make_texture(d), settings);
}

/// The committed exemplar (no ../shared needed), analysed with the given histogram mode.
TextureDescription analyse_committed_exemplar(HistogramMode histogram, bool joint_colour = false)
{
    AnalysisOptions options;
    options.histogram = histogram;
    options.joint_colour = joint_colour;
    return analyze(read_image_linear(test::repo_exemplar("concrete_512.png")), options);
}

double variance(const std::vector<float>& values)
{
    double sum = 0, sum_sq = 0;
    for (float v : values) sum += v, sum_sq += double(v) * v;
    const double mean = sum / values.size();
    return sum_sq / values.size() - mean * mean;
}

}  // namespace

TEST(WaveletNoise, BandVarianceIsMeasuredNotAssumed)
{
    // Monte Carlo over random points confirms each tile's own σ_N² (computed on a regular grid).
    SplitMix64 rng(11);
    const WaveletNoise2D& noise2 = WaveletNoise2D::shared();
    const WaveletNoise3D& noise3 = WaveletNoise3D::shared();
    constexpr int samples = 1 << 20;
    double sum2 = 0, sum3 = 0, sum_sliced = 0;
    // A slice: the plane through an arbitrary point spanned by two orthonormal tilted vectors.
    const double t[3] = {0.6, 0.8, 0.0}, b[3] = {-0.48, 0.36, 0.8};
    for (int i = 0; i < samples; ++i) {
        const double x = 1000 * rng.uniform(), y = 1000 * rng.uniform(), z = 1000 * rng.uniform();
        const double v2 = noise2.eval(x, y);
        const double v3 = noise3.eval(x, y, z);
        const double vs = noise3.eval(3.3 + x * t[0] + y * b[0], 7.1 + x * t[1] + y * b[1], 1.7 + x * t[2] + y * b[2]);
        sum2 += v2 * v2, sum3 += v3 * v3, sum_sliced += vs * vs;
    }
    const double mc2 = sum2 / samples, mc3 = sum3 / samples, sliced = sum_sliced / samples;
    std::printf("sigma_N^2: 2D tile %.4f (MC %.4f), 3D tile %.4f (MC %.4f), 3D sliced MC %.4f; paper 0.265\n",
                noise2.variance(), mc2, noise3.variance(), mc3, sliced);
    RecordProperty("sigma_N2_2D", std::to_string(noise2.variance()));
    RecordProperty("sigma_N2_3D", std::to_string(noise3.variance()));
    RecordProperty("sigma_N2_3D_sliced", std::to_string(sliced));
    EXPECT_NEAR(mc2, noise2.variance(), 0.01 * noise2.variance());
    EXPECT_NEAR(mc3, noise3.variance(), 0.01 * noise3.variance());
    EXPECT_NEAR(sliced, noise3.variance(), 0.02 * noise3.variance());
    // Same order as Cook–DeRose's figures, but ours: any large deviation means a broken tile.
    EXPECT_GT(noise2.variance(), 0.2);
    EXPECT_LT(noise2.variance(), 0.35);
}

TEST(WaveletNoise, BandCarriesItsOwnOctave)
{
    // Render one band alone and measure where its power lands: eq. 10's band j must hold most
    // of it, and the neighbours the rest (paper Fig. 3: small overlap).
    for (int band : {0, 2, 4}) {
        std::vector<double> weights(8, 0.0);
        weights[band] = 1;
        const Image image = render_at_exemplar_scale(red_channel_texture(weights, 3), 512);
        const std::vector<double> power = band_powers(image.channel(0), 512, 512, 8, PsdEstimator::periodic_smooth);
        double total = 0;
        for (double p : power) total += p;
        std::printf("band %d alone: fraction of power in bands j-1, j, j+1 = %.3f %.3f %.3f\n", band,
                    band > 0 ? power[band - 1] / total : 0.0, power[band] / total, power[band + 1] / total);
        EXPECT_GT(power[band] / total, 0.75) << "band " << band;
    }
}

TEST(WaveletAnalysis, RecoversRandomWeights)
{
    // Paper Fig. 5 made quantitative: random weights → 512² synthesis → analysis, 20 seeds.
    constexpr int seeds = 20, bands = 8;
    std::vector<double> relative_error_sum(bands, 0.0);
    AnalysisOptions options;
    options.colour_mode = ColourMode::rgb;
    options.histogram = HistogramMode::off;
    for (int seed = 1; seed <= seeds; ++seed) {
        SplitMix64 rng(seed * 7919);
        std::vector<double> weights(bands);
        for (double& w : weights) w = 0.02 + 0.08 * rng.uniform();
        const Image image = render_at_exemplar_scale(red_channel_texture(weights, seed), 512);
        const TextureDescription recovered = analyze(image, options);
        const auto& w = recovered.parameters.get<WaveletParameters>().band_weights[0];
        ASSERT_EQ(w.size(), std::size_t(bands));
        for (int j = 0; j < bands; ++j) relative_error_sum[j] += std::abs(w[j] - weights[j]) / weights[j];
    }
    for (int j = 0; j < bands; ++j) {
        const double mean_error = relative_error_sum[j] / seeds;
        const int paper_band = 9 - j;  // paper's b for 512²: 9 is the finest
        std::printf("band j=%d (paper b=%d): mean relative weight error %.1f %%\n", j, paper_band, 100 * mean_error);
        if (paper_band >= 6) EXPECT_LT(mean_error, 0.05) << "fine band b=" << paper_band;
        EXPECT_LT(mean_error, 0.35) << "band b=" << paper_band;
    }
}

class ExemplarTest : public ::testing::TestWithParam<const char*> {};

TEST_P(ExemplarTest, VarianceInvariantHolds)
{
    // Eq. 2: σ_N² Σ w² must equal each decorrelated channel's variance.
    const std::string path = test::shared_exemplar(GetParam());
    if (path.empty()) GTEST_SKIP() << "../shared/exemplars not present";
    const Image photo = read_image_linear(path);
    AnalysisOptions options;
    options.histogram = HistogramMode::off;
    const TextureDescription d = analyze(photo, options);
    ColourBasis basis;
    basis.mean = d.mean;
    basis.basis = d.basis;
    const auto channels = decorrelate(photo, basis);
    const WaveletTexture texture(d);
    for (int c = 0; c < 3; ++c) {
        const double expected = texture.sigma_m()[c] * texture.sigma_m()[c];
        const double measured = variance(channels[c]);
        std::printf("%s channel %d: sigma_N^2 sum w^2 / var = %.4f\n", GetParam(), c, expected / measured);
        EXPECT_NEAR(expected / measured, 1.0, 0.05) << GetParam() << " channel " << c;
    }
}

TEST_P(ExemplarTest, SynthesisMatchesPhotoStatistics)
{
    const std::string path = test::shared_exemplar(GetParam());
    if (path.empty()) GTEST_SKIP() << "../shared/exemplars not present";
    const Image photo = read_image_linear(path);
    const TextureDescription d = analyze(photo, AnalysisOptions{});
    const Image synthesis = render_at_exemplar_scale(d, photo.width);
    const ComparisonReport report = compare_images(photo, synthesis);
    std::printf("%s: covariance error %.3f, log-PSD dB %.2f %.2f %.2f, W1/sigma %.3f %.3f %.3f\n", GetParam(),
                report.covariance_error, report.log_psd_db[0], report.log_psd_db[1], report.log_psd_db[2],
                report.w1_relative[0], report.w1_relative[1], report.w1_relative[2]);
    EXPECT_LT(report.covariance_error, 0.10);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(report.mean_test[c], report.mean_reference[c], 0.1 * report.stddev_reference[c] + 1e-4);
        EXPECT_LT(report.log_psd_db[c], 3.0);
    }
}

INSTANTIATE_TEST_SUITE_P(SharedExemplars, ExemplarTest,
                         ::testing::Values("concrete.png", "dirt.png", "grass.png", "rusted_metal.png", "sandy_rock.png"),
                         [](const auto& info) {
                             std::string name = info.param;
                             return name.substr(0, name.find('.'));
                         });

TEST(WaveletAnalysis, PcaBeatsIndependentRgbOnColour)
{
    // Paper Fig. 7: only decorrelated channels reproduce the photo's colour covariance.
    std::string path = test::shared_exemplar("grass.png");
    if (path.empty()) GTEST_SKIP() << "../shared/exemplars not present";
    const Image photo = read_image_linear(path);
    double error[2];
    int i = 0;
    for (ColourMode mode : {ColourMode::pca, ColourMode::rgb}) {
        AnalysisOptions options;
        options.colour_mode = mode;
        const Image synthesis = render_at_exemplar_scale(analyze(photo, options), photo.width);
        error[i++] = covariance_relative_error(photo, synthesis);
    }
    std::printf("grass colour covariance error: pca %.3f, independent rgb %.3f\n", error[0], error[1]);
    EXPECT_LT(error[0], 0.10);
    EXPECT_LT(error[0], error[1]);
}

TEST(WaveletAnalysis, HistogramMatchingReducesW1OnANonGaussianPhoto)
{
    std::string path = test::shared_exemplar("rusted_metal.png");
    if (path.empty()) GTEST_SKIP() << "../shared/exemplars not present";
    const Image photo = read_image_linear(path);
    double w1[2] = {0, 0};
    int i = 0;
    for (HistogramMode mode : {HistogramMode::on, HistogramMode::off}) {
        AnalysisOptions options;
        options.histogram = mode;
        const ComparisonReport report = compare_images(photo, render_at_exemplar_scale(analyze(photo, options), photo.width));
        w1[i++] = (report.w1_relative[0] + report.w1_relative[1] + report.w1_relative[2]) / 3;
    }
    std::printf("rusted_metal mean W1/sigma: histogram on %.3f, off %.3f\n", w1[0], w1[1]);
    EXPECT_LT(w1[0], 0.8 * w1[1]);
}

TEST(WaveletAnalysis, WorksOnTheCommittedExemplarAndNonSquarePhotos)
{
    const Image photo = read_image_linear(test::repo_exemplar("concrete_512.png"));
    const TextureDescription d = analyze(photo, AnalysisOptions{});
    EXPECT_EQ(d.parameters.get<WaveletParameters>().band_weights[0].size(), 8u);
    // A non-square, non-power-of-two crop is analysed whole (no cropping to a square).
    Image crop(300, 200, 3);
    for (int y = 0; y < 200; ++y)
        for (int x = 0; x < 300; ++x)
            for (int c = 0; c < 3; ++c) crop.at(x, y, c) = photo.at(x, y, c);
    const TextureDescription e = analyze(crop, AnalysisOptions{});
    EXPECT_EQ(e.parameters.get<WaveletParameters>().band_weights[0].size(), 6u);
    EXPECT_EQ(e.provenance.source_width, 300);
}

TEST(WaveletTexture, RenderIsIdenticalForAnyThreadCount)
{
    const TextureDescription d = analyse_committed_exemplar(HistogramMode::automatic);
    for (bool solid : {false, true}) {
        RenderSettings settings;
        settings.width = settings.height = 96;
        settings.units_per_pixel = 1.7 / d.pixels_per_unit;
        settings.solid = solid;
        settings.threads = 1;
        const Image one = render(*make_texture(d), settings);
        settings.threads = 2;
        const Image two = render(*make_texture(d), settings);
        EXPECT_EQ(one.pixels, two.pixels) << (solid ? "solid" : "2D");
    }
}

namespace {

/// Raster and solid-slice values against eval() / eval_solid(), bit for bit.
void check_vectorised_paths_against_point_methods()
{
    // Analysis gives uniform histogram knots (the cubic's segment by one multiplication); a
    // .stex stores them in float decimals, not uniform to 1e-9 (the segment by search): both.
    const TextureDescription analysed = analyse_committed_exemplar(HistogramMode::on);
    const TextureDescription descriptions[] = {analysed, parse_stex(format_stex(analysed), "t.stex"),
                                               analyse_committed_exemplar(HistogramMode::off),
                                               analyse_committed_exemplar(HistogramMode::on, true)};
    for (const TextureDescription& d : descriptions) {
        const double pixel = 1.0 / d.pixels_per_unit;
        const auto plain = make_texture(d);
        const auto periodic = make_periodic_texture(d, {0.75, 0.5});
        for (const Texture* texture : {plain.get(), periodic.get()})
            for (double footprint_px : {0.0, 1.0, 2.6, 37.0}) {
                RasterRegion region;
                region.origin_u = -0.41, region.origin_v = 0.23;
                region.du = 1.1 * pixel, region.dv = 0.8 * pixel;
                region.x0 = 3, region.y0 = -7, region.width = 77, region.height = 5;
                region.footprint = Footprint2D::square(footprint_px * pixel);
                const std::size_t n = std::size_t(region.width) * region.height;
                std::vector<float> planes(3 * n), rgb(3 * n);
                texture->eval_region(region, RgbOutput::planar(planes.data(), planes.data() + n, planes.data() + 2 * n));
                texture->eval_region(region, rgb.data());
                for (int y = 0; y < region.height; ++y)
                    for (int x = 0; x < region.width; ++x) {
                        const std::size_t p = std::size_t(y) * region.width + x;
                        const Rgb expected = texture->eval({region.u(x), region.v(y)}, region.footprint);
                        for (int c = 0; c < 3; ++c) {
                            ASSERT_EQ(planes[c * n + p], expected[c]) << x << ", " << y << " at " << footprint_px << " px";
                            ASSERT_EQ(rgb[3 * p + c], expected[c]) << x << ", " << y << " at " << footprint_px << " px";
                        }
                    }
            }
        // At 5e9 texture units the lattice indices pass 2^31 (positions may reach 2^45 exemplar pixels).
        const std::pair<double, double> slices[] = {{0.37, 1.0}, {0.37, 3.3}, {0.37, 29.0}, {5e9, 1.0}, {5e9, 3.3}};
        for (const auto& [origin, footprint_px] : slices) {
            SolidRegion slice;
            slice.plane.origin_u = origin, slice.plane.origin_v = -1.9;
            slice.plane.du = 0.9 * pixel, slice.plane.dv = 1.2 * pixel;
            slice.plane.x0 = -4, slice.plane.y0 = 11, slice.plane.width = 61, slice.plane.height = 4;
            slice.plane.footprint = Footprint2D::square(footprint_px * pixel);
            slice.w = -0.77;
            std::vector<float> rgb(std::size_t(slice.plane.width) * slice.plane.height * 3);
            plain->eval_solid_region(slice, RgbOutput::interleaved(rgb.data()));
            for (int y = 0; y < slice.plane.height; ++y)
                for (int x = 0; x < slice.plane.width; ++x) {
                    const Rgb expected = plain->eval_solid(slice.point(x, y));
                    for (int c = 0; c < 3; ++c)
                        ASSERT_EQ(rgb[(std::size_t(y) * slice.plane.width + x) * 3 + c], expected[c])
                            << "solid " << x << ", " << y << " at " << footprint_px << " px";
                }
        }
        // Scattered surface points (a position-map bake), each with its own footprint: more
        // than one 256-point chunk and not a multiple of any vector length; positions negative,
        // near the origin and at 5e9 units; footprints from a point sample to most bands dropped.
        SplitMix64 rng(17);
        std::vector<SurfacePoint> points(601);
        for (std::size_t k = 0; k < points.size(); ++k) {
            SurfacePoint& point = points[k];
            const double far = k % 7 == 3 ? 5e9 : 0.0;
            point.p = {far + 4 * rng.uniform() - 2, 4 * rng.uniform() - 2, far - 3 * rng.uniform()};
            const double footprint_px = k % 5 == 0 ? 0.0 : std::exp2(6 * rng.uniform() - 1);
            point.dpdx = {footprint_px * pixel * rng.uniform(), footprint_px * pixel, 0};
            point.dpdy = {0, 0.5 * footprint_px * pixel, footprint_px * pixel * rng.uniform()};
        }
        std::vector<float> planes(3 * points.size());
        const std::size_t n = points.size();
        plain->eval_solid_points({points.data(), n}, RgbOutput::planar(planes.data(), planes.data() + n, planes.data() + 2 * n));
        for (std::size_t k = 0; k < n; ++k) {
            const Rgb expected = plain->eval_solid(points[k]);
            for (int c = 0; c < 3; ++c) ASSERT_EQ(planes[c * n + k], expected[c]) << "surface point " << k;
        }
    }
}

}  // namespace

TEST(WaveletTexture, VectorisedRasterPathsEqualThePointMethodsBitForBit)
{
    // The SIMD raster (Highway, the CPU's best instruction set) performs eval()'s operations in
    // eval()'s order: every value must be equal, not close. Widths that are not a multiple of any
    // vector length (vector loop and scalar tail), footprints that keep every band, fade some
    // and drop most (the Gauss–Hermite histogram filter), planar and interleaved output, the
    // periodic form, solid slices and scattered surface points; histograms on (the
    // monotone-cubic batch) and off, and joint colour; on every instruction set Highway
    // compiled the kernels for that this CPU has.
    for (const std::int64_t target : hwy::SupportedAndGeneratedTargets()) {
        hwy::SetSupportedTargetsForTest(target);
        SCOPED_TRACE(hwy::TargetName(target));
        check_vectorised_paths_against_point_methods();
    }
    hwy::SetSupportedTargetsForTest(0);
}

TEST(WaveletTexture, MinificationConvergesToTheMean)
{
    const TextureDescription d = analyse_committed_exemplar(HistogramMode::on);
    const auto texture = make_texture(d);
    const Rgb mean = texture->mean();
    const Rgb far = texture->eval({0.3, 0.7}, Footprint2D::square(1e6));
    const Rgb solid_far = texture->eval_solid({{0.3, 0.7, 0.2}, {0, 0, 1}, {1e6, 0, 0}, {0, 1e6, 0}});
    for (int c = 0; c < 3; ++c) {
        EXPECT_FLOAT_EQ(far[c], mean[c]);
        EXPECT_FLOAT_EQ(solid_far[c], mean[c]);
        // With histogram maps the limit is E[f(Z)], which must be the photo's mean, not f(0).
        EXPECT_NEAR(mean[c], d.mean[c], 0.01 * d.mean[c]);
    }
}

TEST(WaveletTexture, BandClampingBeatsPointSamplingAgainstSupersampledReference)
{
    // Filtering error against a 16×16 supersampled box reference, 4 exemplar pixels per pixel.
    const TextureDescription d = analyse_committed_exemplar(HistogramMode::off);
    const auto texture = make_texture(d);
    constexpr int size = 48, super = 16;
    const double step = 4.0 / d.pixels_per_unit;
    double filtered_error = 0, point_error = 0, reference_variance = 0, reference_mean = 0;
    std::vector<double> reference(size * size);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            double sum = 0;
            for (int j = 0; j < super; ++j)
                for (int i = 0; i < super; ++i)
                    sum += texture->eval({(x + (i + 0.5) / super) * step, (y + (j + 0.5) / super) * step},
                                         Footprint2D::point())[1];
            reference[y * size + x] = sum / (super * super);
            reference_mean += reference[y * size + x] / (size * size);
        }
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const Vec2 centre{(x + 0.5) * step, (y + 0.5) * step};
            const double r = reference[y * size + x];
            filtered_error += std::pow(texture->eval(centre, Footprint2D::square(step))[1] - r, 2);
            point_error += std::pow(texture->eval(centre, Footprint2D::point())[1] - r, 2);
            reference_variance += std::pow(r - reference_mean, 2);
        }
    const double filtered = std::sqrt(filtered_error / reference_variance);
    const double point = std::sqrt(point_error / reference_variance);
    std::printf("RMSE / reference sigma at 4 exemplar px per pixel: band clamping %.3f, point sampling %.3f\n",
                filtered, point);
    EXPECT_LT(filtered, 0.7 * point);
}

TEST(WaveletTexture, SolidSliceHasThePhotoVariance)
{
    const TextureDescription d = analyse_committed_exemplar(HistogramMode::off);
    RenderSettings settings;
    settings.width = settings.height = 512;
    settings.units_per_pixel = 1.0 / d.pixels_per_unit;
    const Image flat = render(*make_texture(d), settings);
    settings.solid = true;
    settings.z = 0.37;
    const Image solid = render(*make_texture(d), settings);
    for (int c = 0; c < 3; ++c) {
        const double ratio = variance(solid.channel(c)) / variance(flat.channel(c));
        std::printf("channel %d: solid slice / 2D variance = %.3f\n", c, ratio);
        EXPECT_NEAR(ratio, 1.0, 0.15);
    }
}

}  // namespace stochtex
