// Unit tests of the numerical building blocks: normal distribution, Gauss–Hermite, monotone
// cubic, empirical distributions, band indexing and the PSD estimators.
#include "colour/gaussian.h"
#include "colour/histogram_map.h"
#include "spectra/band_power.h"

#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <cmath>
#include <random>

namespace stochtex {

TEST(Gaussian, InverseCdfInvertsCdf)
{
    for (double z = -7; z <= 5; z += 0.37)  // above 5, 1 − Φ(z) underflows double EXPECT_NEAR(inverse_normal_cdf(normal_cdf(z)), z, 1e-9 * (1 + std::abs(z)));
    EXPECT_NEAR(inverse_normal_cdf(0.975), 1.959963984540054, 1e-12);
}

TEST(Gaussian, HermiteRuleIntegratesMoments)
{
    const GaussHermite& rule = GaussHermite::standard_normal();
    double m0 = 0, m1 = 0, m2 = 0, m4 = 0, m8 = 0;
    for (int i = 0; i < GaussHermite::count; ++i) {
        const double z = rule.node[i], w = rule.weight[i];
        m0 += w, m1 += w * z, m2 += w * z * z, m4 += w * std::pow(z, 4), m8 += w * std::pow(z, 8);
    }
    EXPECT_NEAR(m0, 1, 1e-12);
    EXPECT_NEAR(m1, 0, 1e-12);
    EXPECT_NEAR(m2, 1, 1e-12);
    EXPECT_NEAR(m4, 3, 1e-10);
    EXPECT_NEAR(m8, 105, 1e-8);  // (8−1)!! — exact below degree 2·count
}

TEST(MonotoneCubic, InterpolatesKnotsStaysMonotoneAndClamps)
{
    // A staircase is the classic overshoot case for an unconstrained cubic.
    const MonotoneCubic f({0, 1, 2, 3, 4, 5}, {0, 0, 1, 1, 1, 3});
    for (double x : {0.0, 1.0, 2.0, 3.0, 4.0, 5.0}) EXPECT_DOUBLE_EQ(f(x), (x < 2 ? 0 : x < 5 ? 1 : 3));
    double previous = f(-1);
    for (double x = -1; x <= 6; x += 0.01) {
        const double value = f(x);
        EXPECT_GE(value, previous - 1e-12) << "at x = " << x;
        EXPECT_GE(value, 0);
        EXPECT_LE(value, 3);
        previous = value;
    }
    EXPECT_EQ(f(-10), 0);
    EXPECT_EQ(f(10), 3);
}

TEST(MonotoneCubic, BatchEvaluationIsBitIdenticalForEveryKnotCountAndInstructionSet)
{
    // eval() reads the knot arrays as register tables of 1 to 4 vectors (a count per vector
    // width) or by gathers beyond: every knot count from 2 to 40, uniform knots (the segment by
    // a product) and uneven ones (by counting), at the knots, between and outside them.
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    for (int knots = 2; knots <= 40; ++knots)
        for (const bool even : {true, false}) {
            std::vector<double> x(static_cast<std::size_t>(knots), 0.0), y(x);
            double position = -1.3, value = -2.0;
            for (int k = 0; k < knots; ++k) {
                x[std::size_t(k)] = even ? -1.3 + 0.37 * k : (position += 0.05 + uniform(rng));
                y[std::size_t(k)] = (value += uniform(rng) * (k % 3 == 0 ? 0.0 : 1.0));
            }
            const MonotoneCubic f(x, y);
            std::vector<double> t;
            for (const double knot : x) t.insert(t.end(), {knot, std::nextafter(knot, -1e9), std::nextafter(knot, 1e9)});
            for (int k = 0; k < 301; ++k) t.push_back(x.front() - 1 + (x.back() - x.front() + 2) * uniform(rng));
            std::vector<double> out(t.size());
            for (const std::int64_t target : hwy::SupportedAndGeneratedTargets()) {
                hwy::SetSupportedTargetsForTest(target);
                f.eval(t.data(), out.data(), t.size());
                for (std::size_t i = 0; i < t.size(); ++i)
                    ASSERT_EQ(out[i], f(t[i])) << knots << (even ? " even" : " uneven") << " knots, t = " << t[i]
                                               << ", " << hwy::TargetName(target);
            }
            hwy::SetSupportedTargetsForTest(0);
        }
}

TEST(EmpiricalDistribution, QuantilesAndGaussianisation)
{
    std::mt19937 rng(3);
    std::exponential_distribution<float> exponential(2.0f);
    std::vector<float> values(200000);
    for (float& v : values) v = exponential(rng);
    const EmpiricalDistribution distribution(values);
    EXPECT_NEAR(distribution.quantile(0.5), std::log(2.0) / 2, 0.01);
    EXPECT_NEAR(distribution.mean(), 0.5, 0.01);
    EXPECT_NEAR(distribution.cdf(distribution.quantile(0.9)), 0.9, 1e-3);

    gaussianize(values, distribution);
    const EmpiricalDistribution gaussian(values);
    EXPECT_NEAR(gaussian.mean(), 0, 0.01);
    EXPECT_NEAR(gaussian.stddev(), distribution.stddev(), 0.02 * distribution.stddev());
    EXPECT_NEAR(gaussian.quantile(normal_cdf(1)), distribution.stddev(), 0.03 * distribution.stddev());
}

TEST(HistogramMap, FitReproducesTheDistributionAndMirrors)
{
    std::mt19937 rng(5);
    std::gamma_distribution<float> gamma(2.0f, 1.0f);
    std::vector<float> values(200000);
    for (float& v : values) v = gamma(rng);
    const EmpiricalDistribution distribution(values);
    const HistogramMap map = fit_histogram_map(distribution, 10);
    const MonotoneCubic f(map.z, map.value);
    const double mapped = relative_w1_to_model(distribution, [&](double p) { return f(inverse_normal_cdf(p)); });
    const double gaussian = relative_w1_to_model(distribution, [&](double p) {
        return distribution.mean() + distribution.stddev() * inverse_normal_cdf(p);
    });
    EXPECT_LT(mapped, 0.02);
    EXPECT_GT(gaussian, 3 * mapped);

    const HistogramMap mirror = mirrored(map);
    const MonotoneCubic g(mirror.z, mirror.value);
    for (double z = -2.5; z <= 2.5; z += 0.1) EXPECT_NEAR(g(z), -f(-z), 1e-12);
}

TEST(BandPower, FrequencyToBandIsExactAtPowersOfTwo)
{
    EXPECT_EQ(band_of_frequency(0.5), -1);
    EXPECT_EQ(band_of_frequency(0.4999), 0);
    EXPECT_EQ(band_of_frequency(0.25), 0);
    EXPECT_EQ(band_of_frequency(0.2499), 1);
    EXPECT_EQ(band_of_frequency(1.0 / 512), 7);
    EXPECT_EQ(supported_band_count(512, 512), 8);  // paper: log2 N − 1
    EXPECT_EQ(supported_band_count(1024, 1024), 9);
    EXPECT_EQ(supported_band_count(512, 2048), 8);
    EXPECT_EQ(supported_band_count(600, 700), 8);
}

TEST(BandPower, ParsevalHoldsForAnySize)
{
    std::mt19937 rng(7);
    std::normal_distribution<float> normal(0.3f, 2.0f);
    for (auto [w, h] : {std::pair{128, 128}, std::pair{100, 160}, std::pair{97, 131}}) {
        std::vector<float> plane(std::size_t(w) * h);
        double sum = 0, sum_sq = 0;
        for (float& v : plane) v = normal(rng), sum += v, sum_sq += double(v) * v;
        const double variance = sum_sq / plane.size() - (sum / plane.size()) * (sum / plane.size());
        const std::vector<double> power =
            band_powers(plane, w, h, supported_band_count(w, h), PsdEstimator::periodic);
        double total = 0;
        for (double p : power) total += p;
        EXPECT_NEAR(total, variance, 1e-4 * variance) << w << "x" << h;
    }
}

TEST(BandPower, PeriodicSmoothRemovesTheEdgeLeakOfARamp)
{
    // A ramp is smooth inside but jumps where the periodic FFT wraps it: the raw periodogram
    // puts a "+" of power into the fine bands, the periodic + smooth decomposition does not.
    const int n = 128;
    std::vector<float> ramp(n * n);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) ramp[y * n + x] = float(x + 0.5 * y) / n;
    const auto periodic = band_powers(ramp, n, n, 6, PsdEstimator::periodic);
    const auto smooth = band_powers(ramp, n, n, 6, PsdEstimator::periodic_smooth);
    EXPECT_GT(periodic[0], 1e-5);
    EXPECT_LT(smooth[0], 1e-3 * periodic[0]);
    EXPECT_LT(smooth[1], 1e-3 * periodic[1]);
}

}  // namespace stochtex
