#include "colour/histogram_map.h"

#include "colour/gaussian.h"

#include <stochtex/error.h>

#include <algorithm>
#include <cmath>

namespace stochtex {

MonotoneCubic::MonotoneCubic(std::vector<double> x, std::vector<double> y) : x_(std::move(x)), y_(std::move(y))
{
    const std::size_t n = x_.size();
    if (n < 2 || y_.size() != n) throw Error("monotone cubic: need at least two knots of equal count");
    std::vector<double> secant(n - 1);
    for (std::size_t i = 0; i + 1 < n; ++i) secant[i] = (y_[i + 1] - y_[i]) / (x_[i + 1] - x_[i]);
    slope_.resize(n);
    slope_[0] = secant[0];
    slope_[n - 1] = secant[n - 2];
    for (std::size_t i = 1; i + 1 < n; ++i)
        slope_[i] = secant[i - 1] * secant[i] <= 0 ? 0.0 : 0.5 * (secant[i - 1] + secant[i]);
    // Fritsch–Carlson: limit the tangents so that each cubic segment stays monotone.
    for (std::size_t i = 0; i + 1 < n; ++i) {
        if (secant[i] == 0) {
            slope_[i] = slope_[i + 1] = 0;
            continue;
        }
        const double alpha = slope_[i] / secant[i], beta = slope_[i + 1] / secant[i];
        const double radius = alpha * alpha + beta * beta;
        if (radius > 9) {
            const double tau = 3 / std::sqrt(radius);
            slope_[i] = tau * alpha * secant[i];
            slope_[i + 1] = tau * beta * secant[i];
        }
    }
    // The cubic Hermite segment in monomial form (same function; Horner's rule to evaluate).
    inverse_width_.resize(n - 1), c1_.resize(n - 1), c2_.resize(n - 1), c3_.resize(n - 1);
    for (std::size_t i = 0; i + 1 < n; ++i) {
        const double h = x_[i + 1] - x_[i], rise = y_[i + 1] - y_[i];
        inverse_width_[i] = 1 / h;
        c1_[i] = h * slope_[i];
        c2_[i] = 3 * rise - 2 * h * slope_[i] - h * slope_[i + 1];
        c3_[i] = -2 * rise + h * slope_[i] + h * slope_[i + 1];
    }
    const double step = (x_.back() - x_.front()) / double(n - 1);
    uniform_ = true;
    for (std::size_t i = 0; i < n && uniform_; ++i)
        uniform_ = std::fabs(x_[i] - (x_.front() + double(i) * step)) <= 1e-9 * step;
    inverse_step_ = 1 / step;
}

double MonotoneCubic::operator()(double t) const
{
    if (t <= x_.front()) return y_.front();
    if (t >= x_.back()) return y_.back();
    std::size_t i = uniform_ ? std::size_t((t - x_.front()) * inverse_step_)
                             : std::size_t(std::upper_bound(x_.begin(), x_.end(), t) - x_.begin()) - 1;
    // Rounding at a knot may pick the neighbouring segment: step back into the right one.
    if (i > x_.size() - 2) i = x_.size() - 2;
    if (t < x_[i]) --i;
    else if (t >= x_[i + 1] && i + 2 < x_.size()) ++i;
    const double s = (t - x_[i]) * inverse_width_[i];
    return y_[i] + s * (c1_[i] + s * (c2_[i] + s * c3_[i]));
}

EmpiricalDistribution::EmpiricalDistribution(const std::vector<float>& values, int bins)
{
    if (values.empty()) throw Error("empirical distribution of an empty channel");
    const auto [min_it, max_it] = std::minmax_element(values.begin(), values.end());
    lo_ = *min_it;
    hi_ = *max_it;
    if (hi_ <= lo_) hi_ = lo_ + 1e-12;  // constant channel: a degenerate but valid distribution
    bin_width_ = (hi_ - lo_) / bins;
    std::vector<double> counts(bins, 0.0);
    double sum = 0, sum_sq = 0;
    for (float v : values) {
        const int bin = std::min(bins - 1, int((v - lo_) / bin_width_));
        counts[bin] += 1;
        sum += v;
        sum_sq += double(v) * v;
    }
    const double n = double(values.size());
    mean_ = sum / n;
    stddev_ = std::sqrt(std::max(0.0, sum_sq / n - mean_ * mean_));
    cumulative_.assign(bins + 1, 0.0);
    for (int i = 0; i < bins; ++i) cumulative_[i + 1] = cumulative_[i] + counts[i] / n;
}

double EmpiricalDistribution::cdf(double x) const
{
    const double position = (x - lo_) / bin_width_;
    if (position <= 0) return 0;
    const int bins = int(cumulative_.size()) - 1;
    if (position >= bins) return 1;
    const int i = int(position);
    return cumulative_[i] + (position - i) * (cumulative_[i + 1] - cumulative_[i]);
}

double EmpiricalDistribution::quantile(double p) const
{
    p = std::clamp(p, 0.0, 1.0);
    // First edge whose cumulative fraction reaches p, then invert the linear piece inside it.
    const auto it = std::lower_bound(cumulative_.begin(), cumulative_.end(), p);
    if (it == cumulative_.begin()) return lo_;
    if (it == cumulative_.end()) return hi_;
    const std::size_t i = std::size_t(it - cumulative_.begin()) - 1;
    const double mass = cumulative_[i + 1] - cumulative_[i];
    const double fraction = mass > 0 ? (p - cumulative_[i]) / mass : 0.0;
    return lo_ + (double(i) + fraction) * bin_width_;
}

HistogramMap fit_histogram_map(const EmpiricalDistribution& distribution, int knot_count, double z_max)
{
    if (knot_count < 4) throw Error("histogram map needs at least 4 knots, got " + std::to_string(knot_count));
    HistogramMap map;
    for (int k = 0; k < knot_count; ++k) {
        const double z = -z_max + 2 * z_max * k / (knot_count - 1);
        map.z.push_back(z);
        map.value.push_back(distribution.quantile(normal_cdf(z)));
    }
    // Quantiles of a histogram are non-decreasing already; enforce it against rounding.
    for (std::size_t k = 1; k < map.value.size(); ++k) map.value[k] = std::max(map.value[k], map.value[k - 1]);
    return map;
}

void gaussianize(std::vector<float>& values, const EmpiricalDistribution& distribution)
{
    // Tabulate x → σ Φ⁻¹(F(x)) on a fine grid once: O(pixels) instead of one Φ⁻¹ per pixel.
    constexpr int table_size = 4096;
    const double sigma = distribution.stddev();
    const double lo = distribution.quantile(0), hi = distribution.quantile(1);
    const double step = (hi - lo) / table_size;
    if (!(step > 0)) {
        std::fill(values.begin(), values.end(), 0.0f);
        return;
    }
    std::vector<double> table(table_size + 1);
    for (int i = 0; i <= table_size; ++i) {
        // Mid-rank convention keeps the extreme values finite: F is pulled inside (0, 1).
        const double p = std::clamp(distribution.cdf(lo + i * step), 0.5e-6, 1 - 0.5e-6);
        table[i] = sigma * inverse_normal_cdf(p);
    }
    for (float& v : values) {
        const double position = std::clamp((v - lo) / step, 0.0, double(table_size));
        const int i = std::min(table_size - 1, int(position));
        v = float(table[i] + (position - i) * (table[i + 1] - table[i]));
    }
}

double relative_w1_to_model(const EmpiricalDistribution& distribution,
                            const std::function<double(double p)>& model_quantile)
{
    // W1 = ∫₀¹ |Q_data(p) − Q_model(p)| dp, midpoint rule on a fine grid.
    constexpr int steps = 2000;
    double sum = 0;
    for (int i = 0; i < steps; ++i) {
        const double p = (i + 0.5) / steps;
        sum += std::abs(distribution.quantile(p) - model_quantile(p));
    }
    const double sigma = distribution.stddev();
    return sigma > 0 ? sum / steps / sigma : 0.0;
}

HistogramMap mirrored(const HistogramMap& map)
{
    HistogramMap result = map;
    const std::size_t n = map.value.size();
    for (std::size_t k = 0; k < n; ++k) result.value[k] = -map.value[n - 1 - k];
    return result;
}

}  // namespace stochtex
