// Tests of the texture metrics: each checks a mathematical property with a known answer.
#include <stochtex/error.h>
#include <stochtex/metrics.h>

#include "analysis/colour_statistics.h"
#include "analysis/distribution_distances.h"
#include "analysis/gradient_statistics.h"
#include "analysis/spectral_distances.h"
#include "numerics/constants.h"
#include "spectra/fft.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <random>

namespace stochtex {
namespace {

std::vector<float> white_noise(int width, int height, double stddev, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> normal(0.0f, float(stddev));
    std::vector<float> plane(std::size_t(width) * height);
    for (float& v : plane) v = 3.0f + normal(rng);  // the offset must not matter
    return plane;
}

Image random_rgb(int width, int height, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    Image image(width, height, 3);
    for (float& v : image.pixels) v = uniform(rng);
    return image;
}

std::size_t peak_bin(const RadialPsd& psd) {
    return std::size_t(std::max_element(psd.power.begin(), psd.power.end()) - psd.power.begin());
}

// Power compensation plus density scaling: white noise of variance σ² has expected density σ² in
// every bin, whatever the image size or aspect (this is Parseval with the 1/(W·H) bin area).
TEST(RadialPsd, WhiteNoiseIsFlatAtTheVarianceForAnySize) {
    const double variance = 0.25;
    for (auto [width, height] : {std::pair{256, 256}, std::pair{320, 192}, std::pair{255, 201}}) {
        SCOPED_TRACE(std::to_string(width) + "x" + std::to_string(height));
        const RadialPsd psd = radial_psd(white_noise(width, height, std::sqrt(variance), 7), width, height);
        double sum = 0;
        int bins = 0;
        for (std::size_t i = 0; i < psd.frequency.size(); ++i) {
            if (psd.frequency[i] < 0.1) continue;  // few FFT samples per bin below this
            EXPECT_NEAR(psd.power[i] / variance, 1.0, 0.25) << "at " << psd.frequency[i] << " cycles/px";
            sum += psd.power[i];
            ++bins;
        }
        ASSERT_GT(bins, 8);
        EXPECT_NEAR(sum / bins / variance, 1.0, 0.05);
    }
}

TEST(RadialPsd, BinsSpanFromOneOverMinSizeToNyquistInAscendingOrder) {
    const int width = 96, height = 64, bins_per_octave = 4;
    const RadialPsd psd = radial_psd(white_noise(width, height, 1.0, 3), width, height, bins_per_octave);
    ASSERT_EQ(psd.frequency.size(), psd.power.size());
    ASSERT_FALSE(psd.frequency.empty());
    const double half_bin = std::exp2(0.5 / bins_per_octave);
    EXPECT_NEAR(psd.frequency.front(), 1.0 / height / half_bin, 1e-12);  // bin whose top edge is 1/64
    EXPECT_NEAR(psd.frequency.back(), 0.5 / half_bin, 1e-12);            // bin whose top edge is Nyquist
    for (std::size_t i = 1; i < psd.frequency.size(); ++i) {
        EXPECT_GT(psd.frequency[i], psd.frequency[i - 1]);
        EXPECT_GT(psd.power[i], 0.0);
    }
}

// A cosine of 0.15625 cycles/px (inside bin [0.1487, 0.1768]) along x, then along y, in a
// non-square image: the peak must land in that bin either way, so width and height are not mixed up.
TEST(RadialPsd, CosinePeaksInTheBinHoldingItsFrequency) {
    const int width = 128, height = 96, bins_per_octave = 4;
    const double frequency = 0.15625;  // 20 cycles across 128 px, 15 across 96 px
    const double half_bin = std::exp2(0.5 / bins_per_octave);
    for (bool along_x : {true, false}) {
        SCOPED_TRACE(along_x ? "along x" : "along y");
        std::vector<float> plane(std::size_t(width) * height);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                plane[std::size_t(y) * width + x] = float(std::cos(2 * kPi * frequency * (along_x ? x : y)));
        const RadialPsd psd = radial_psd(plane, width, height, bins_per_octave);
        const double peak = psd.frequency[peak_bin(psd)];
        EXPECT_GT(frequency, peak / half_bin);
        EXPECT_LE(frequency, peak * half_bin);
    }
}

TEST(RadialPsd, RejectsBadArguments) {
    EXPECT_THROW(radial_psd(std::vector<float>(10), 4, 4), Error);
    EXPECT_THROW(radial_psd(std::vector<float>(4), 4, 1), Error);
    EXPECT_THROW(radial_psd(std::vector<float>(16), 4, 4, 0), Error);
}

TEST(LogPsdDistance, IsZeroForItselfAndTenLog10FourForTwiceTheAmplitude) {
    const int width = 80, height = 60;
    std::vector<float> plane = white_noise(width, height, 1.0, 11);
    const RadialPsd psd = radial_psd(plane, width, height);
    EXPECT_DOUBLE_EQ(log_psd_distance_db(psd, psd), 0.0);
    for (float& v : plane) v *= 2.0f;
    EXPECT_NEAR(log_psd_distance_db(radial_psd(plane, width, height), psd), 10 * std::log10(4.0), 1e-4);
}

TEST(LogPsdDistance, ImagesOfDifferentSizesShareBinCentres) {
    const RadialPsd small = radial_psd(white_noise(64, 48, 1.0, 5), 64, 48);
    const RadialPsd large = radial_psd(white_noise(512, 256, 1.0, 6), 512, 256);
    ASSERT_LT(small.frequency.size(), large.frequency.size());
    for (double f : small.frequency)
        EXPECT_NE(std::find(large.frequency.begin(), large.frequency.end(), f), large.frequency.end()) << f;
}

TEST(LogPsdDistance, MatchesBinsByFrequencyNotByIndex) {
    const RadialPsd a{{0.1, 0.2, 0.4}, {1.0, 1.0, 1.0}};
    const RadialPsd b{{0.05, 0.1, 0.2, 0.3}, {7.0, 4.0, 4.0, 9.0}};  // common: 0.1 and 0.2
    EXPECT_NEAR(log_psd_distance_db(b, a), 10 * std::log10(4.0), 1e-12);
    EXPECT_NEAR(log_psd_distance_db(a, b), 10 * std::log10(4.0), 1e-12);
}

TEST(LogPsdDistance, ThrowsWithoutACommonBin) {
    const RadialPsd low{{0.01, 0.02}, {1.0, 1.0}}, high{{0.2, 0.4}, {1.0, 1.0}};
    EXPECT_THROW(log_psd_distance_db(low, high), Error);
    const RadialPsd constant = radial_psd(std::vector<float>(64, 0.5f), 8, 8);
    EXPECT_THROW(log_psd_distance_db(constant, constant), Error);  // zero power everywhere
}

TEST(Wasserstein1, OfAShiftedSampleIsTheShift) {
    std::vector<float> a = white_noise(50, 40, 1.0, 2), b = a;
    for (float& v : b) v += 0.75f;
    std::shuffle(b.begin(), b.end(), std::mt19937(1));  // order must not matter
    EXPECT_NEAR(wasserstein1(a, b), 0.75, 1e-5);
    EXPECT_NEAR(wasserstein1(b, a), 0.75, 1e-5);
    EXPECT_DOUBLE_EQ(wasserstein1(a, a), 0.0);
}

TEST(Wasserstein1, IsExactForDifferentSampleSizes) {
    // F_a − F_b = 1/2 − 1/3 on [0, 0.5) and 1/2 − 2/3 on [0.5, 1): W1 = 1/12 + 1/12.
    EXPECT_NEAR(wasserstein1({0.0f, 1.0f}, {0.0f, 0.5f, 1.0f}), 1.0 / 6.0, 1e-12);
    EXPECT_NEAR(wasserstein1({0.0f}, {1.0f, 2.0f, 3.0f}), 2.0, 1e-12);
    // Tied values each count: on [1, 3) F_a = 2/3 and F_b = 1/2, so W1 = (1/6)·2.
    EXPECT_NEAR(wasserstein1({1.0f, 1.0f, 3.0f}, {1.0f, 3.0f}), 1.0 / 3.0, 1e-12);
}

TEST(Wasserstein1, ThrowsOnAnEmptySample) {
    EXPECT_THROW(wasserstein1({}, {1.0f}), Error);
    EXPECT_THROW(wasserstein1({1.0f}, {}), Error);
}

TEST(ColourCovariance, OfTwoPixelsIsTheOuterProductOfTheHalfDifference) {
    Image image(2, 1, 3);
    for (int c = 0; c < 3; ++c) image.at(1, 0, c) = 2.0f * (c + 1);  // pixels 0 and (2, 4, 6)
    const auto means = channel_means(image);
    const auto covariance = colour_covariance(image);
    for (int r = 0; r < 3; ++r) {
        EXPECT_DOUBLE_EQ(means[r], r + 1.0);
        for (int c = 0; c < 3; ++c) EXPECT_DOUBLE_EQ(covariance[r][c], (r + 1.0) * (c + 1.0));
    }
}

TEST(ColourCovariance, RelativeErrorIsZeroForAnOffsetAndKnownForAScale) {
    const Image reference = random_rgb(40, 30, 9);
    Image offset = reference, doubled = reference, red_doubled = reference;
    for (float& v : offset.pixels) v += 0.5f;
    for (float& v : doubled.pixels) v *= 2.0f;
    for (std::size_t i = 0; i < red_doubled.pixel_count(); ++i) red_doubled.pixels[i * 3] *= 2.0f;
    EXPECT_DOUBLE_EQ(covariance_relative_error(reference, reference), 0.0);
    EXPECT_NEAR(covariance_relative_error(reference, offset), 0.0, 1e-5);
    EXPECT_NEAR(covariance_relative_error(reference, doubled), 3.0, 1e-5);  // ‖4C − C‖/‖C‖
    // Scaling R by 2 maps C to D·C·D with D = diag(2, 1, 1): C_RR ×4, C_RG and C_RB ×2.
    const auto c = colour_covariance(reference);
    double norm_squared = 0;
    for (const auto& row : c)
        for (double v : row) norm_squared += v * v;
    const double expected =
        std::sqrt((9 * c[0][0] * c[0][0] + 2 * (c[0][1] * c[0][1] + c[0][2] * c[0][2])) / norm_squared);
    EXPECT_NEAR(covariance_relative_error(reference, red_doubled), expected, 1e-6);
}

TEST(ColourCovariance, ThrowsForAConstantReference) {
    Image constant(4, 4, 3);
    EXPECT_THROW(covariance_relative_error(constant, random_rgb(4, 4, 1)), Error);
}

TEST(CompareImages, IdenticalImagesScoreZeroAndTwiceTheAmplitudeScoresSixDecibels) {
    const Image reference = random_rgb(64, 48, 4);
    const ComparisonReport same = compare_images(reference, reference);
    for (int c = 0; c < 3; ++c) {
        EXPECT_DOUBLE_EQ(same.mean_test[c], same.mean_reference[c]);
        EXPECT_NEAR(same.stddev_reference[c], std::sqrt(1.0 / 12.0), 0.02);  // uniform [0, 1)
        EXPECT_DOUBLE_EQ(same.w1[c], 0.0);
        EXPECT_DOUBLE_EQ(same.log_psd_db[c], 0.0);
    }
    EXPECT_DOUBLE_EQ(same.covariance_error, 0.0);
    EXPECT_FALSE(same.psd_reference_luma.power.empty());

    Image doubled = reference;
    for (float& v : doubled.pixels) v *= 2.0f;
    const ComparisonReport scaled = compare_images(reference, doubled);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(scaled.stddev_test[c], 2 * scaled.stddev_reference[c], 1e-6);
        EXPECT_NEAR(scaled.w1[c], scaled.mean_reference[c], 1e-5);  // W1 of X vs 2X is E|X| for X ≥ 0
        EXPECT_NEAR(scaled.w1_relative[c], scaled.w1[c] / scaled.stddev_reference[c], 1e-12);
        EXPECT_NEAR(scaled.log_psd_db[c], 10 * std::log10(4.0), 1e-4);
    }
    EXPECT_NEAR(log_psd_distance_db(scaled.psd_test_luma, scaled.psd_reference_luma), 10 * std::log10(4.0), 1e-4);
}

TEST(CompareImages, RequiresThreeChannels) {
    const Image rgb = random_rgb(16, 16, 2);
    Image grey(16, 16, 1);
    try {
        compare_images(rgb, grey);
        FAIL() << "expected stochtex::Error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("3-channel"), std::string::npos) << e.what();
    }
    EXPECT_THROW(compare_images(grey, rgb), Error);
}

TEST(CompareImages, FormatReportHasEveryRow) {
    const std::string text = format_report(compare_images(random_rgb(32, 32, 1), random_rgb(40, 24, 2)));
    for (const char* row : {"mean ref", "mean test", "stddev ref", "stddev test", "W1", "W1/sigma", "log-PSD dB",
                            "covariance error"})
        EXPECT_NE(text.find(row), std::string::npos) << row << " missing from\n" << text;
    EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 9 + 4 + 2);  // + the four rows below, + structure and its parts
    for (const char* row : {"2D log-PSD distance", "gradient orientation W1", "gradient magnitude W1", "false-colour rate",
                            "structure distance", "cross-orientation"})
        EXPECT_NE(text.find(row), std::string::npos) << row << " missing from\n" << text;
}

