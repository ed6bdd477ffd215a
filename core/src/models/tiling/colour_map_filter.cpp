#include "models/tiling/colour_map_filter.h"

#include "models/tiling/colour_map_kernels.h"

#include <stochtex/error.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace stochtex {

namespace {

/// Uniform nodes on [−4, 4] standard deviations with normalised Gaussian weights: unlike
/// Gauss–Hermite nodes they can be spaced finely enough that a discontinuous map is not
/// sampled as a few isolated points.
struct LineQuadrature {
    std::vector<double> node, weight;
    explicit LineQuadrature(int count)
    {
        double total = 0;
        for (int k = 0; k < count; ++k) {
            const double t = count == 1 ? 0.0 : -4 + 8.0 * k / (count - 1);
            node.push_back(t);
            weight.push_back(std::exp(-0.5 * t * t));
            total += weight.back();
        }
        for (double& w : weight) w /= total;
    }
};

const LineQuadrature& line_quadrature(int count)
{
    static const std::vector<LineQuadrature> rules = [] {
        std::vector<LineQuadrature> r;
        for (int n = 0; n <= 64; ++n) r.emplace_back(std::max(1, n));
        return r;
    }();
    return rules[std::size_t(std::clamp(count, 1, 64))];
}

/// A Gaussian of σ texels sampled at `count` evenly spaced centres over an axis of n texels
/// (n a multiple of count), clamped to the edge; σ < 0 means the full average. The centres all
/// have the same fractional position, so one set of weights serves every output sample.
struct AxisBlur {
    int n = 0, count = 0, step = 0, first = 0;  // output s reads texels first + s·step + t
    bool average = false;
    std::vector<double> weight;

    AxisBlur(int texels, double sigma, int samples) : n(texels), count(samples), step(texels / samples)
    {
        if (sigma < 0) {
            average = true;
            return;
        }
        if (sigma == 0) {  // the raw map, always at full resolution
            weight = {1.0};
            return;
        }
        const double centre = 0.5 * step - 0.5;
        first = int(std::floor(centre - 4 * sigma));
        const int last = int(std::ceil(centre + 4 * sigma));
        double total = 0;
        for (int t = first; t <= last; ++t) {
            const double d = (t - centre) / sigma;
            weight.push_back(std::exp(-0.5 * d * d));
            total += weight.back();
        }
        for (double& w : weight) w /= total;
    }

    /// Blurs the line line[0], line[stride], … into out[0], out[out_stride], ….
    template <class Out>
    void apply(const double* line, std::size_t stride, Out* out, std::size_t out_stride) const
    {
        if (average) {
            double sum = 0;
            for (int t = 0; t < n; ++t) sum += line[std::size_t(t) * stride];
            out[0] = Out(sum / n);
            return;
        }
        for (int s = 0; s < count; ++s) {
            double sum = 0;
            const int start = first + s * step;
            for (std::size_t t = 0; t < weight.size(); ++t)
                sum += weight[t] * line[std::size_t(std::clamp(start + int(t), 0, n - 1)) * stride];
            out[std::size_t(s) * out_stride] = Out(sum);
        }
    }
};

}  // namespace

const char* to_string(ColourMapMethod method)
{
    switch (method) {
    case ColourMapMethod::reference: return "reference";
    case ColourMapMethod::interpolated: return "interpolated";
    case ColourMapMethod::covariance: return "covariance";
    }
    return "?";
}

ColourMapFilter::ColourMapFilter(const std::vector<float>& rgb, int size) : size_(size)
{
    if (size < 8 || (size & (size - 1)) || rgb.size() != std::size_t(size) * size * 3)
        throw Error("colour map: expected a square map whose side is a power of two ≥ 8");
    levels_ = int(std::lround(std::log2(size))) + 1;
    const int last = levels_ - 1;
    auto sigma_of = [&](int k) { return k == last ? -1.0 : k == 0 ? 0.0 : std::ldexp(1.0, k - 1); };
    // Two samples per σ are enough for a blurred map; the average needs one.
    auto resolution_of = [&](int k) { return k == last ? 1 : k <= 2 ? size : size >> (k - 2); };

    // Blur along a (x) first, per level, then along b (y) for every pair.
    std::vector<double> map(rgb.begin(), rgb.end());
    table_.resize(std::size_t(levels_) * levels_);
    std::vector<AxisBlur> blurs;
    for (int k = 0; k < levels_; ++k) blurs.emplace_back(size, sigma_of(k), resolution_of(k));
    for (int i = 0; i < levels_; ++i) {
        const int wa = resolution_of(i);
        std::vector<double> along_a(std::size_t(wa) * size * 3);
        for (int y = 0; y < size; ++y)
            for (int c = 0; c < 3; ++c)
                blurs[i].apply(&map[std::size_t(y) * size * 3 + c], 3, &along_a[std::size_t(y) * wa * 3 + c], 3);
        for (int j = 0; j < levels_; ++j) {
            Blurred& blurred = table_[std::size_t(i) * levels_ + j];
            blurred.width = wa, blurred.height = resolution_of(j);
            // One float more: lookup() reads each texel as four floats (the last one's 4th is this).
            blurred.rgb.resize(std::size_t(wa) * blurred.height * 3 + 1);
            for (int x = 0; x < wa; ++x)
                for (int c = 0; c < 3; ++c)
                    blurs[j].apply(&along_a[std::size_t(x) * 3 + c], std::size_t(wa) * 3, &blurred.rgb[std::size_t(x) * 3 + c],
                                   std::size_t(wa) * 3);
        }
    }
}

