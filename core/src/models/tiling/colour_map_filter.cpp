#include "models/tiling/colour_map_filter.h"

#include "colour/gaussian.h"
#include "models/tiling/colour_map_diagonal_blur.h"
#include "models/tiling/colour_map_kernels.h"

#include <stochtex/error.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace stochtex {

namespace {

/// A quadrature rule for E[f(t)], t ~ 𝒩(0, 1): nodes t_k and weights w_k summing to 1, stored
/// with colour_map_kernels::node_padding entries more (the last node, weight 0) so that the line
/// kernel reads whole vectors of them, and in single precision for the kernel.
struct LineRule {
    std::vector<double> node, weight;
    std::vector<float> node_float, weight_float;  // the kernel's copies
    int count = 0;
    void pad()
    {
        count = int(node.size());
        node.resize(node.size() + colour_map_kernels::node_padding, node.back());
        weight.resize(weight.size() + colour_map_kernels::node_padding, 0.0);
        node_float.assign(node.begin(), node.end());
        weight_float.assign(weight.begin(), weight.end());
    }
};

/// Uniform nodes on [−4, 4] standard deviations with normalised Gaussian weights: unlike
/// Gauss–Hermite nodes they can be spaced finely enough that a discontinuous map is not
/// sampled as a few isolated points.
LineRule uniform_rule(int count)
{
    LineRule rule;
    double total = 0;
    for (int k = 0; k < count; ++k) {
        const double t = count == 1 ? 0.0 : -4 + 8.0 * k / (count - 1);
        rule.node.push_back(t);
        rule.weight.push_back(std::exp(-0.5 * t * t));
        total += rule.weight.back();
    }
    for (double& w : rule.weight) w /= total;
    rule.pad();
    return rule;
}

/// n nodes of weight 1/n, node k the mean of the standard normal over its k-th n-quantile
/// interval (so the rule's mean is exactly 0), then scaled to unit variance. A step of the map
/// along the line then moves the sum by at most 1/n of the jump wherever it falls; uniform nodes
/// over ±4σ give the nodes near the mean a weight of ~3.2/(n − 1), so they need ~3.2× as many
/// nodes for the same bound.
LineRule equal_weight_rule(int count)
{
    auto quantile = [](double p) {  // Φ⁻¹(p) by bisection (set-up only)
        double lo = -12, hi = 12;
        for (int i = 0; i < 200; ++i) {
            const double mid = 0.5 * (lo + hi);
            (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p ? lo : hi) = mid;
        }
        return 0.5 * (lo + hi);
    };
    auto density = [](double t) { return std::isinf(t) ? 0.0 : std::exp(-0.5 * t * t) / std::sqrt(2 * M_PI); };
    LineRule rule;
    double second = 0;
    for (int k = 0; k < count; ++k) {
        const double lo = k == 0 ? -INFINITY : quantile(double(k) / count);
        const double hi = k == count - 1 ? INFINITY : quantile(double(k + 1) / count);
        rule.node.push_back(count * (density(lo) - density(hi)));
        second += rule.node.back() * rule.node.back() / count;
    }
    for (double& t : rule.node) t /= std::sqrt(second);
    rule.weight.assign(std::size_t(count), 1.0 / count);
    rule.pad();
    return rule;
}

/// Gauss–Hermite (colour/gaussian.h) with 3, 5 or 7 nodes: exact for polynomials up to degree
/// 2n − 1. Used where the uniform rule would have that few nodes — a line shorter than about
/// the blur the table already has along it, so the integrand is smooth on the line's scale —
/// where uniform nodes over ±4σ would all but miss the line's variance (3 nodes: ±4σ, weight
/// e⁻⁸ each).
LineRule gauss_hermite_rule(int count)
{
    const SmallGaussHermite& gauss_hermite = SmallGaussHermite::standard_normal(count);
    LineRule rule;
    rule.node = gauss_hermite.node;
    rule.weight = gauss_hermite.weight;
    rule.pad();
    return rule;
}

/// The line's rule for `count` nodes spaced finely enough: Gauss–Hermite below 9, uniform from 9.
const LineRule& line_rule(int count)
{
    static const std::vector<LineRule> rules = [] {
        std::vector<LineRule> r;
        for (int n = 0; n <= colour_map_kernels::max_nodes; ++n) r.push_back(n < 9 ? gauss_hermite_rule(n) : uniform_rule(n));
        return r;
    }();
    return rules[std::size_t(std::clamp(count, 1, colour_map_kernels::max_nodes))];
}

/// The line's nodes: uniform ones no farther apart than `spacing_blurs` × the blur the table
/// already has along the line (at least a texel: the raw map is bilinear), up to
/// `equal_weight_nodes`; a line that would need more takes that many equal-weight nodes. 31:
/// with 21 a perfectly correlated lookup was 0.1 µs instead of 0.12, but its error against
/// E[S(N)] rose above the 63 uniform nodes' (rgb map 9.5 → 12.4 ×10⁻³; with 31: 6.2).
constexpr double spacing_blurs = 2;
constexpr int equal_weight_nodes = 31;

const LineRule& equal_weight_line_rule()
{
    static const LineRule rule = equal_weight_rule(equal_weight_nodes);
    return rule;
}

/// The rule of a line of squared length `length2` (texels²) on a table blurred by `blur2`
/// (texels²) along it: nodes up to spacing_blurs blurs (or a texel) apart; beyond
/// equal_weight_nodes, a table blurred by a texel or more (the integrand smooth at the nodes'
/// spacing, where uniform nodes integrate better than equal weights' sparse tails) keeps up to
/// 63 uniform ones, as before the equal-weight rule; a sharper one takes that rule.
const LineRule& line_rule_for(double length2, double blur2)
{
    const double nodes2 = 64 * length2 / std::max(1.0, spacing_blurs * spacing_blurs * blur2);
    return nodes2 <= double(equal_weight_nodes * equal_weight_nodes) || blur2 >= 1
               ? line_rule(std::min(63, std::max(3, int(std::ceil(std::sqrt(nodes2))) | 1)))
               : equal_weight_line_rule();
}

/// How far (texels², the larger of |var_a − |cov|| and |var_b − |cov||) a covariance may be
/// from a line along a diagonal and still read the diagonal tables: 1 at the line, falling
/// linearly to 0 here, the axis-aligned reading taking the rest. Within the zone the diagonal
/// reading ignores an axis-aligned blur of at most a tenth of a texel; outside it nothing
/// changes. The blend keeps the lookup continuous in Σ.
constexpr double diagonal_zone = 0.01;

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
    return fetch(table_[std::size_t(level_a) * levels_ + level_b], a, b);
}