// ---- What a person sees: orientation, edges, false colour ---------------------------------------

/// White noise filtered in the Fourier domain by √power(fx, fy) (cycles per pixel, fy towards
/// y up): a periodic Gaussian texture whose expected spectrum is power, scaled to unit variance.
std::vector<float> gaussian_texture(int width, int height, unsigned seed,
                                    const std::function<double(double, double)>& power) {
    const std::vector<float> noise = white_noise(width, height, 1.0, seed);
    std::vector<std::complex<float>> spectrum = real_fft_2d(noise, width, height);
    const int spectrum_width = width / 2 + 1;
    for (int ky = 0; ky < height; ++ky)
        for (int kx = 0; kx < spectrum_width; ++kx) {
            const double fx = double(kx) / width, fy_up = -double(ky <= height / 2 ? ky : ky - height) / height;
            spectrum[std::size_t(ky) * spectrum_width + kx] *= float((kx == 0 && ky == 0) ? 0.0 : std::sqrt(power(fx, fy_up)));
        }
    std::vector<float> plane = real_inverse_fft_2d(spectrum, width, height);
    double square = 0;
    for (float v : plane) square += double(v) * v;
    const float scale = float(1.0 / std::sqrt(square / plane.size()));
    for (float& v : plane) v *= scale;
    return plane;
}

