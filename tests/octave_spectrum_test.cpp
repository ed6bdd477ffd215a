// Spectra as variance per octave, octave fits and channel polylines (octave_spectrum.h,
// channel_map.h): the core's side of re-expressing a texture in another renderer's noise.
#include <stochtex/channel_map.h>
#include <stochtex/error.h>
#include <stochtex/metrics.h>
#include <stochtex/models/channel_spectrum.h>
#include <stochtex/models/wavelet_parameters.h>

#include "numerics/nonnegative_least_squares.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace {

using namespace stochtex;

/// A smooth one-octave-wide bump of variance-per-octave, centred at ℓ = 0, total variance 1.
OctaveSpectrum bump_spectrum()
{
    OctaveSpectrum s;
    const double width = 0.6;
    for (double l = -6; l <= 4 + 1e-9; l += 1.0 / 16) {
        s.log2_frequency.push_back(l);
        s.variance_per_octave.push_back(std::exp(-0.5 * l * l / (width * width)) / (width * std::sqrt(2 * M_PI)));
    }
    return s;
}

TEST(OctaveSpectrum, WhiteNoiseIntegratesToItsVariance)
{
    // Parseval through the conversion: Σ g·dℓ over the measured bins is the variance, minus the
    // corners beyond Nyquist (1 − π/4 of white noise's power) that a radial PSD leaves out.
    constexpr int size = 256;
    std::mt19937 random(11);
    std::normal_distribution<float> normal(0.0f, 2.0f);
    std::vector<float> plane(size * size);
    for (float& v : plane) v = normal(random);
    const OctaveSpectrum g = octave_spectrum(radial_psd(plane, size, size, 8), 1.0);
    EXPECT_NEAR(g.variance(), 4.0 * M_PI / 4, 0.08 * 4.0);
    // White noise: S constant, so g ∝ f²: +6.02 dB per octave.
    const double ratio = g.at(-2.0) / g.at(-3.0);
    EXPECT_NEAR(10 * std::log10(ratio), 6.02, 0.6);
}

TEST(OctaveSpectrum, ShiftingIsScaling)
{
    // The same bump measured in other units is the same curve moved along ℓ.
    const OctaveSpectrum s = bump_spectrum();
    EXPECT_NEAR(s.variance(), 1.0, 1e-3);
    EXPECT_NEAR(s.at(0.3), s.at(-0.3), 1e-12);
    EXPECT_EQ(s.at(100), 0.0);
}

TEST(OctaveSpectrum, FitRecoversKnownOctaveWeights)
{
    // Target: four octaves of the bump at known weights and a known shift; the fit must find both.
    const OctaveSpectrum basis = bump_spectrum();
    const double finest = 5, shift = -0.375;
    const std::vector<double> weights{0.5, 1.0, 0.25, 0.75};
    OctaveSpectrum target;
    double variance = 0;
    for (double l = -2; l <= 7 + 1e-9; l += 1.0 / 8) {
        double g = 0;
        for (std::size_t k = 0; k < weights.size(); ++k) g += weights[k] * weights[k] * basis.at(l - (finest + shift - double(k)));
        target.log2_frequency.push_back(l);
        target.variance_per_octave.push_back(g);
    }
    for (double w : weights) variance += w * w;  // basis variance 1
    const OctaveFit fit = fit_octaves(target, variance, basis, 1.0, finest, 4);
    ASSERT_EQ(fit.weight.size(), weights.size());
    EXPECT_NEAR(fit.log2_frequency[0], finest + shift, 1e-9);
    for (std::size_t k = 0; k < weights.size(); ++k) EXPECT_NEAR(fit.weight[k], weights[k], 0.02) << "octave " << k;
    EXPECT_LT(fit.rms_error_db, 0.1);
    double fitted = 0;
    for (double w : fit.weight) fitted += w * w;
    EXPECT_NEAR(fitted, variance, 1e-9) << "the variance is matched exactly";
}

