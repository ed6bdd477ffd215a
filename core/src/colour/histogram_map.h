// Histogram matching for Gaussian noise models (paper 000, §5).
//
// A HistogramMap (texture_description.h) stores knots (z_k, Q(Φ(z_k))): the channel's inverse
// CDF composed with the normal CDF. Synthesis then maps the noise value z = m/σ_M directly,
// value = f(z), with no Φ evaluation, and f is nearly linear for near-Gaussian channels, so a
// monotone cubic with ~10 knots fits it better than it would fit Q(p) itself.
#pragma once

#include <stochtex/texture_description.h>

#include <functional>
#include <vector>

namespace stochtex {

/// Fritsch–Carlson monotone cubic Hermite interpolation, clamped to the end values.
class MonotoneCubic {
public:
    MonotoneCubic() = default;
    MonotoneCubic(std::vector<double> x, std::vector<double> y);

    double operator()(double t) const;
    /// out[i] = (*this)(t[i]) for i < count, bit-identical, vectorised (colour_mapping_batch.cpp).
    void eval(const double* t, double* out, std::size_t count) const;
    bool empty() const { return x_.empty(); }
    /// The Hermite tangents at the knots (after the Fritsch–Carlson limiter), for exporters.
    const std::vector<double>& slopes() const { return slope_; }

private:
    std::vector<double> x_, y_, slope_;
    // Evaluation form (a hot path of synthesis): per segment i, with s = (t − x_i)/h_i,
    // f = y_i + s·(c1 + s·(c2 + s·c3)); knots fitted by the analysis are uniform in z, so the
    // segment is found by one multiplication instead of a binary search.
    std::vector<double> inverse_width_, c1_, c2_, c3_;
    bool uniform_ = false;
    double inverse_step_ = 0;
};

/// The channel's value distribution summarised by a fine histogram, for Gaussianisation and
/// quantiles in O(pixels) (no sort: analysis must stay in the tens of milliseconds).
class EmpiricalDistribution {
public:
    explicit EmpiricalDistribution(const std::vector<float>& values, int bins = 4096);

    /// Q(p): the p-quantile, p in [0, 1].
    double quantile(double p) const;
    /// F(x): fraction of values ≤ x (linear within a bin).
    double cdf(double x) const;
    double mean() const { return mean_; }
    double stddev() const { return stddev_; }

private:
    double lo_, hi_, bin_width_;
    std::vector<double> cumulative_;  // cumulative_[i] = F(lo + i·bin_width)
    double mean_ = 0, stddev_ = 0;
};

/// Knots at z uniformly spaced in [−z_max, z_max] (symmetric, so mirroring a channel is exact).
HistogramMap fit_histogram_map(const EmpiricalDistribution& distribution, int knot_count, double z_max = 3.0);

/// Replaces each value by σ Φ⁻¹(F(value)): the same ranks, a Gaussian histogram (σ = stddev).
void gaussianize(std::vector<float>& values, const EmpiricalDistribution& distribution);

/// W1 between the channel and a model distribution given by its quantile function, divided by
/// the channel's stddev: how far "Gaussian" (or "the fitted map") is from the photo.
double relative_w1_to_model(const EmpiricalDistribution& distribution,
                            const std::function<double(double p)>& model_quantile);

/// The mirrored map of a negated channel: value'(z) = −value(−z).
HistogramMap mirrored(const HistogramMap& map);

}  // namespace stochtex