/// A Gaussian low-pass elongated along direction `degrees` (σ 0.15 cycles/px along it, 0.02
/// across): stripes running perpendicular to that direction, like ripples or bark; plus a white
/// floor 30 dB down, as a photo's grain and sensor noise (without it the high frequencies hold
/// float rounding only, and even the radial spectra of two realisations differ there by dBs).
std::function<double(double, double)> oriented_power(double degrees) {
    const double c = std::cos(degrees * kPi / 180), s = std::sin(degrees * kPi / 180);
    return [c, s](double fx, double fy) {
        const double along = c * fx + s * fy, across = -s * fx + c * fy;
        return 1e-3 + std::exp(-0.5 * (along * along / (0.15 * 0.15) + across * across / (0.02 * 0.02)));
    };
}

/// The isotropic power with oriented_power's radial profile: its mean over the angle at each radius.
double isotropic_power_like_oriented(double fx, double fy) {
    const double radius = std::hypot(fx, fy);
    const auto oriented = oriented_power(0);
    constexpr int kAngles = 720;
    double sum = 0;
    for (int a = 0; a < kAngles; ++a) sum += oriented(radius * std::cos(2 * kPi * a / kAngles), radius * std::sin(2 * kPi * a / kAngles));
    return sum / kAngles;
}

