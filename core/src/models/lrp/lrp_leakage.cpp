#include "models/lrp/lrp_leakage.h"
#include <stochtex/models/lrp_parameters.h>

#include "spectra/fft.h"
#include "models/lrp/lrp_window.h"
#include "numerics/nonnegative_least_squares.h"

#include <algorithm>
#include <cmath>
#include <complex>

namespace stochtex {

namespace {

/// The variance-normalised window of the lattice point at the origin, w_0 / √Σ w_i², sampled at
/// integer pixel offsets and wrapped onto a size² periodic grid (FFT order).
std::vector<float> wrapped_normalised_window(double spacing, int size)
{
    std::vector<float> grid(std::size_t(size) * size, 0.0f);
    const int reach = int(std::ceil(lrp_window_radius * spacing));
    // The synthesis table (in y²): the exact Bessel series would cost seconds for wide windows.
    const LrpWindowTable& window = LrpWindowTable::shared();
    auto w_at = [&](double dx, double dy) { return double(window(float((dx * dx + dy * dy) / (spacing * spacing)))); };
    auto window_sum_squares = [&](double x, double y) {
        const double cx = std::round(x / spacing), cy = std::round(y / spacing);
        double sum = 0;
        for (int j = -1; j <= 1; ++j)
            for (int i = -1; i <= 1; ++i) {
                const double w = w_at(x - (cx + i) * spacing, y - (cy + j) * spacing);
                sum += w * w;
            }
        return sum;
    };
    for (int y = -reach; y <= reach; ++y)
        for (int x = -reach; x <= reach; ++x) {
            const double w = w_at(x, y);
            if (!(w > 0)) continue;
            const std::size_t i = std::size_t(((y % size) + size) % size) * size + std::size_t(((x % size) + size) % size);
            grid[i] += float(w / std::sqrt(window_sum_squares(x, y)));
        }
    return grid;
}

/// Weight of the radial-ring rows against the strata's (measured on five photos, 512² crops: 0.3
/// keeps every stratum's energy within 0.69–1.27 of its target with most of the rings' gain).
constexpr double ring_weight = 0.3;

std::size_t fft_index(int kx, int ky, int size)
{
    return std::size_t(((ky % size) + size) % size) * size + std::size_t(((kx % size) + size) % size);
}

}  // namespace

DiscreteSpectrum expected_stratum_spectrum(const LrpStratum& stratum, int size)
{
    // Power spectrum of the window, normalised to unit sum (FFT order).
    const std::vector<std::complex<float>> window = real_fft_2d(wrapped_normalised_window(stratum.spacing, size), size, size);
    const int half_width = size / 2 + 1;
    std::vector<float> kernel(std::size_t(size) * size, 0.0f);
    double kernel_sum = 0;
    for (int ky = 0; ky < size; ++ky)
        for (int kx = 0; kx < half_width; ++kx) {
            const double p = std::norm(window[std::size_t(ky) * half_width + kx]);
            kernel[fft_index(kx, ky, size)] = float(p);
            kernel_sum += p;
            if (kx != 0 && 2 * kx != size) {
                kernel[fft_index(-kx, -ky, size)] = float(p);
                kernel_sum += p;
            }
        }
    // The density of drawn frequencies: each sub-stratum equally likely, its bins equally, ±f.
    std::vector<float> density(std::size_t(size) * size, 0.0f);
    const double per_substratum = 1.0 / double(stratum.substrata.size());
    for (const std::vector<int>& bins : stratum.substrata) {
        const double per_bin = per_substratum / double(bins.size() / 2);
        for (std::size_t b = 0; b + 1 < bins.size(); b += 2) {
            density[fft_index(bins[b], bins[b + 1], size)] += float(0.5 * per_bin);
            density[fft_index(-bins[b], -bins[b + 1], size)] += float(0.5 * per_bin);
        }
    }
    // Circular convolution on the grid: frequencies past Nyquist fold back, as in a render.
    std::vector<std::complex<float>> product = real_fft_2d(density, size, size);
    const std::vector<std::complex<float>> kernel_spectrum = real_fft_2d(kernel, size, size);
    for (std::size_t i = 0; i < product.size(); ++i) product[i] *= kernel_spectrum[i];
    const std::vector<float> convolved = real_inverse_fft_2d(product, size, size);
    DiscreteSpectrum result(size);
    const double scale = 1.0 / (kernel_sum * double(size) * size);
    for (int ky = -size / 2; ky < size / 2; ++ky)
        for (int kx = -size / 2; kx < size / 2; ++kx)
            result.at(kx, ky) = std::max(0.0, double(convolved[fft_index(kx, ky, size)]) * scale);
    return result;
}

namespace {

/// Radial rings of the size² grid, `per_octave` per octave from Nyquist down to 1/T (the rings of
/// radial_log_spectrum_distance_db); −1 for DC and the corners past Nyquist.
std::vector<int> radial_rings(int size, int per_octave, int* count)
{
    *count = int(std::ceil(per_octave * std::log2(size / 2.0))) + 1;
    std::vector<int> ring(std::size_t(size) * size, -1);
    for (int ky = -size / 2; ky < size / 2; ++ky)
        for (int kx = -size / 2; kx < size / 2; ++kx) {
            const double f = std::hypot(kx, ky) / size;
            if (f == 0 || f > 0.5) continue;
            ring[std::size_t(ky + size / 2) * size + std::size_t(kx + size / 2)] =
                std::min(*count - 1, int(std::floor(per_octave * std::log2(0.5 / f))));
        }
    return ring;
}

/// Rings per octave in the variance solve: as the fidelity metric's.
constexpr int rings_per_octave = 4;

}  // namespace

std::vector<std::vector<double>> stratum_leakage(const std::vector<LrpStratum>& strata, const std::vector<int>& label,
                                                 int size, const std::vector<int>* rings, int ring_count,
                                                 std::vector<std::vector<double>>* ring_leakage)
{
    std::vector<std::vector<double>> leakage(strata.size(), std::vector<double>(strata.size(), 0.0));
    if (ring_leakage) ring_leakage->assign(std::size_t(ring_count), std::vector<double>(strata.size(), 0.0));
    for (std::size_t b = 0; b < strata.size(); ++b) {
        const DiscreteSpectrum q = expected_stratum_spectrum(strata[b], size);
        for (std::size_t i = 0; i < label.size(); ++i) {
            if (label[i] >= 0 && std::size_t(label[i]) < strata.size()) leakage[std::size_t(label[i])][b] += q.power[i];
            if (ring_leakage && (*rings)[i] >= 0) (*ring_leakage)[std::size_t((*rings)[i])][b] += q.power[i];
        }
    }
    return leakage;
}

std::vector<std::vector<double>> stratum_leakage(const std::vector<LrpStratum>& strata, const std::vector<int>& label,
                                                 int size)
{
    return stratum_leakage(strata, label, size, nullptr, 0, nullptr);
}

void correct_stratum_leakage(std::vector<LrpStratum>& strata, const std::vector<int>& label,
                             const std::array<const DiscreteSpectrum*, 3>& channels, bool match_rings)
{
    if (strata.empty()) return;
    const std::size_t n = strata.size();
    const int size = channels[0]->size;
    int ring_count = 0;
    const std::vector<int> rings = radial_rings(size, rings_per_octave, &ring_count);
    std::vector<std::vector<double>> ring_leakage;
    const std::vector<std::vector<double>> leakage =
        stratum_leakage(strata, label, size, &rings, ring_count, match_rings ? &ring_leakage : nullptr);
    const std::size_t m = match_rings ? std::size_t(ring_count) : 0;
    for (int c = 0; c < 3; ++c) {
        if (!channels[std::size_t(c)]) continue;
        const DiscreteSpectrum& channel = *channels[std::size_t(c)];
        std::vector<double> target(n, 0.0), ring_target(m, 0.0);
        for (std::size_t i = 0; i < label.size(); ++i) {
            if (label[i] >= 0 && std::size_t(label[i]) < n) target[std::size_t(label[i])] += channel.power[i];
            if (m && rings[i] >= 0) ring_target[std::size_t(rings[i])] += channel.power[i];
        }
        double total = 0;
        for (double t : target) total += t;
        if (!(total > 0)) continue;
        // Rows: each stratum's energy (relative error), each radial ring's (relative error: about
        // a dB, the fidelity metric's), then the total variance.
        Eigen::MatrixXd a = Eigen::MatrixXd::Zero(Eigen::Index(n + m + 1), Eigen::Index(n));
        Eigen::VectorXd rhs = Eigen::VectorXd::Zero(Eigen::Index(n + m + 1));
        for (std::size_t row = 0; row < n; ++row) {
            // A stratum with (almost) none of this channel's energy is weighed as if it held 1 % of the mean.
            const double scale = std::max(target[row], 0.01 * total / double(n));
            for (std::size_t col = 0; col < n; ++col) a(Eigen::Index(row), Eigen::Index(col)) = leakage[row][col] / scale;
            rhs(Eigen::Index(row)) = target[row] / scale;
        }
        for (std::size_t row = 0; row < m; ++row) {
            if (!(ring_target[row] > 1e-9 * total)) continue;  // a ring the photo leaves empty
            for (std::size_t col = 0; col < n; ++col)
                a(Eigen::Index(n + row), Eigen::Index(col)) = ring_weight * ring_leakage[row][col] / ring_target[row];
            rhs(Eigen::Index(n + row)) = ring_weight;
        }
        for (std::size_t col = 0; col < n; ++col) a(Eigen::Index(n + m), Eigen::Index(col)) = 1 / total;
        rhs(Eigen::Index(n + m)) = 1;
        const Eigen::VectorXd variance = nonnegative_least_squares(a, rhs);
        for (std::size_t s = 0; s < n; ++s) strata[s].sigma[std::size_t(c)] = std::sqrt(std::max(0.0, variance(Eigen::Index(s))));
    }
}

}  // namespace stochtex
