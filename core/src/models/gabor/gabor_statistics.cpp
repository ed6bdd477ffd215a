#include "models/gabor/gabor_statistics.h"
#include "numerics/constants.h"

#include <stochtex/models/gabor_parameters.h>
#include <stochtex/models/gabor_shader_data.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <mutex>
#include <vector>

namespace stochtex {

double scaled_bessel_i0(double x)
{
    x = std::abs(x);
    if (x < 3.75) {
        const double t = (x / 3.75) * (x / 3.75);
        const double i0 =
            1 + t * (3.5156229 + t * (3.0899424 + t * (1.2067492 + t * (0.2659732 + t * (0.0360768 + t * 0.0045813)))));
        return std::exp(-x) * i0;
    }
    const double t = 3.75 / x;
    const double p = 0.39894228 +
                     t * (0.01328592 + t * (0.00225319 + t * (-0.00157565 + t * (0.00916281 + t * (-0.02057706 +
                          t * (0.02635537 + t * (-0.01647633 + t * 0.00392377)))))));
    return p / std::sqrt(x);
}

namespace {

/// Gauss–Legendre nodes and weights on [0, 1] (Newton on P_n; no hand-copied tables).
struct GaussLegendre {
    std::vector<double> node, weight;
    explicit GaussLegendre(int n)
    {
        for (int i = 0; i < n; ++i) {
            double x = std::cos(kPi * (i + 0.75) / (n + 0.5)), derivative = 1;
            for (int iteration = 0; iteration < 100; ++iteration) {
                double p0 = 1, p1 = x;
                for (int k = 2; k <= n; ++k) {
                    const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
                    p0 = p1, p1 = p2;
                }
                derivative = n * (x * p1 - p0) / (x * x - 1);
                const double step = p1 / derivative;
                x -= step;
                if (std::abs(step) < 1e-15) break;
            }
            node.push_back(0.5 * (1 - x));
            weight.push_back(1 / ((1 - x * x) * derivative * derivative));  // 2/((1−x²)P'²) halved for [0, 1]
        }
    }
    /// ∫ f over [lo, hi].
    template <class F>
    double integrate(double lo, double hi, const F& f) const
    {
        double sum = 0;
        for (std::size_t i = 0; i < node.size(); ++i) sum += weight[i] * f(lo + (hi - lo) * node[i]);
        return sum * (hi - lo);
    }
};

const GaussLegendre& legendre_8()
{
    static const GaussLegendre rule(8);
    return rule;
}

/// Radial average of a 2D PSD pair of blobs at ±ω^s, |ω^s| = f_s: the same as a ring of radius f_s.
/// Per unit variance each blob is C₂·exp(−2π|f ∓ ω^s|²/a²) with C₂ = 1/a², and averaging a blob over
/// the angle of f gives exp(−k(ρ² + f_s²)) I₀(2kρf_s), k = 2π/a².
double ring_psd(double rho, double f_s, double a)
{
    const double k = 2 * kPi / (a * a);
    return 2 * std::exp(-k * (rho - f_s) * (rho - f_s)) * scaled_bessel_i0(2 * k * rho * f_s) / (a * a);
}

/// E over u uniform on the unit sphere of exp(−α u₁² − β u₂²). Integrating the azimuth first
/// gives a Bessel function; the remaining integral over u₃ is peaked near |u₃| = 1 when α or β
/// is large, hence panels graded towards 1.
double sphere_gaussian_average(double alpha, double beta)
{
    const double low = std::min(alpha, beta), half_gap = 0.5 * std::abs(alpha - beta);
    auto integrand = [&](double c) {
        const double y = 1 - c * c;
        return std::exp(-y * low) * scaled_bessel_i0(y * half_gap);
    };
    double sum = 0, lo = 0;
    for (int k = 1; k <= 26; ++k) {
        const double hi = k == 26 ? 1.0 : 1 - std::ldexp(1.0, -k);
        sum += legendre_8().integrate(lo, hi, integrand);
        lo = hi;
    }
    return sum;
}

/// sphere_gaussian_average tabulated on log(1 + α), log(1 + β) ∈ [0, log(1 + 10⁶)] and
/// interpolated bilinearly (relative error < 0.5 %): it is needed per evaluation and octave when a
/// filtered isotropic texture feeds a histogram map.
class SphereGaussianTable {
public:
    static const SphereGaussianTable& get()
    {
        static std::once_flag once;
        static SphereGaussianTable* table;
        std::call_once(once, [] { table = new SphereGaussianTable(); });
        return *table;
    }
    double operator()(double alpha, double beta) const
    {
        const double x = std::min(std::log1p(std::max(0.0, alpha)) / step_, double(size - 1) - 1e-9);
        const double y = std::min(std::log1p(std::max(0.0, beta)) / step_, double(size - 1) - 1e-9);
        const int i = int(x), j = int(y);
        const double fx = x - i, fy = y - j;
        auto at = [&](int u, int v) { return values_[std::size_t(v) * size + u]; };
        return (1 - fy) * ((1 - fx) * at(i, j) + fx * at(i + 1, j)) + fy * ((1 - fx) * at(i, j + 1) + fx * at(i + 1, j + 1));
    }