TEST(OctaveSpectrum, WaveletChannelSpectrumHoldsTheChannelVariance)
{
    TextureDescription d;
    d.model = "wavelet";
    d.pixels_per_unit = 256;
    d.parameters = WaveletParameters{{std::vector<double>{0.1, 0.2, 0.3, 0.2, 0.1, 0.05},
                                   std::vector<double>(6, 0.1), std::vector<double>(6, 0.0)}};
    const OctaveSpectrum s = channel_spectrum(d, 0);
    const double sigma = channel_sigma(d, 0);
    // The bands' tails outside the measured range hold a few per cent.
    EXPECT_NEAR(s.variance(), sigma * sigma, 0.05 * sigma * sigma);
    // Band 2 (the strongest) sits at ppu·2^-2 lattice cells per unit, [1/4, 1/2) cycles per cell.
    double peak_l = 0, peak = 0;
    for (std::size_t i = 0; i < s.log2_frequency.size(); ++i)
        if (s.variance_per_octave[i] > peak) peak = s.variance_per_octave[i], peak_l = s.log2_frequency[i];
    EXPECT_GT(peak_l, std::log2(256.0 / 4) - 2.5);
    EXPECT_LT(peak_l, std::log2(256.0 / 4) - 0.5);
    EXPECT_THROW(channel_spectrum(d, 3), Error);
    d.model = "gabor";
    EXPECT_THROW(channel_spectrum(d, 0), Error);
}

TEST(ChannelMap, PolylineStaysWithinTolerance)
{
    TextureDescription d;
    d.model = "wavelet";
    d.parameters = WaveletParameters{{std::vector<double>{0.2, 0.1}, std::vector<double>{0.1, 0.1}, std::vector<double>{0.1, 0.0}}};
    // A skewed, monotone map on 10 knots (as analysis writes them).
    for (int k = 0; k < 10; ++k) {
        const double z = -3 + 6.0 * k / 9;
        d.histograms[0].z.push_back(z);
        d.histograms[0].value.push_back(0.05 * std::exp(0.6 * z));
    }
    const double tolerance = 1e-4;
    const auto line = channel_value_polyline(d, 0, -4, 4, tolerance, 256);
    ASSERT_GE(line.size(), 10u);
    EXPECT_EQ(line.front()[0], -4);
    EXPECT_EQ(line.back()[0], 4);
    for (double z = -4; z <= 4; z += 0.001) {
        std::size_t i = 1;
        while (i + 1 < line.size() && line[i][0] < z) ++i;
        const double s = (z - line[i - 1][0]) / (line[i][0] - line[i - 1][0]);
        const double interpolated = line[i - 1][1] + s * (line[i][1] - line[i - 1][1]);
        ASSERT_NEAR(interpolated, channel_value(d, 0, z), 1.01 * tolerance) << "z = " << z;
    }
    // A channel without a map is σ_M·z: one segment.
    const auto linear = channel_value_polyline(d, 1, -4, 4, tolerance, 256);
    ASSERT_EQ(linear.size(), 2u);
    EXPECT_NEAR(linear.back()[1], 4 * channel_sigma(d, 1), 1e-12);
    EXPECT_THROW(channel_value_polyline(d, 0, -4, 4, 1e-9, 8), Error) << "too many points must be an error";
}

TEST(NonnegativeLeastSquares, MatchesTheKuhnTuckerConditions)
{
    std::mt19937 random(5);
    std::normal_distribution<double> normal;
    for (int trial = 0; trial < 20; ++trial) {
        Eigen::MatrixXd a(30, 8);
        Eigen::VectorXd b(30);
        for (int i = 0; i < 30; ++i) {
            b[i] = normal(random);
            for (int j = 0; j < 8; ++j) a(i, j) = normal(random);
        }
        const Eigen::VectorXd x = nonnegative_least_squares(a, b);
        const Eigen::VectorXd gradient = a.transpose() * (a * x - b);
        for (int j = 0; j < 8; ++j) {
            EXPECT_GE(x[j], 0);
            if (x[j] > 0) EXPECT_NEAR(gradient[j], 0, 1e-9);  // free: stationary
            else EXPECT_GE(gradient[j], -1e-9);               // at the bound: cannot descend
        }
    }
}

}  // namespace