Rgb ColourMapFilter::fetch(const Blurred& m, double a, double b)
{
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

double ColourMapFilter::fractional_level(double variance) const
{
    // σ_k = 2^(k−1) texels: level 1 + log2 σ = 1 + ½ log2 σ²; below one texel, linear in σ
    // towards the raw map; beyond the last finite blur, towards the average (reached at σ =
    // half the map).
    if (!(variance > 0)) return 0;
    if (variance < 1) return std::sqrt(variance);
    return std::min(double(levels_ - 1), 1 + 0.5 * std::log2(variance));
}

ColourMapFilter::LevelBlend ColourMapFilter::level_blend(double level_a, double level_b) const
{
    // From the (floor, floor) corner to the (ceil, ceil) one through the corner on the side of
    // the larger fraction: weights 1 − max t, |t_a − t_b|, min t.
    LevelBlend blend;
    const int ia = std::min(int(level_a), levels_ - 1), ib = std::min(int(level_b), levels_ - 1);
    const double ta = level_a - ia, tb = level_b - ib;
    const int ja = std::min(ia + 1, levels_ - 1), jb = std::min(ib + 1, levels_ - 1);
    auto add = [&](int la, int lb, double w) {
        if (w == 0 && blend.count > 0) return;  // adds c·0 = +0 (the map's values are ≥ 0)
        blend.level_a[std::size_t(blend.count)] = la, blend.level_b[std::size_t(blend.count)] = lb;
        blend.weight[std::size_t(blend.count++)] = w;
    };
    add(ia, ib, 1 - std::max(ta, tb));
    if (ta >= tb) add(ja, ib, ta - tb);
    else add(ia, jb, tb - ta);
    add(ja, jb, std::min(ta, tb));
    return blend;
}

Rgb ColourMapFilter::fetch_fractional(double level_a, double level_b, double a, double b) const
{
    return Fractional(*this, level_a, level_b).fetch(a, b);
}

Rgb ColourMapFilter::Fractional::fetch(double a, double b) const
{
    double sum[3] = {0, 0, 0};
    for (int k = 0; k < blend_.count; ++k) {
        const Rgb c = filter_.fetch(blend_.level_a[std::size_t(k)], blend_.level_b[std::size_t(k)], a, b);
        for (int ch = 0; ch < 3; ++ch) sum[ch] += blend_.weight[std::size_t(k)] * c[ch];
    }
    return {float(sum[0]), float(sum[1]), float(sum[2])};
}

ColourMapFilter::Line ColourMapFilter::line(double mean_a, double mean_b, const PairCovariance& covariance,
                                            ColourMapMethod method) const
{
    Line line;
    line.a = std::clamp(mean_a, 0.0, 1.0), line.b = std::clamp(mean_b, 0.0, 1.0);
    // Texel units: the map spans [0, 1] with size_ texels per axis.
    const double n2 = double(size_) * size_;
    const double var_a = std::max(0.0, covariance.aa) * n2, var_b = std::max(0.0, covariance.bb) * n2;
    const double cov = covariance.ab * n2;
    // |cov| > 1e-3 √(var_a var_b), squared (no square root on the way in).
    if (method == ColourMapMethod::interpolated || !(cov * cov > 1e-6 * (var_a * var_b))) {
        line.level_a = fractional_level(var_a), line.level_b = fractional_level(var_b);
        return line;
    }
    auto nodes = [](const LineRule& rule, double alpha, double beta) {
        Nodes n;
        n.alpha = alpha, n.beta = beta;
        n.node = rule.node.data(), n.weight = rule.weight.data(), n.count = rule.count;
        n.node_float = rule.node_float.data(), n.weight_float = rule.weight_float.data();
        return n;
    };
    // Σ = diag(var_a − |cov|, var_b − |cov|) + |cov| (1, ±1)(1, ±1)ᵀ: near a diagonal line the
    // diagonal tables take it, at the level of the largest blur σ_k² ≤ |cov| (per axis), the
    // rest |cov| − σ_k² by nodes along the diagonal (of length² 2 · rest, the table's blur along
    // it 2 σ_k²: a few Gauss–Hermite nodes, at most 17 past the last level).
    const double along = std::abs(cov);
    const double rest = std::max(std::abs(var_a - along), std::abs(var_b - along));
    if (rest < diagonal_zone) {
        line.diagonal_weight = 1 - rest / diagonal_zone;
        int level = 0;
        double next = 1;  // σ²_(level+1) = 4^level
        while (level < diagonal_levels() && next <= along) ++level, next *= 4;
        const double blur2 = level == 0 ? 0.0 : 0.25 * next;
        const int sign = cov < 0 ? -1 : 1;
        // line_rule_for(2 (|cov| − σ_k²), 2 σ_k²) without its division and root (the
        // smallest odd count n ≥ 3 with n² ≥ nodes²; never the equal-weight rule: on the raw
        // map the rest is under a texel², under 128 nodes²).
        const double rest2 = along - blur2, scale = std::max(1.0, spacing_blurs * spacing_blurs * 2 * blur2);
        int count = 3;
        while (count < 63 && double(count * count) * scale < 64 * 2 * rest2) count += 2;
        const double step = std::sqrt(rest2);
        line.diagonal = &diagonal_table(sign, level);
        line.diagonal_nodes = nodes(line_rule(count), step, sign * step);
        if (rest == 0) return line;  // the axis-aligned reading is not needed
    }
    // Σ = diag(d) + u uᵀ: u = (α, ±β) with αβ = |cov| and α/β = r = sqrt(var_a / var_b) leaves
    // d = (var_a − α², var_b − β²) ≥ 0 (zero for a perfect correlation).
    const double magnitude = std::min(std::abs(cov), std::sqrt(var_a * var_b));
    const double r = std::sqrt(var_a / var_b);
    const double alpha2 = magnitude * r, beta2 = magnitude / r;
    const double alpha = std::sqrt(alpha2), beta = std::sqrt(beta2) * (cov < 0 ? -1 : 1);
    // d from the moments directly, not from α squared: a perfect correlation (var_a = var_b =
    // |cov|, a colour map indexed by one noise twice) then gives r = 1 and d = 0 exactly, one
    // table, where √(x)² − x left d ~ 1e-16 var — a blur level of ~1e-8, which costs four tables
    // per node for a weight that rounds away.
    const double d_a = std::max(0.0, var_a - alpha2), d_b = std::max(0.0, var_b - beta2);
    line.level_a = fractional_level(d_a), line.level_b = fractional_level(d_b);
    // The blur along u is at least √min d.
    line.nodes = nodes(line_rule_for(alpha2 + beta2, std::min(d_a, d_b)), alpha, beta);
    return line;
}

const ColourMapFilter::Blurred& ColourMapFilter::diagonal_table(int sign, int level) const
{
    if (level == 0) return table_[0];
    const int side = sign < 0 ? 1 : 0;
    std::call_once(diagonal_->built[side], [&] {
        for (std::vector<float>& rgb : diagonal_blurs(table_[0].rgb, size_, sign, diagonal_levels()))
            diagonal_->tables[side].push_back(Blurred{size_, size_, std::move(rgb)});
    });
    return diagonal_->tables[side][std::size_t(level - 1)];
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
    // Σ_k w_k · fetch(a + t_k α, b + t_k β).
    auto along = [&](const Nodes& n, auto&& fetch_at) {
        double sum[3] = {0, 0, 0};
        for (int k = 0; k < n.count; ++k) {
            const double t = n.node[k];
            const Rgb c = fetch_at(std::clamp(l.a + t * n.alpha / size_, 0.0, 1.0), std::clamp(l.b + t * n.beta / size_, 0.0, 1.0));
            for (int ch = 0; ch < 3; ++ch) sum[ch] += n.weight[k] * c[ch];
        }
        return Rgb{float(sum[0]), float(sum[1]), float(sum[2])};
    };
    Rgb axis{};
    if (l.diagonal_weight < 1) {
        if (l.nodes.alpha == 0 && l.nodes.beta == 0) {
            axis = fetch_fractional(l.level_a, l.level_b, l.a, l.b);
        } else {
            const Fractional levels(*this, l.level_a, l.level_b);
            axis = along(l.nodes, [&](double a, double b) { return levels.fetch(a, b); });
        }
        if (l.diagonal_weight == 0) return axis;
    }
    const Rgb diagonal = along(l.diagonal_nodes, [&](double a, double b) { return fetch(*l.diagonal, a, b); });
    if (l.diagonal_weight == 1) return diagonal;
    Rgb out;
    for (int c = 0; c < 3; ++c) out[c] = float((1 - l.diagonal_weight) * axis[c] + l.diagonal_weight * diagonal[c]);
    return out;
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
        const LevelBlend blend = filter.level_blend(level_a, level_b);
        for (int k = 0; k < blend.count; ++k)
            add(filter, blend.level_a[std::size_t(k)], blend.level_b[std::size_t(k)], blend.weight[std::size_t(k)]);
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
    std::array<Table, 3> tables_;  // the first count_ set by add() (not value-initialised: a rep stos per lookup)
    int count_ = 0;
};

Rgb ColourMapFilter::lookup(double mean_a, double mean_b, const PairCovariance& covariance, ColourMapMethod method) const
{
    if (method == ColourMapMethod::reference) return filtered(mean_a, mean_b, covariance, method);
    return read(line(mean_a, mean_b, covariance, method));
}

void ColourMapFilter::lookup_row(std::size_t count, const double* mean_a, const double* mean_b, const PairCovariance* covariance,
                                 ColourMapMethod method, Rgb* out) const
{
    if (method == ColourMapMethod::reference) {
        for (std::size_t i = 0; i < count; ++i) out[i] = filtered(mean_a[i], mean_b[i], covariance[i], method);
        return;
    }
    constexpr std::size_t chunk = 32;
    Line lines[chunk];
    for (std::size_t start = 0; start < count; start += chunk) {
        const std::size_t n = std::min(chunk, count - start);
        for (std::size_t i = 0; i < n; ++i) lines[i] = line(mean_a[start + i], mean_b[start + i], covariance[start + i], method);
        for (std::size_t i = 0; i < n; ++i) out[start + i] = read(lines[i]);
    }
}

Rgb ColourMapFilter::read(const Line& l) const
{
    // Σ_k w_k · fetch(a + t_k α, b + t_k β) in single precision, the nodes' addresses and
    // corner weights vectorised across the nodes, summed in node order (colour_map_kernels.h).
    auto along = [&](const Nodes& n, const colour_map_kernels::Table* tables, int table_count) {
        colour_map_kernels::LineNodes nodes{};
        nodes.tables = tables, nodes.table_count = table_count;
        nodes.a = l.a, nodes.b = l.b, nodes.step_a = n.alpha / size_, nodes.step_b = n.beta / size_;
        nodes.node = n.node_float, nodes.weight = n.weight_float, nodes.count = n.count;
        Rgb sum;
        colour_map_kernels::line_sum(nodes, sum.data());
        return sum;
    };
    Rgb axis{};
    if (l.diagonal_weight < 1) {
        const Packed levels(*this, l.level_a, l.level_b);
        if (l.nodes.alpha == 0 && l.nodes.beta == 0) {
            const Colour4 c = levels.fetch(l.a, l.b);
            axis = {c[0], c[1], c[2]};
        } else {
            colour_map_kernels::Table tables[3];
            axis = along(l.nodes, tables, levels.kernel_tables(tables));
        }
        if (l.diagonal_weight == 0) return axis;
    }
    const Blurred& m = *l.diagonal;
    const colour_map_kernels::Table table{m.rgb.data(), std::size_t(m.width) * 3, m.width, m.height,
                                          std::max(0, m.width - 2), std::max(0, m.height - 2), 1.0f};
    const Rgb diagonal = along(l.diagonal_nodes, &table, 1);
    if (l.diagonal_weight == 1) return diagonal;
    const float w = float(l.diagonal_weight);
    Rgb out;
    for (int c = 0; c < 3; ++c) out[c] = (1 - w) * axis[c] + w * diagonal[c];
    return out;
}

Rgb ColourMapFilter::expected(double mean_a, double mean_b, const PairCovariance& covariance) const
{
    // N = μ + L z, L the Cholesky factor; z on a fine uniform grid with Gaussian weights.
    const double l11 = std::sqrt(std::max(0.0, covariance.aa));
    const double l21 = l11 > 0 ? covariance.ab / l11 : 0.0;
    const double l22 = std::sqrt(std::max(0.0, covariance.bb - l21 * l21));
    const int count = 64;
    static const LineRule rule = uniform_rule(count);
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