    static constexpr int size = 97;
    double step() const { return step_; }
    const std::vector<double>& values() const { return values_; }

private:
    SphereGaussianTable() : step_(std::log1p(1e6) / (size - 1)), values_(std::size_t(size) * size)
    {
        for (int j = 0; j < size; ++j)
            for (int i = 0; i <= j; ++i) {
                const double value = sphere_gaussian_average(std::expm1(i * step_), std::expm1(j * step_));
                values_[std::size_t(j) * size + i] = values_[std::size_t(i) * size + j] = value;
            }
    }
    double step_;
    std::vector<double> values_;
};

}  // namespace

GaborSphereTable gabor_sphere_table()
{
    const SphereGaussianTable& table = SphereGaussianTable::get();
    return {SphereGaussianTable::size, table.step(), std::vector<float>(table.values().begin(), table.values().end())};
}

namespace {

/// An oriented noise's second-order statistics are those of its two populations of impulses,
/// mixed by their shares: random phases leave no cross terms, and both have unit variance.
template <class Statistic>
double mixed(const GaborNoiseParameters& noise, const Statistic& statistic)
{
    GaborNoiseParameters part = noise;
    part.kind = GaborKind::anisotropic;
    const double oriented = noise.oriented_fraction > 0 ? statistic(part) : 0.0;
    part.kind = GaborKind::isotropic;
    const double isotropic = noise.oriented_fraction < 1 ? statistic(part) : 0.0;
    return noise.oriented_fraction * oriented + (1 - noise.oriented_fraction) * isotropic;
}

}  // namespace

double gabor_correlation(const GaborNoiseParameters& noise, const Vec3& tau)
{
    if (noise.kind == GaborKind::oriented)
        return mixed(noise, [&](const GaborNoiseParameters& part) { return gabor_correlation(part, tau); });
    const double a = noise.bandwidth, f = noise.frequency;
    const double envelope = std::exp(-kPi * a * a * dot3(tau, tau) / 2);
    switch (noise.kind) {
    case GaborKind::anisotropic: return envelope * std::cos(2 * kPi * f * dot3(noise.direction, tau));
    case GaborKind::hybrid: {
        const double along = dot3(noise.direction, tau);
        const double in_plane = std::sqrt(std::max(0.0, dot3(tau, tau) - along * along));
        return envelope * std::cyl_bessel_j(0.0, 2 * kPi * f * in_plane);
    }
    case GaborKind::isotropic:
    case GaborKind::oriented: break;
    }
    const double x = 2 * kPi * f * std::sqrt(dot3(tau, tau));
    return envelope * (x < 1e-8 ? 1.0 : std::sin(x) / x);
}

double gabor_slice_radial_psd(const GaborNoiseParameters& noise, double rho)
{
    if (noise.kind == GaborKind::oriented)
        return mixed(noise, [&](const GaborNoiseParameters& part) { return gabor_slice_radial_psd(part, rho); });
    const double a = noise.bandwidth, f = noise.frequency;
    const Vec3& d = noise.direction;
    switch (noise.kind) {
    case GaborKind::anisotropic: return ring_psd(rho, f * std::hypot(d[0], d[1]), a);
    case GaborKind::hybrid: {
        // ω = F(cos ψ e₁ + sin ψ e₂) projected on (u, v): a smooth periodic function of ψ, for
        // which the trapezoid rule converges fast.
        const TangentFrame plane = tangent_frame(d, {0, 0, 0});
        constexpr int steps = 64;
        double sum = 0;
        for (int i = 0; i < steps; ++i) {
            const double psi = kPi * (i + 0.5) / steps, c = std::cos(psi), s = std::sin(psi);
            sum += ring_psd(rho, f * std::hypot(c * plane.t[0] + s * plane.b[0], c * plane.t[1] + s * plane.b[1]), a);
        }
        return sum / steps;
    }
    case GaborKind::isotropic:
    case GaborKind::oriented: break;
    }
    // |ω^s| = F·√(1 − z²), z = cos(colatitude) uniform; the ring depends on |ω^s|² only, so the
    // integrand is smooth in z; panels resolve narrow rings (small bandwidth).
    double sum = 0;
    constexpr int panels = 16;
    for (int k = 0; k < panels; ++k)
        sum += legendre_8().integrate(double(k) / panels, double(k + 1) / panels,
                                      [&](double z) { return ring_psd(rho, f * std::sqrt(1 - z * z), a); });
    return sum;
}

double gabor_retained_variance(const GaborNoiseParameters& noise, const TangentFrame& frame, const GaborFilter& filter)
{
    if (filter.identity) return 1;
    if (noise.kind == GaborKind::oriented)
        return mixed(noise, [&](const GaborNoiseParameters& part) { return gabor_retained_variance(part, frame, filter); });
    const Symmetric2& damping = filter.damping;  // the kernel's amplitude is exp(−ω^sᵀDω^s): variance exp(−2ω^sᵀDω^s)
    const double f = noise.frequency;
    switch (noise.kind) {
    case GaborKind::anisotropic: {
        const Vec3& d = noise.direction;
        const double st = f * dot3(frame.t, d), sb = f * dot3(frame.b, d);
        return filter.amplitude * std::exp(-2 * damping.quadratic_form(st, sb));
    }
    case GaborKind::hybrid: {
        // Q(ψ) = 2 ω^s(ψ)ᵀ D ω^s(ψ) = c₀ + R cos(2ψ − ψ₀), whose exponential averages to e^-c₀ I₀(R).
        const TangentFrame plane = tangent_frame(noise.direction, {0, 0, 0});
        const double u1t = f * dot3(frame.t, plane.t), u1b = f * dot3(frame.b, plane.t);
        const double u2t = f * dot3(frame.t, plane.b), u2b = f * dot3(frame.b, plane.b);
        const double m11 = 2 * damping.quadratic_form(u1t, u1b), m22 = 2 * damping.quadratic_form(u2t, u2b);
        const double m12 = 2 * (damping.xx * u1t * u2t + damping.xy * (u1t * u2b + u1b * u2t) + damping.yy * u1b * u2b);
        const double c0 = 0.5 * (m11 + m22), r = std::hypot(0.5 * (m11 - m22), m12);
        return filter.amplitude * std::exp(-(c0 - r)) * scaled_bessel_i0(r);
    }
    case GaborKind::isotropic:
    case GaborKind::oriented: break;
    }
    // ω^s = F(u_t, u_b) with u uniform on the sphere: only the eigenvalues of 2F²D matter.
    const double scale = 2 * f * f;
    return filter.amplitude * SphereGaussianTable::get()(scale * damping.largest_eigenvalue(),
                                                          scale * std::max(0.0, damping.smallest_eigenvalue()));
}

}  // namespace stochtex
