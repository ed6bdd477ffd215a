#include "models/wavelet/band_leakage.h"

#include "models/wavelet/wavelet_noise.h"
#include "spectra/band_power.h"
#include "spectra/fft.h"
#include "numerics/constants.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <complex>
#include <map>
#include <mutex>

namespace stochtex {

namespace {

double sinc(double f) { return f == 0 ? 1.0 : std::sin(kPi * f) / (kPi * f); }

std::vector<std::vector<double>> compute_leakage(int band_count)
{
    const WaveletNoise2D& noise = WaveletNoise2D::shared();
    const int n = noise.period_x();  // the shared tile is square
    const std::vector<std::complex<float>> spectrum = real_fft_2d(noise.coefficients(), n, n);
    const int half = n / 2 + 1;
    // The spline's transfer function falls as 1/f³; aliases beyond ±2 lattice periods carry
    // less than 1e-5 of the power.
    constexpr int aliases = 2;
    std::vector<std::vector<double>> leakage(band_count, std::vector<double>(band_count, 0.0));
    for (int ky = 0; ky < n; ++ky) {
        const double fy0 = double(ky <= n / 2 ? ky : ky - n) / n;
        for (int kx = 0; kx < half; ++kx) {
            const double coefficient_power = std::norm(spectrum[std::size_t(ky) * half + kx]);
            if (coefficient_power == 0) continue;
            const double multiplicity = (kx == 0 || kx == n / 2) ? 1.0 : 2.0;
            const double fx0 = double(kx) / n;
            for (int my = -aliases; my <= aliases; ++my)
                for (int mx = -aliases; mx <= aliases; ++mx) {
                    const double fx = fx0 + mx, fy = fy0 + my;
                    const double power =
                        multiplicity * coefficient_power * std::pow(sinc(fx) * sinc(fy), 6);
                    for (int j = 0; j < band_count; ++j) {
                        // Band j is sampled every 2^-j lattice units: cycles per pixel, folded.
                        double nx = std::ldexp(fx, -j), ny = std::ldexp(fy, -j);
                        nx -= std::round(nx);
                        ny -= std::round(ny);
                        const double nu = std::max(std::abs(nx), std::abs(ny));
                        if (nu == 0) continue;  // exact DC: the mean, not band power
                        const int b = std::clamp(band_of_frequency(nu), 0, band_count - 1);
                        leakage[b][j] += power;
                    }
                }
        }
    }
    for (int j = 0; j < band_count; ++j) {
        double total = 0;
        for (int b = 0; b < band_count; ++b) total += leakage[b][j];
        for (int b = 0; b < band_count; ++b) leakage[b][j] /= total;
    }
    return leakage;
}

}  // namespace

const std::vector<std::vector<double>>& band_leakage(int band_count)
{
    static std::mutex mutex;
    static std::map<int, std::vector<std::vector<double>>> cache;
    std::lock_guard<std::mutex> lock(mutex);
    auto it = cache.find(band_count);
    if (it == cache.end()) it = cache.emplace(band_count, compute_leakage(band_count)).first;
    return it->second;
}

int leakage_corrected_band_count(int width, int height)
{
    // Band j's lowest frequency is 2^-(j+2) cycles per pixel: min(W, H)·2^-(j+2) ≥ 8.
    int count = 0;
    while (std::ldexp(double(std::min(width, height)), -(count + 2)) >= 8) ++count;
    return count;
}

std::vector<double> solve_band_weights(const std::vector<double>& power, double band_variance, int corrected_bands)
{
    const int n = int(power.size());
    if (n == 0) return {};
    const auto& leakage = band_leakage(n);
    Eigen::MatrixXd a(n, n);
    Eigen::VectorXd p(n);
    for (int b = 0; b < n; ++b) {
        p[b] = std::max(0.0, power[b]);
        for (int j = 0; j < n; ++j) a(b, j) = band_variance * (j < corrected_bands ? leakage[b][j] : double(b == j));
    }
    // NNLS by projected coordinate descent: the matrix is diagonally dominant (~0.8 on the
    // diagonal), so a few dozen sweeps converge to float precision.
    const Eigen::MatrixXd gram = a.transpose() * a;
    const Eigen::VectorXd rhs = a.transpose() * p;
    Eigen::VectorXd x = a.colPivHouseholderQr().solve(p).cwiseMax(0.0);
    for (int sweep = 0; sweep < 200; ++sweep) {
        double change = 0;
        for (int j = 0; j < n; ++j) {
            if (gram(j, j) <= 0) continue;
            const double updated = std::max(0.0, x[j] + (rhs[j] - gram.row(j).dot(x)) / gram(j, j));
            change = std::max(change, std::abs(updated - x[j]));
            x[j] = updated;
        }
        if (change <= 1e-14 * (1 + x.cwiseAbs().maxCoeff())) break;
    }
    std::vector<double> weights(n);
    for (int j = 0; j < n; ++j) weights[j] = std::sqrt(x[j]);
    return weights;
}

}  // namespace stochtex