double polar_distance(const std::vector<float>& a, int wa, int ha, const std::vector<float>& b, int wb, int hb) {
    return polar_log_psd_distance_db(polar_psd(a, wa, ha), polar_psd(b, wb, hb));
}

TEST(PolarPsd, WhiteNoiseIsFlatAtTheVarianceInEveryWellSampledCell) {
    const int width = 256, height = 192;
    const PolarPsd psd = polar_psd(white_noise(width, height, 0.5, 3), width, height);
    ASSERT_EQ(psd.power.size(), psd.frequency.size() * psd.angle_bins);
    ASSERT_EQ(psd.samples.size(), psd.power.size());
    int cells = 0;
    for (std::size_t i = 0; i < psd.power.size(); ++i) {
        if (psd.samples[i] < 400) continue;  // ±0.3 dB of periodogram noise at 200 independent samples
        EXPECT_NEAR(psd.power[i] / 0.25, 1.0, 0.25) << "cell " << i;
        ++cells;
    }
    EXPECT_GT(cells, 30);
}

// A cosine along x puts its power in angle cell 0 (centred on the x axis), one along y in the
// cell centred on 90°; the radius bin is the one radial_psd peaks in.
TEST(PolarPsd, CosinePowerLandsInTheCellOfItsDirection) {
    const int width = 128, height = 96;
    for (bool along_x : {true, false}) {
        SCOPED_TRACE(along_x ? "along x" : "along y");
        std::vector<float> plane(std::size_t(width) * height);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                plane[std::size_t(y) * width + x] = float(std::cos(2 * kPi * 0.15625 * (along_x ? x : y)));
        const PolarPsd psd = polar_psd(plane, width, height);
        const std::size_t peak = std::size_t(std::max_element(psd.power.begin(), psd.power.end()) - psd.power.begin());
        EXPECT_EQ(int(peak % psd.angle_bins), along_x ? 0 : psd.angle_bins / 2);
        const RadialPsd radial = radial_psd(plane, width, height);
        EXPECT_DOUBLE_EQ(psd.frequency[peak / psd.angle_bins], radial.frequency[peak_bin(radial)]);
    }
}

