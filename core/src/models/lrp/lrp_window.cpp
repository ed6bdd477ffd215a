#include "models/lrp/lrp_window.h"

#include "numerics/constants.h"

#include <cmath>
#include <map>
#include <mutex>
#include <vector>

namespace stochtex {

namespace {

constexpr double kaiser_alpha = 3 * kPi;

/// Composite Simpson rule with `intervals` (even) intervals: f is called with the node index
/// and its position (node i at a + i·h, the last at b), so a caller can read tabulated factors.
template <class F>
double simpson_nodes(const F& f, double a, double b, int intervals)
{
    const double h = (b - a) / intervals;
    double sum = f(0, a) + f(intervals, b);
    for (int i = 1; i < intervals; ++i) sum += (i % 2 ? 4 : 2) * f(i, a + i * h);
    return sum * h / 3;
}

template <class F>
double simpson(const F& f, double a, double b, int intervals)
{
    return simpson_nodes([&f](int, double x) { return f(x); }, a, b, intervals);
}

/// The radius at which the cumulative energy of a spectrum sampled on [0, ρ_max] reaches
/// `fraction` of its total (linear interpolation between samples).
double energy_radius(const std::vector<double>& rho, const std::vector<double>& density, double fraction)
{
    std::vector<double> cumulative(rho.size(), 0.0);
    for (std::size_t i = 1; i < rho.size(); ++i)
        cumulative[i] = cumulative[i - 1] + 0.5 * (density[i] + density[i - 1]) * (rho[i] - rho[i - 1]);
    const double target = fraction * cumulative.back();
    for (std::size_t i = 1; i < rho.size(); ++i)
        if (cumulative[i] >= target) {
            const double t = (target - cumulative[i - 1]) / (cumulative[i] - cumulative[i - 1]);
            return rho[i - 1] + t * (rho[i] - rho[i - 1]);
        }
    return rho.back();
}

/// Cached per fraction: the transforms cost a few milliseconds.
template <class Compute>
double cached(std::map<double, double>& cache, double fraction, const Compute& compute)
{
    static std::mutex mutex;
    std::lock_guard<std::mutex> lock(mutex);
    const auto found = cache.find(fraction);
    if (found != cache.end()) return found->second;
    return cache[fraction] = compute();
}

// The transforms are integrated up to 3 cycles per spacing, where |ŵ|² has fallen below 1e-7 of
// its peak: the energy beyond does not move the 75 % radius in the third decimal.
constexpr double spectrum_extent = 3;
constexpr int spectrum_samples = 480, window_intervals = 200;

/// w at the window transforms' Simpson nodes on [0, 1.5]: each transform integrates w against
/// another factor at the same nodes for every one of its 481 frequencies, and w is a Bessel
/// function (~0.3 µs), so computing it once instead of per frequency removes ~97 000 of them
/// from a texture's construction (the values, and so the spreads, are the same bits).
const std::vector<double>& window_at_transform_nodes()
{
    static const std::vector<double> values = [] {
        std::vector<double> w(window_intervals + 1);
        simpson_nodes([&w](int i, double y) { return w[std::size_t(i)] = lrp_window(y); }, 0, lrp_window_radius,
                      window_intervals);
        return w;
    }();
    return values;
}

}  // namespace

double lrp_window(double y)
{
    const double t = y / lrp_window_radius;
    if (!(std::abs(t) < 1)) return 0;
    return std::cyl_bessel_i(3.0, kaiser_alpha * std::sqrt(1 - t * t)) / std::cyl_bessel_i(3.0, kaiser_alpha);
}

double lrp_window_radial_energy()
{
    // A constant of the window (40 000 Bessel evaluations): integrated once per process.
    static const double energy =
        simpson([](double r) { return r * lrp_window(r) * lrp_window(r); }, 0, lrp_window_radius, 20000);
    return energy;
}

namespace {

/// The radius holding `fraction` of a spectrum's energy, the spectrum sampled on [0, 3] cycles
/// per spacing: `density(f)` is the energy per unit radius at f.
template <class Density>
double spectral_radius(double fraction, const Density& density)
{
    std::vector<double> rho(spectrum_samples + 1), energy(spectrum_samples + 1);
    for (int i = 0; i <= spectrum_samples; ++i) {
        rho[std::size_t(i)] = spectrum_extent * i / spectrum_samples;
        energy[std::size_t(i)] = density(rho[std::size_t(i)]);
    }
    return energy_radius(rho, energy, fraction);
}

}  // namespace

double lrp_window_spread_1d(double fraction)
{
    static std::map<double, double> cache;
    return cached(cache, fraction, [fraction] {
        return spectral_radius(fraction, [](double f) {
            // ŵ(f) = 2 ∫₀^1.5 w(y) cos(2π f y) dy (w is even).
            const std::vector<double>& w = window_at_transform_nodes();
            const double transform =
                2 * simpson_nodes([f, &w](int i, double y) { return w[std::size_t(i)] * std::cos(2 * kPi * f * y); }, 0,
                                  lrp_window_radius, window_intervals);
            return transform * transform;
        });
    });
}

double lrp_window_spread_2d(double fraction)
{
    // Seeded with the fraction every texture asks for (lrp_noise.cpp, lrp_structure_noise.cpp):
    // its ~97 000 J₀ evaluations were most of an lrp texture's start-up (~20 ms). The literal is
    // lrp_window_spread_2d_computed(0.75), bit for bit (LrpWindow.SpreadSeedIsTheComputedValue).
    static std::map<double, double> cache{{0.75, 0x1.a5dbbcae46c39p-2}};
    return cached(cache, fraction, [fraction] { return lrp_window_spread_2d_computed(fraction); });
}

double lrp_window_spread_2d_computed(double fraction)
{
    return spectral_radius(fraction, [](double f) {
        // Hankel transform of the radial window, Ŵ(ρ) = 2π ∫₀^1.5 w(r) J₀(2πρr) r dr; the
        // energy per unit radius is 2πρ |Ŵ(ρ)|².
        const std::vector<double>& w = window_at_transform_nodes();
        const double transform =
            2 * kPi *
            simpson_nodes(
                [f, &w](int i, double r) { return w[std::size_t(i)] * std::cyl_bessel_j(0.0, 2 * kPi * f * r) * r; },
                0, lrp_window_radius, window_intervals);
        return 2 * kPi * f * transform * transform;
    });
}

const LrpWindowTable& LrpWindowTable::shared()
{
    static const LrpWindowTable table;
    return table;
}

LrpWindowTable::LrpWindowTable()
{
    const double extent = lrp_window_radius * lrp_window_radius;
    scale_ = float(size / extent);
    for (int i = 0; i <= size; ++i) value_[i] = float(lrp_window(std::sqrt(extent * i / size)));
    value_[size + 1] = 0.0f;
}

}  // namespace stochtex