Rgb ColourMapFilter::fetch(int level_a, int level_b, double a, double b) const
{
    const Blurred& m = table_[std::size_t(level_a) * levels_ + level_b];
    const double x = std::clamp(a * m.width - 0.5, 0.0, double(m.width - 1));
    const double y = std::clamp(b * m.height - 0.5, 0.0, double(m.height - 1));
    const int x0 = std::min(int(x), std::max(0, m.width - 2)), y0 = std::min(int(y), std::max(0, m.height - 2));
    const int x1 = std::min(x0 + 1, m.width - 1), y1 = std::min(y0 + 1, m.height - 1);
    const double fx = x - x0, fy = y - y0;
    Rgb out;
    for (int c = 0; c < 3; ++c) {
        auto at = [&](int xi, int yi) { return double(m.rgb[(std::size_t(yi) * m.width + xi) * 3 + c]); };
        out[c] = float((at(x0, y0) * (1 - fx) + at(x1, y0) * fx) * (1 - fy) + (at(x0, y1) * (1 - fx) + at(x1, y1) * fx) * fy);
    }
    return out;
}

double ColourMapFilter::fractional_level(double sigma) const
{
    // σ_k = 2^(k−1) texels: level 1 + log2 σ; below one texel, linear towards the raw map;
    // beyond the last finite blur, towards the average (reached at σ = half the map).
    if (!(sigma > 0)) return 0;
    if (sigma < 1) return sigma;
    return std::min(double(levels_ - 1), 1 + std::log2(sigma));
}

Rgb ColourMapFilter::fetch_fractional(double level_a, double level_b, double a, double b) const
{
    return Fractional(*this, level_a, level_b).fetch(a, b);
}

ColourMapFilter::Fractional::Fractional(const ColourMapFilter& filter, double level_a, double level_b) : filter_(filter)
{
    // The four (floor, ceil) level pairs and the blend weights, once for all the fetches at
    // these levels (the covariance method's nodes share them).
    ia_ = std::min(int(level_a), filter.levels_ - 1), ib_ = std::min(int(level_b), filter.levels_ - 1);
    ta_ = level_a - ia_, tb_ = level_b - ib_;
    ja_ = std::min(ia_ + 1, filter.levels_ - 1), jb_ = std::min(ib_ + 1, filter.levels_ - 1);
}

Rgb ColourMapFilter::Fractional::fetch(double a, double b) const
{
    const Rgb c00 = filter_.fetch(ia_, ib_, a, b);
    if (ta_ == 0 && tb_ == 0) return c00;
    // A corner whose weight is 0 adds c·0 = +0 (the map's values are ≥ 0): any value will do,
    // so it is not fetched.
    const Rgb c10 = ta_ == 0 ? c00 : filter_.fetch(ja_, ib_, a, b);
    const Rgb c01 = tb_ == 0 ? c00 : filter_.fetch(ia_, jb_, a, b);
    const Rgb c11 = ta_ == 0 ? c01 : tb_ == 0 ? c10 : filter_.fetch(ja_, jb_, a, b);
    Rgb out;
    for (int c = 0; c < 3; ++c)
        out[c] = float((c00[c] * (1 - ta_) + c10[c] * ta_) * (1 - tb_) + (c01[c] * (1 - ta_) + c11[c] * ta_) * tb_);
    return out;
}