// The case: an oriented texture and an isotropic one with the same radial spectrum.
// The radial metric cannot tell them apart; the 2D one must, while two realisations of the same
// oriented noise (and realisations at different sizes: density normalisation) stay close.
TEST(PolarLogPsdDistance, SeesOrientationTheRadialSpectrumCannot) {
    const int n = 256;
    const std::vector<float> oriented = gaussian_texture(n, n, 1, oriented_power(30));
    const std::vector<float> oriented_again = gaussian_texture(n, n, 2, oriented_power(30));
    const std::vector<float> oriented_larger = gaussian_texture(384, 320, 3, oriented_power(30));
    const std::vector<float> isotropic = gaussian_texture(n, n, 4, isotropic_power_like_oriented);

    const double radial = log_psd_distance_db(radial_psd(oriented, n, n), radial_psd(isotropic, n, n));
    const double radial_same = log_psd_distance_db(radial_psd(oriented, n, n), radial_psd(oriented_again, n, n));
    const double polar = polar_distance(oriented, n, n, isotropic, n, n);
    const double polar_same = polar_distance(oriented, n, n, oriented_again, n, n);
    const double polar_sizes = polar_distance(oriented, n, n, oriented_larger, 384, 320);
    std::printf("radial: oriented vs isotropic %.2f dB, two realisations %.2f dB; 2D: %.2f dB, %.2f dB, "
                "256² vs 384×320 %.2f dB\n", radial, radial_same, polar, polar_same, polar_sizes);
    // At 256² the radial metric's lowest bins hold a few FFT samples each, so two realisations
    // already differ by dBs: "cannot tell apart" means no further than that.
    EXPECT_LT(radial, radial_same + 0.5);
    // The radial metric counts only bins of ≥ 128 samples: its own noise must stay under the
    // fidelity target (1.5 dB), or no synthesis could meet it (with every bin: 3.3 dB here).
    EXPECT_LT(radial_same, 1.5);
    EXPECT_LT(polar_same, 1.5);
    EXPECT_LT(polar_sizes, 1.5);
    EXPECT_GT(polar, 5.0);
    EXPECT_GT(polar, 4 * polar_same);
    // The difference is orientation, not level: the angular part carries nearly all of it.
    const double angular = polar_log_psd_angular_db(polar_psd(oriented, n, n), polar_psd(isotropic, n, n));
    std::printf("2D angular part: oriented vs isotropic %.2f dB\n", angular);
    EXPECT_GT(angular, 0.8 * polar);
    EXPECT_LE(angular, polar);
    EXPECT_DOUBLE_EQ(polar_distance(oriented, n, n, oriented, n, n), 0.0);
}

TEST(PolarLogPsdDistance, TwiceTheAmplitudeIsTenLog10FourWithNoAngularPartAndGridsMustMatch) {
    std::vector<float> plane = white_noise(128, 128, 1.0, 8);
    const PolarPsd psd = polar_psd(plane, 128, 128);
    for (float& v : plane) v *= 2.0f;
    EXPECT_NEAR(polar_log_psd_distance_db(polar_psd(plane, 128, 128), psd), 10 * std::log10(4.0), 1e-4);
    EXPECT_NEAR(polar_log_psd_angular_db(polar_psd(plane, 128, 128), psd), 0.0, 1e-4);  // a level error only
    EXPECT_THROW(polar_log_psd_distance_db(psd, polar_psd(plane, 128, 128, 4, 8)), Error);
    EXPECT_THROW(polar_log_psd_distance_db(psd, psd, 1 << 20), Error);  // no cell that full
    EXPECT_THROW(polar_psd(plane, 128, 128, 4, 0), Error);
}

