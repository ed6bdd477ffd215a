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

std::vector<std::vector<double>> stratum_leakage(const std::vector<LrpStratum>& strata, const std::vector<int>& label,
                                                 int size)
{
    std::vector<std::vector<double>> leakage(strata.size(), std::vector<double>(strata.size(), 0.0));
    for (std::size_t b = 0; b < strata.size(); ++b) {
        const DiscreteSpectrum q = expected_stratum_spectrum(strata[b], size);
        for (std::size_t i = 0; i < label.size(); ++i)
            if (label[i] >= 0 && std::size_t(label[i]) < strata.size()) leakage[std::size_t(label[i])][b] += q.power[i];
    }
    return leakage;
}

void correct_stratum_leakage(std::vector<LrpStratum>& strata, const std::vector<int>& label,
                             const std::array<const DiscreteSpectrum*, 3>& channels)
{
    if (strata.empty()) return;
    const std::size_t n = strata.size();
    const int size = channels[0]->size;
    const std::vector<std::vector<double>> leakage = stratum_leakage(strata, label, size);
    for (int c = 0; c < 3; ++c) {
        if (!channels[std::size_t(c)]) continue;
        std::vector<double> target(n, 0.0);
        for (std::size_t i = 0; i < label.size(); ++i)
            if (label[i] >= 0 && std::size_t(label[i]) < n) target[std::size_t(label[i])] += channels[std::size_t(c)]->power[i];
        double total = 0;
        for (double t : target) total += t;
        if (!(total > 0)) continue;
        // Rows: each stratum's energy (relative error), then the total variance.
        Eigen::MatrixXd a = Eigen::MatrixXd::Zero(Eigen::Index(n + 1), Eigen::Index(n));
        Eigen::VectorXd rhs = Eigen::VectorXd::Ones(Eigen::Index(n + 1));
        for (std::size_t row = 0; row < n; ++row) {
            // A stratum with (almost) none of this channel's energy is weighed as if it held 1 % of the mean.
            const double scale = std::max(target[row], 0.01 * total / double(n));
            for (std::size_t col = 0; col < n; ++col) a(Eigen::Index(row), Eigen::Index(col)) = leakage[row][col] / scale;
            rhs(Eigen::Index(row)) = target[row] / scale;
        }
        for (std::size_t col = 0; col < n; ++col) a(Eigen::Index(n), Eigen::Index(col)) = 1 / total;
        const Eigen::VectorXd variance = nonnegative_least_squares(a, rhs);
        for (std::size_t s = 0; s < n; ++s) strata[s].sigma[std::size_t(c)] = std::sqrt(std::max(0.0, variance(Eigen::Index(s))));
    }
}

}  // namespace stochtex