ColourMapFilter::Line ColourMapFilter::line(double mean_a, double mean_b, const PairCovariance& covariance,
                                            ColourMapMethod method) const
{
    Line line;
    line.a = std::clamp(mean_a, 0.0, 1.0), line.b = std::clamp(mean_b, 0.0, 1.0);
    // Texel units: the map spans [0, 1] with size_ texels per axis.
    const double n2 = double(size_) * size_;
    const double var_a = std::max(0.0, covariance.aa) * n2, var_b = std::max(0.0, covariance.bb) * n2;
    double cov = covariance.ab * n2;
    const double bound = std::sqrt(var_a * var_b);
    if (method == ColourMapMethod::interpolated || !(std::abs(cov) > 1e-3 * bound)) {
        line.level_a = fractional_level(std::sqrt(var_a)), line.level_b = fractional_level(std::sqrt(var_b));
        return line;
    }
    // Σ = diag(d) + u uᵀ: u = (α, ±β) with αβ = |cov| and α/β = sqrt(var_a / var_b) leaves
    // d = (var_a − α², var_b − β²) ≥ 0 (zero for a perfect correlation).
    cov = std::clamp(cov, -bound, bound);
    line.alpha = std::sqrt(std::abs(cov) * std::sqrt(var_a / var_b));
    line.beta = std::sqrt(std::abs(cov) * std::sqrt(var_b / var_a)) * (cov < 0 ? -1 : 1);
    // d from the moments directly (α² = |cov|·√(var_a/var_b)), not from α squared: a perfect
    // correlation (var_a = var_b = |cov|, a colour map indexed by one noise twice) then gives
    // d = 0 exactly, one table, where √(x)² − x left d ~ 1e-16 var — a blur level of ~1e-8,
    // which costs four tables per node for a weight that rounds away.
    const double d_a = std::max(0.0, var_a - std::abs(cov) * std::sqrt(var_a / var_b));
    const double d_b = std::max(0.0, var_b - std::abs(cov) * std::sqrt(var_b / var_a));
    line.level_a = fractional_level(std::sqrt(d_a)), line.level_b = fractional_level(std::sqrt(d_b));
    // Nodes along u no farther apart than about a texel or the blur already there.
    const double length = std::hypot(line.alpha, line.beta);
    const double spacing = std::max(1.0, std::sqrt(std::min(d_a, d_b)));
    line.count = std::clamp(int(std::ceil(8 * length / spacing)) | 1, 3, 63);
    return line;
}

Rgb ColourMapFilter::filtered(double mean_a, double mean_b, const PairCovariance& covariance, ColourMapMethod method) const
{
    if (method == ColourMapMethod::reference) {
        const double a = std::clamp(mean_a, 0.0, 1.0), b = std::clamp(mean_b, 0.0, 1.0);
        const double n2 = double(size_) * size_;
        auto level = [&](double variance) {
            return std::min(levels_ - 1, int(std::lround(std::log2(1 + std::sqrt(std::max(0.0, variance) * n2)))));
        };
        return fetch(level(covariance.aa), level(covariance.bb), a, b);
    }
    const Line l = line(mean_a, mean_b, covariance, method);
    if (l.alpha == 0 && l.beta == 0) return fetch_fractional(l.level_a, l.level_b, l.a, l.b);
    const LineQuadrature& rule = line_quadrature(l.count);
    const Fractional levels(*this, l.level_a, l.level_b);
    double sum[3] = {0, 0, 0};
    for (int k = 0; k < l.count; ++k) {
        const double t = rule.node[k];
        const Rgb c = levels.fetch(std::clamp(l.a + t * l.alpha / size_, 0.0, 1.0), std::clamp(l.b + t * l.beta / size_, 0.0, 1.0));
        for (int ch = 0; ch < 3; ++ch) sum[ch] += rule.weight[k] * c[ch];
    }
    return {float(sum[0]), float(sum[1]), float(sum[2])};
}

namespace {
/// An RGB texel and its neighbour's R as one vector (lane 3 unused): one load, lane-wise maths.
typedef float Colour4 __attribute__((vector_size(4 * sizeof(float))));

inline Colour4 load_rgb(const float* p)
{
    Colour4 c;
    std::memcpy(&c, p, sizeof c);
    return c;
}

inline Colour4 splat4(float v) { return Colour4{v, v, v, v}; }
}  // namespace

class ColourMapFilter::Packed {
public:
    Packed(const ColourMapFilter& filter, double level_a, double level_b)
    {
        // Fractional's four (floor, ceil) level pairs, the zero-weight ones dropped.
        const int ia = std::min(int(level_a), filter.levels_ - 1), ib = std::min(int(level_b), filter.levels_ - 1);
        const double ta = level_a - ia, tb = level_b - ib;
        const int ja = std::min(ia + 1, filter.levels_ - 1), jb = std::min(ib + 1, filter.levels_ - 1);
        add(filter, ia, ib, (1 - ta) * (1 - tb));
        if (ta != 0) add(filter, ja, ib, ta * (1 - tb));
        if (tb != 0) add(filter, ia, jb, (1 - ta) * tb);
        if (ta != 0 && tb != 0) add(filter, ja, jb, ta * tb);
    }

