// Tests of the texture metrics: each checks a mathematical property with a known answer.
#include <stochtex/error.h>
#include <stochtex/metrics.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace stochtex {
namespace {

constexpr double kPi = 3.14159265358979323846;

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
    EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 9);
}

}  // namespace
}  // namespace stochtex