TEST(CentredSpectrum, CosinePeaksWhereItsFrequencyIsOnTheCentredGrid) {
    const int width = 128, height = 96, size = 64;
    std::vector<float> plane(std::size_t(width) * height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) plane[std::size_t(y) * width + x] = float(std::cos(2 * kPi * 0.25 * x));
    const CentredSpectrum spectrum = centred_spectrum(plane, width, height, size);
    ASSERT_EQ(spectrum.power.size(), std::size_t(size) * size);
    // ±0.25 cycles/px along x: columns (±0.25 + ½)·64 = 16 and 48, the centre row.
    std::vector<std::size_t> order(spectrum.power.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::partial_sort(order.begin(), order.begin() + 2, order.end(),
                      [&](std::size_t a, std::size_t b) { return spectrum.power[a] > spectrum.power[b]; });
    std::vector<std::size_t> peaks{order[0], order[1]};
    std::sort(peaks.begin(), peaks.end());
    EXPECT_EQ(peaks[0], std::size_t(32 * size + 16));
    EXPECT_EQ(peaks[1], std::size_t(32 * size + 48));
}

TEST(CircularWasserstein1, IsTheShortestTurnForPointMasses) {
    std::vector<double> a(36, 0.0), b(36, 0.0), c(36, 0.0);
    a[0] = 1, b[10] = 1, c[30] = 1;  // bins of 5°: at 0°, 50° and 150° (= −30°)
    EXPECT_NEAR(circular_wasserstein1_degrees(a, b), 50.0, 1e-9);
    EXPECT_NEAR(circular_wasserstein1_degrees(a, c), 30.0, 1e-9);  // across 180° ≡ 0°
    EXPECT_NEAR(circular_wasserstein1_degrees(c, a), 30.0, 1e-9);
    EXPECT_DOUBLE_EQ(circular_wasserstein1_degrees(a, a), 0.0);
    std::vector<double> uniform(36, 1.0);  // unnormalised: the distance normalises
    EXPECT_NEAR(circular_wasserstein1_degrees(a, uniform), 45.0, 180.0 / 36);  // mean |turn| to a uniform spread
    EXPECT_THROW(circular_wasserstein1_degrees(a, std::vector<double>(12, 1.0)), Error);
}

/// A Gaussian blur of a periodic plane, in the Fourier domain (σ in pixels).
std::vector<float> blurred(const std::vector<float>& plane, int width, int height, double sigma) {
    std::vector<std::complex<float>> spectrum = real_fft_2d(plane, width, height);
    const int spectrum_width = width / 2 + 1;
    for (int ky = 0; ky < height; ++ky)
        for (int kx = 0; kx < spectrum_width; ++kx) {
            const double fx = double(kx) / width, fy = double(ky <= height / 2 ? ky : ky - height) / height;
            spectrum[std::size_t(ky) * spectrum_width + kx] *= float(std::exp(-2 * kPi * kPi * sigma * sigma * (fx * fx + fy * fy)) / (double(width) * height));
        }
    return real_inverse_fft_2d(spectrum, width, height);
}

// Stripes turned by 90° keep their sharpness and move all gradient energy by 90°; a blur keeps
// the directions and softens the edges. Each metric must see its own change and not the other.
TEST(GradientStatistics, OrientationSeesARotationAndMagnitudeSeesABlur) {
    const int n = 256;
    const std::vector<float> stripes = gaussian_texture(n, n, 1, oriented_power(30));
    const std::vector<float> stripes_again = gaussian_texture(n, n, 2, oriented_power(30));
    const std::vector<float> turned = gaussian_texture(n, n, 3, oriented_power(120));
    const GradientStatistics g = gradient_statistics(stripes, n, n), g_again = gradient_statistics(stripes_again, n, n),
                             g_turned = gradient_statistics(turned, n, n);
    ASSERT_EQ(g.orientation.size(), 36u);
    // Gradients point across the stripes, along the spectrum's long axis: 30°.
    const std::size_t peak = std::size_t(std::max_element(g.orientation.begin(), g.orientation.end()) - g.orientation.begin());
    EXPECT_NEAR(double(peak) * 5.0, 30.0, 5.0);
    const double same = circular_wasserstein1_degrees(g.orientation, g_again.orientation);
    const double rotation = circular_wasserstein1_degrees(g.orientation, g_turned.orientation);
    std::printf("orientation W1: two realisations %.2f°, turned by 90° %.2f°\n", same, rotation);
    EXPECT_LT(same, 3.0);
    EXPECT_GT(rotation, 40.0);  // nearly all energy turns by 90°, in part the short way round

    const auto magnitude_distance = [](const GradientStatistics& a, const GradientStatistics& b) {
        double mean = 0;
        for (float m : a.magnitude_over_sigma) mean += m;
        return wasserstein1(a.magnitude_over_sigma, b.magnitude_over_sigma) / (mean / a.magnitude_over_sigma.size());
    };
    const std::vector<float> isotropic = gaussian_texture(n, n, 5, [](double fx, double fy) {
        return std::exp(-0.5 * (fx * fx + fy * fy) / (0.2 * 0.2));
    });
    const GradientStatistics g_isotropic = gradient_statistics(isotropic, n, n),
                             g_blurred = gradient_statistics(blurred(isotropic, n, n, 1.5), n, n),
                             g_isotropic_again = gradient_statistics(
                                 gaussian_texture(n, n, 6, [](double fx, double fy) { return std::exp(-0.5 * (fx * fx + fy * fy) / (0.2 * 0.2)); }), n, n);
    const double sharp_same = magnitude_distance(g_isotropic, g_isotropic_again);
    const double blur = magnitude_distance(g_isotropic, g_blurred);
    const double blur_orientation = circular_wasserstein1_degrees(g_isotropic.orientation, g_blurred.orientation);
    std::printf("magnitude W1 (relative): two realisations %.3f, blurred (σ 1.5 px) %.3f; blur's orientation W1 %.2f°; "
                "stripes turned: magnitude %.3f\n", sharp_same, blur, blur_orientation, magnitude_distance(g, g_turned));
    EXPECT_LT(sharp_same, 0.03);
    EXPECT_GT(blur, 0.3);
    EXPECT_LT(blur_orientation, 3.0);
    EXPECT_LT(magnitude_distance(g, g_turned), 0.05);
}

TEST(GradientStatistics, RejectsConstantAndTinyPlanes) {
    EXPECT_THROW(gradient_statistics(std::vector<float>(64, 1.0f), 8, 8), Error);
    EXPECT_THROW(gradient_statistics(std::vector<float>(4, 1.0f), 2, 2), Error);
}

/// A colour texture like a photo of soil: luma from a Gaussian texture, chroma drifting slowly
/// along a short brown-to-olive line (natural chroma is a narrow, correlated cluster).
Image soil(int width, int height, unsigned seed) {
    const std::vector<float> detail = gaussian_texture(width, height, seed, [](double fx, double fy) {
        return 1.0 / (1e-4 + fx * fx + fy * fy);
    });
    const std::vector<float> tint = gaussian_texture(width, height, seed + 1, [](double fx, double fy) {
        return std::exp(-0.5 * (fx * fx + fy * fy) / (0.01 * 0.01));
    });
    Image image(width, height, 3);
    for (std::size_t i = 0; i < image.pixel_count(); ++i) {
        const float luma = std::max(0.02f, 0.2f * std::exp(0.5f * detail[i]));
        const float t = 0.5f + 0.15f * tint[i];
        const float brown[3] = {1.4f, 0.95f, 0.6f}, olive[3] = {1.05f, 1.05f, 0.7f};
        for (int c = 0; c < 3; ++c) image.pixels[i * 3 + c] = luma * (brown[c] * (1 - t) + olive[c] * t);
    }
    return image;
}

Image crop(const Image& source, int x0, int y0, int width, int height) {
    Image out(width, height, 3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c) out.at(x, y, c) = source.at(x0 + x, y0 + y, c);
    return out;
}

TEST(FalseColourRate, AnotherCropOfThePhotoIsCleanAndColouredFlecksAreCounted) {
    const Image photo = soil(512, 256, 21);
    const Image left = crop(photo, 0, 0, 256, 256), right = crop(photo, 256, 0, 256, 256);
    EXPECT_LE(false_colour_rate(left, left), 0.005);  // by construction: 99.5 % held, then dilated
    const double other_crop = false_colour_rate(left, right);
    Image flecked = right;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    int flecks = 0;
    for (std::size_t i = 0; i < flecked.pixel_count(); ++i) {
        if (uniform(rng) >= 0.05f) continue;  // 5 % of pixels, half saturated blue, half saturated red
        float* p = &flecked.pixels[i * 3];
        const float luma = 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
        const bool blue = (flecks++ % 2) == 0;
        p[0] = blue ? 0.2f * luma : 2.5f * luma;
        p[1] = 0.2f * luma;
        p[2] = blue ? 4.0f * luma : 0.2f * luma;
    }
    const double flecked_rate = false_colour_rate(left, flecked);
    std::printf("false-colour rate: other crop %.3f %%, with 5 %% flecks %.2f %%\n", 100 * other_crop, 100 * flecked_rate);
    EXPECT_LT(other_crop, 0.01);
    EXPECT_GT(flecked_rate, 0.045);
    EXPECT_LT(flecked_rate, 0.06);  // the flecks, not the rest
}

TEST(FalseColourRate, ChromaIsZeroForGreyAndSignedForRedAndBlue) {
    for (float v : {0.0f, 0.01f, 0.18f, 1.0f, 3.0f}) {
        const auto grey = cielab_chroma(v, v, v);
        EXPECT_NEAR(grey[0], 0.0, 1e-3) << v;
        EXPECT_NEAR(grey[1], 0.0, 1e-3) << v;
    }
    EXPECT_GT(cielab_chroma(0.8f, 0.1f, 0.1f)[0], 40.0);   // red: a* > 0
    EXPECT_LT(cielab_chroma(0.1f, 0.1f, 0.8f)[1], -40.0);  // blue: b* < 0
}

// On the shared photos a crop against the rest of the same photo must stay under 1 %: the
// threshold the acceptance sets for a synthesis.
TEST(FalseColourRate, OtherHalfOfEachSharedColourPhotoIsUnderOnePercent) {
    for (const char* name : {"dirt.png", "gravel.png", "grass.png", "rusted_metal.png"}) {
        const std::string path = test::shared_exemplar(name);
        if (path.empty()) GTEST_SKIP() << "no ../shared/exemplars";
        const Image photo = read_image_linear(path);
        const int half = photo.width / 2;
        const double rate = false_colour_rate(crop(photo, 0, 0, half, photo.height), crop(photo, half, 0, half, photo.height));
        std::printf("%s: false-colour rate of the right half against the left %.3f %%\n", name, 100 * rate);
        EXPECT_LT(rate, 0.01) << name;
    }
}

TEST(CompareImages, PerceptualMetricsAreZeroForItselfAndSeeOrientation) {
    const int n = 256;
    const auto to_rgb = [n](const std::vector<float>& plane) {
        Image image(n, n, 3);
        for (std::size_t i = 0; i < image.pixel_count(); ++i)
            for (int c = 0; c < 3; ++c) image.pixels[i * 3 + c] = 0.5f + 0.1f * plane[i];
        return image;
    };
    const Image oriented = to_rgb(gaussian_texture(n, n, 1, oriented_power(30)));
    const ComparisonReport self = compare_images(oriented, oriented);
    EXPECT_DOUBLE_EQ(self.polar_log_psd_db, 0.0);
    EXPECT_DOUBLE_EQ(self.gradient_orientation_degrees, 0.0);
    EXPECT_DOUBLE_EQ(self.gradient_magnitude_w1, 0.0);
    EXPECT_LE(self.false_colour_rate, 0.005);
    EXPECT_EQ(self.spectrum_reference_luma.size, 256);
    EXPECT_EQ(self.spectrum_test_luma.power, self.spectrum_reference_luma.power);

    const ComparisonReport versus_isotropic = compare_images(oriented, to_rgb(gaussian_texture(n, n, 4, isotropic_power_like_oriented)));
    EXPECT_GT(versus_isotropic.polar_log_psd_db, 5.0);
    EXPECT_GT(versus_isotropic.polar_log_psd_angular_db, 4.0);
    EXPECT_GT(versus_isotropic.gradient_orientation_degrees, 10.0);
    const ComparisonReport versus_again = compare_images(oriented, to_rgb(gaussian_texture(n, n, 2, oriented_power(30))));
    EXPECT_LT(versus_again.polar_log_psd_db, 1.5);
    EXPECT_LT(versus_again.gradient_orientation_degrees, 3.0);
    for (int c = 0; c < 3; ++c) EXPECT_LT(versus_isotropic.log_psd_db[c], versus_again.log_psd_db[c] + 0.5);
}

TEST(CompareImages, OnePreparedReferenceServesManyTestsAsTheMetricsDefineThem) {
    // The model choice prepares the photo's side once and compares every candidate with it:
    // each report must be what the metrics give for that pair, whatever was compared before.
    const Image photo = random_rgb(96, 80, 1);
    const auto luma = [](const Image& rgb) {  // the luma compare_images measures gradients on
        std::vector<float> plane(rgb.pixel_count());
        for (std::size_t i = 0; i < plane.size(); ++i)
            plane[i] = 0.2126f * rgb.pixels[i * 3] + 0.7152f * rgb.pixels[i * 3 + 1] + 0.0722f * rgb.pixels[i * 3 + 2];
        return plane;
    };
    const ComparisonReference prepared(photo);
    EXPECT_EQ(prepared.width(), 96);
    EXPECT_EQ(prepared.height(), 80);
    for (unsigned seed : {2u, 3u, 4u}) {
        const Image test = random_rgb(64 + 8 * int(seed), 72, seed);
        const ComparisonReport report = compare_images(prepared, test);
        for (int c = 0; c < 3; ++c) {
            EXPECT_EQ(report.w1[c], wasserstein1(photo.channel(c), test.channel(c))) << "seed " << seed;
            EXPECT_EQ(report.stddev_reference[c], std::sqrt(colour_covariance(photo)[c][c]));
        }
        EXPECT_EQ(report.mean_reference, channel_means(photo));
        EXPECT_EQ(report.covariance_error, covariance_relative_error(photo, test));
        EXPECT_EQ(report.false_colour_rate, false_colour_rate(photo, test));
        const GradientStatistics a = gradient_statistics(luma(photo), photo.width, photo.height);
        const GradientStatistics b = gradient_statistics(luma(test), test.width, test.height);
        EXPECT_EQ(report.gradient_orientation_degrees, circular_wasserstein1_degrees(a.orientation, b.orientation));
        const ComparisonReport fresh = compare_images(photo, test);
        EXPECT_EQ(report.polar_log_psd_db, fresh.polar_log_psd_db);
        EXPECT_EQ(report.gradient_magnitude_w1, fresh.gradient_magnitude_w1);
        EXPECT_EQ(report.psd_reference_luma.power, fresh.psd_reference_luma.power);
    }
    EXPECT_THROW(ComparisonReference(Image(4, 4, 1)), Error);
}

TEST(CompareImages, PerceptualMetricsAreNotAvailableOnTinyImages) {
    const ComparisonReport tiny = compare_images(random_rgb(8, 8, 1), random_rgb(8, 8, 2));
    EXPECT_TRUE(std::isnan(tiny.polar_log_psd_db));
    EXPECT_TRUE(std::isnan(tiny.polar_log_psd_angular_db));
    for (double db : tiny.log_psd_db) EXPECT_TRUE(std::isnan(db));  // no radius bin holds 128 samples
    EXPECT_NE(format_report(tiny).find("n/a"), std::string::npos);
}

}  // namespace
}  // namespace stochtex
