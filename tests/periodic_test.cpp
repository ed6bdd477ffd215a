// Periodic textures (make_periodic_texture): what the OIIO plugin's wrapping virtual image and
// the POV-Ray baked maps rely on. Periodicity itself, equality with the plain texture when the
// period fits every band, statistics when bands have to be snapped or dropped, bad periods.
#include "region_check.h"
#include "test_support.h"

#include "analysis/colour_statistics.h"
#include "numerics/random.h"
#include "models/wavelet/wavelet_noise.h"

#include <stochtex/analysis.h>
#include <stochtex/error.h>
#include <stochtex/image.h>
#include <stochtex/metrics.h>
#include <stochtex/render.h>

#include <gtest/gtest.h>

#include <cmath>

namespace stochtex {
namespace {

TextureDescription committed_texture()
{
    static const TextureDescription description = [] {
        AnalysisOptions options;
        options.histogram = HistogramMode::on;  // the non-linear path must wrap as well
        return analyze(read_image_linear(test::repo_exemplar("concrete_512.png")), options);
    }();
    return description;
}

std::array<double, 3> channel_variances(const Image& image)
{
    const auto covariance = colour_covariance(image);
    return {covariance[0][0], covariance[1][1], covariance[2][2]};
}

TEST(PeriodicNoiseTile, AnyEvenPeriodIsPeriodicAndItsVarianceIsExact)
{
    const WaveletNoise2D& tile = WaveletNoise2D::with_period(100, 36);
    SplitMix64 rng(7);
    double sum_sq = 0;
    constexpr int samples = 200000;
    for (int i = 0; i < samples; ++i) {
        const double x = 1000 * (rng.uniform() - 0.5), y = 1000 * (rng.uniform() - 0.5);
        const float value = tile.eval(x, y);
        EXPECT_NEAR(tile.eval(x + 100, y), value, 1e-5) << x << ", " << y;
        EXPECT_NEAR(tile.eval(x, y - 36 * 3), value, 1e-5) << x << ", " << y;
        sum_sq += double(value) * value;
        if (HasFailure()) break;
    }
    // Monte Carlo of E[N²] over uniform points: 200k samples give ~0.5 % standard error.
    EXPECT_NEAR(sum_sq / samples, tile.variance(), 0.02 * tile.variance());
    EXPECT_EQ(&WaveletNoise2D::with_period(256, 256), &WaveletNoise2D::shared());
    EXPECT_THROW(WaveletNoise2D::with_period(7, 8), std::invalid_argument);
}

TEST(PeriodicTexture, RepeatsExactlyWithItsPeriodAtEveryFootprint)
{
    const TextureDescription d = committed_texture();
    const Vec2 period{1000.0 / d.pixels_per_unit, 600.0 / d.pixels_per_unit};  // not powers of two
    const auto texture = make_periodic_texture(d, period);
    SplitMix64 rng(11);
    for (int i = 0; i < 2000; ++i) {
        const Vec2 uv{4 * rng.uniform() - 2, 4 * rng.uniform() - 2};
        const Footprint2D footprint = Footprint2D::square(std::ldexp(1.0, int(10 * rng.uniform())) / d.pixels_per_unit);
        const Rgb a = texture->eval(uv, footprint);
        const Rgb b = texture->eval({uv[0] + period[0], uv[1] - 2 * period[1]}, footprint);
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(a[c], b[c], 1e-5) << "at " << uv[0] << ", " << uv[1];
    }
}

TEST(PeriodicTexture, EqualsThePlainTextureWhenEveryBandFitsThePeriod)
{
    // 2^15 exemplar pixels: every band's natural lattice period is a multiple of the shared
    // 256-cell tile, so nothing is snapped and the two textures are the same function.
    const TextureDescription d = committed_texture();
    const double side = 32768 / d.pixels_per_unit;
    const auto periodic = make_periodic_texture(d, {side, side});
    const auto plain = make_texture(d);
    SplitMix64 rng(3);
    for (int i = 0; i < 2000; ++i) {
        const Vec2 uv{side * rng.uniform(), side * rng.uniform()};
        const Footprint2D footprint = Footprint2D::square(2 * rng.uniform() / d.pixels_per_unit);
        const Rgb a = periodic->eval(uv, footprint), b = plain->eval(uv, footprint);
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(a[c], b[c], 1e-5);
    }
}

TEST(PeriodicTexture, SnappedBandsKeepThePhotoStatistics)
{
    // An awkward 600 × 440-pixel period: bands get non-power-of-two tiles. The render of one
    // period must keep the plain texture's mean and per-channel variance (same pixel scale).
    const TextureDescription d = committed_texture();
    RenderSettings settings;
    settings.width = 600, settings.height = 440;
    settings.units_per_pixel = 1.0 / d.pixels_per_unit;
    const Image periodic = render(*make_periodic_texture(d, {600 / d.pixels_per_unit, 440 / d.pixels_per_unit}), settings);
    settings.width = settings.height = 1024;
    const Image plain = render(*make_texture(d), settings);
    const auto vp = channel_variances(periodic), vq = channel_variances(plain);
    const auto mp = channel_means(periodic), mq = channel_means(plain);
    for (int c = 0; c < 3; ++c) {
        // Sampling error of one texture window: the coarse bands hold few independent cycles
        // in 600 px (the plain 1024² render differs from its own expectation by as much).
        EXPECT_NEAR(vp[c], vq[c], 0.2 * vq[c]) << "channel " << c;
        EXPECT_NEAR(mp[c], mq[c], 0.35 * std::sqrt(vq[c])) << "channel " << c;
    }
}

TEST(PeriodicTexture, BandsCoarserThanThePeriodAreFilteredAway)
{
    // A 16-pixel period holds only the two or three finest bands; the rest count as filtered,
    // so the image average still equals the texture's mean (histogram map included).
    const TextureDescription d = committed_texture();
    const auto texture = make_periodic_texture(d, {16 / d.pixels_per_unit, 16 / d.pixels_per_unit});
    RenderSettings settings;
    settings.width = settings.height = 16;
    settings.units_per_pixel = 1.0 / d.pixels_per_unit;
    const Image image = render(*texture, settings);
    const auto image_mean = channel_means(image);
    const Rgb mean = texture->mean();
    const auto variance = channel_variances(image);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(image_mean[c], mean[c], 0.05 * std::abs(mean[c]) + 2 * std::sqrt(variance[c] / 16)) << c;
        EXPECT_GT(variance[c], 0) << "the fine bands are still there";
    }
}

TEST(PeriodicTexture, RejectsBadPeriods)
{
    const TextureDescription d = committed_texture();
    EXPECT_THROW(make_periodic_texture(d, {0, 1}), Error);
    EXPECT_THROW(make_periodic_texture(d, {1, -1}), Error);
    EXPECT_THROW(make_periodic_texture(d, {1, std::nan("")}), Error);
    EXPECT_THROW(make_periodic_texture(d, {1, INFINITY}), Error);
}

}  // namespace
}  // namespace stochtex

namespace stochtex {
namespace {

TEST(RasterRegion, SeparableRegionPathIsBitIdenticalToPointEvaluation)
{
    // WaveletTexture::eval_region shares splines along rows and columns; it must still give
    // exactly eval()'s values (tiles of the plugin, renders and single lookups agree).
    const TextureDescription d = committed_texture();
    test::expect_region_matches_points(*make_texture(d), d.pixels_per_unit);
    test::expect_region_matches_points(*make_periodic_texture(d, {300 / d.pixels_per_unit, 200 / d.pixels_per_unit}),
                                       d.pixels_per_unit);
}

}  // namespace
}  // namespace stochtex