    Colour4 fetch(double a, double b) const
    {
        Colour4 out{};
        for (int k = 0; k < count_; ++k) {
            const Table& m = tables_[std::size_t(k)];
            // ColourMapFilter::fetch's clamped texel coordinates.
            const double x = std::clamp(a * m.width - 0.5, 0.0, double(m.width - 1));
            const double y = std::clamp(b * m.height - 0.5, 0.0, double(m.height - 1));
            const int x0 = std::min(int(x), m.last_x0), y0 = std::min(int(y), m.last_y0);
            const int x1 = std::min(x0 + 1, m.width - 1), y1 = std::min(y0 + 1, m.height - 1);
            const float fx = float(x - x0), fy = float(y - y0);
            const float* r0 = m.rgb + std::size_t(y0) * m.stride, * r1 = m.rgb + std::size_t(y1) * m.stride;
            const Colour4 gx = splat4(fx), hx = splat4(1 - fx);
            const Colour4 low = hx * load_rgb(r0 + 3 * x0) + gx * load_rgb(r0 + 3 * x1);
            const Colour4 high = hx * load_rgb(r1 + 3 * x0) + gx * load_rgb(r1 + 3 * x1);
            out += m.weight * (splat4(1 - fy) * low + splat4(fy) * high);
        }
        return out;
    }

    /// The tables for the vectorised line quadrature (colour_map_kernels.h).
    int kernel_tables(colour_map_kernels::Table* out) const
    {
        for (int k = 0; k < count_; ++k) {
            const Table& m = tables_[std::size_t(k)];
            out[k] = {m.rgb, m.stride, m.width, m.height, m.last_x0, m.last_y0, m.weight[0]};
        }
        return count_;
    }

private:
    struct Table {
        const float* rgb;
        std::size_t stride;  // floats per row
        int width, height, last_x0, last_y0;
        Colour4 weight;
    };
    void add(const ColourMapFilter& filter, int level_a, int level_b, double weight)
    {
        const Blurred& m = filter.table_[std::size_t(level_a) * filter.levels_ + level_b];
        tables_[std::size_t(count_++)] = {m.rgb.data(), std::size_t(m.width) * 3, m.width, m.height, std::max(0, m.width - 2),
                                          std::max(0, m.height - 2), splat4(float(weight))};
    }
    std::array<Table, 4> tables_{};
    int count_ = 0;
};

Rgb ColourMapFilter::lookup(double mean_a, double mean_b, const PairCovariance& covariance, ColourMapMethod method) const
{
    if (method == ColourMapMethod::reference) return filtered(mean_a, mean_b, covariance, method);
    const Line l = line(mean_a, mean_b, covariance, method);
    const Packed levels(*this, l.level_a, l.level_b);
    if (l.alpha == 0 && l.beta == 0) {
        const Colour4 c = levels.fetch(l.a, l.b);
        return {c[0], c[1], c[2]};
    }
    // Σ_k float(w_k) · fetch(a + t_k α, b + t_k β), the nodes' fetches vectorised across the
    // nodes and summed in node order (colour_map_kernels.h: Packed::fetch's operations).
    const LineQuadrature& rule = line_quadrature(l.count);
    colour_map_kernels::Table tables[4];
    colour_map_kernels::LineNodes nodes{};
    nodes.tables = tables, nodes.table_count = levels.kernel_tables(tables);
    nodes.a = l.a, nodes.b = l.b, nodes.step_a = l.alpha / size_, nodes.step_b = l.beta / size_;
    nodes.node = rule.node.data(), nodes.weight = rule.weight.data(), nodes.count = l.count;
    float sum[3];
    colour_map_kernels::line_sum(nodes, sum);
    return {sum[0], sum[1], sum[2]};
}

Rgb ColourMapFilter::expected(double mean_a, double mean_b, const PairCovariance& covariance) const
{
    // N = μ + L z, L the Cholesky factor; z on a fine uniform grid with Gaussian weights.
    const double l11 = std::sqrt(std::max(0.0, covariance.aa));
    const double l21 = l11 > 0 ? covariance.ab / l11 : 0.0;
    const double l22 = std::sqrt(std::max(0.0, covariance.bb - l21 * l21));
    const int count = 64;
    const LineQuadrature& rule = line_quadrature(count);
    double sum[3] = {0, 0, 0};
    for (int i = 0; i < count; ++i)
        for (int j = 0; j < count; ++j) {
            const double z1 = rule.node[i], z2 = rule.node[j];
            const Rgb c = point(std::clamp(mean_a + l11 * z1, 0.0, 1.0), std::clamp(mean_b + l21 * z1 + l22 * z2, 0.0, 1.0));
            for (int ch = 0; ch < 3; ++ch) sum[ch] += rule.weight[i] * rule.weight[j] * c[ch];
        }
    return {float(sum[0]), float(sum[1]), float(sum[2])};
}

}  // namespace stochtex
