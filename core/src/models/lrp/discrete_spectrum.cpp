#include "models/lrp/discrete_spectrum.h"

#include "spectra/fft.h"
#include "numerics/constants.h"

#include <stochtex/error.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace stochtex {

double DiscreteSpectrum::total() const
{
    double sum = 0;
    for (double p : power) sum += p;
    return sum;
}

int welch_size(int width, int height, int max_size)
{
    int size = 1;
    while (2 * size < std::min(width, height) && 2 * size <= max_size) size *= 2;
    return size;
}

namespace {

/// Crop origins along an axis of `length` pixels: every T/2, the last one flush with the end.
std::vector<int> crop_origins(int length, int size)
{
    std::vector<int> origins;
    for (int start = 0; start + size <= length; start += size / 2) origins.push_back(start);
    if (origins.empty()) return origins;
    if (origins.back() + size < length) origins.push_back(length - size);
    return origins;
}

}  // namespace

DiscreteSpectrum welch_psd(const std::vector<float>& plane, int width, int height, int size)
{
    if (size < 4 || (size & (size - 1)) || size > width || size > height || plane.size() != std::size_t(width) * height)
        throw Error("welch_psd: a " + std::to_string(size) + "-point spectrum needs a power of two ≥ 4 within the " +
                    std::to_string(width) + "x" + std::to_string(height) + " plane");
    std::vector<double> taper(size);
    double taper_square_sum = 0;
    for (int i = 0; i < size; ++i) {
        const double s = std::sin(kPi * (i + 0.5) / size);
        taper[i] = s * s;
    }
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) taper_square_sum += taper[x] * taper[x] * taper[y] * taper[y];

    DiscreteSpectrum result(size);
    const std::vector<int> xs = crop_origins(width, size), ys = crop_origins(height, size);
    std::vector<float> crop(std::size_t(size) * size);
    const int half_width = size / 2 + 1;
    for (int y0 : ys)
        for (int x0 : xs) {
            double mean = 0;
            for (int y = 0; y < size; ++y)
                for (int x = 0; x < size; ++x) mean += plane[std::size_t(y0 + y) * width + x0 + x];
            mean /= double(size) * size;
            for (int y = 0; y < size; ++y)
                for (int x = 0; x < size; ++x)
                    crop[std::size_t(y) * size + x] =
                        float((plane[std::size_t(y0 + y) * width + x0 + x] - mean) * taper[x] * taper[y]);
            const std::vector<std::complex<float>> spectrum = real_fft_2d(crop, size, size);
            // Parseval: Σ_k |F_k|² = T² Σ_n (w x)², and Σ_n (w x)² / Σ_n w² estimates the variance.
            const double normalisation = 1.0 / (double(size) * size * taper_square_sum * xs.size() * ys.size());
            for (int ky = 0; ky < size; ++ky)
                for (int kx = 0; kx < half_width; ++kx) {
                    const double p = std::norm(spectrum[std::size_t(ky) * half_width + kx]) * normalisation;
                    const int fx = centred_bin(kx, size), fy = centred_bin(ky, size);
                    result.at(fx, fy) += p;
                    // The half spectrum holds each conjugate pair once, except the columns that are
                    // their own mirror (kx = 0 and kx = T/2).
                    if (kx != 0 && kx != size / 2) result.at(-fx, fy == -size / 2 ? fy : -fy) += p;
                }
        }
    result.at(0, 0) = 0;
    return result;
}

namespace {

template <class Density>
DiscreteSpectrum sampled_spectrum(int size, double variance, const Density& density)
{
    DiscreteSpectrum result(size);
    for (int ky = -size / 2; ky < size / 2; ++ky)
        for (int kx = -size / 2; kx < size / 2; ++kx)
            if (kx || ky) result.at(kx, ky) = density(double(kx) / size, double(ky) / size);
    const double total = result.total();
    if (!(total > 0)) throw Error("analytic spectrum: no power on the " + std::to_string(size) + "² grid");
    for (double& p : result.power) p *= variance / total;
    return result;
}

}  // namespace

DiscreteSpectrum ring_spectrum(int size, double radius, double width, double variance)
{
    return sampled_spectrum(size, variance, [&](double fx, double fy) {
        const double d = (std::hypot(fx, fy) - radius) / width;
        return std::exp(-0.5 * d * d);
    });
}

DiscreteSpectrum lobe_spectrum(int size, double fx, double fy, double along, double across, double variance)
{
    const double length = std::hypot(fx, fy);
    const double ux = length > 0 ? fx / length : 1, uy = length > 0 ? fy / length : 0;
    auto lobe = [&](double x, double y) {
        const double a = (x * ux + y * uy) / along, b = (-x * uy + y * ux) / across;
        return std::exp(-0.5 * (a * a + b * b));
    };
    return sampled_spectrum(size, variance, [&](double x, double y) { return lobe(x - fx, y - fy) + lobe(x + fx, y + fy); });
}

double log_spectrum_distance_db(const DiscreteSpectrum& measured, const DiscreteSpectrum& target, double floor)
{
    if (measured.size != target.size) throw Error("log_spectrum_distance_db: spectra of different sizes");
    const double peak = *std::max_element(target.power.begin(), target.power.end());
    double sum = 0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < target.power.size(); ++i) {
        if (!(target.power[i] >= floor * peak) || !(target.power[i] > 0)) continue;
        const double db = 10 * std::log10(std::max(measured.power[i], 1e-30) / target.power[i]);
        sum += db * db;
        ++count;
    }
    return count ? std::sqrt(sum / double(count)) : 0;
}

double radial_log_spectrum_distance_db(const DiscreteSpectrum& measured, const DiscreteSpectrum& target,
                                       int bins_per_octave)
{
    if (measured.size != target.size) throw Error("radial_log_spectrum_distance_db: spectra of different sizes");
    const int size = target.size;
    // Ring r holds frequencies in (½·2^-(r+1)/b, ½·2^-r/b] cycles per pixel, down to 1/T.
    const int rings = int(std::ceil(bins_per_octave * std::log2(size / 2.0))) + 1;
    std::vector<double> got(std::size_t(rings), 0.0), wanted(std::size_t(rings), 0.0);
    for (int ky = -size / 2; ky < size / 2; ++ky)
        for (int kx = -size / 2; kx < size / 2; ++kx) {
            const double f = std::hypot(kx, ky) / size;
            if (f == 0 || f > 0.5) continue;
            const int ring = std::min(rings - 1, int(std::floor(bins_per_octave * std::log2(0.5 / f))));
            got[std::size_t(ring)] += measured.at(kx, ky);
            wanted[std::size_t(ring)] += target.at(kx, ky);
        }
    double sum = 0;
    int count = 0;
    for (int r = 0; r < rings; ++r)
        if (wanted[std::size_t(r)] > 0 && got[std::size_t(r)] > 0) {
            const double db = 10 * std::log10(got[std::size_t(r)] / wanted[std::size_t(r)]);
            sum += db * db;
            ++count;
        }
    return count ? std::sqrt(sum / count) : 0;
}

std::vector<double> energy_ratios(const DiscreteSpectrum& measured, const DiscreteSpectrum& target,
                                  const std::vector<int>& label)
{
    if (measured.size != target.size || label.size() != target.power.size())
        throw Error("energy_ratios: spectra and labels of different sizes");
    const int count = label.empty() ? 0 : *std::max_element(label.begin(), label.end()) + 1;
    std::vector<double> got(std::size_t(std::max(count, 0)), 0.0), wanted(got.size(), 0.0);
    for (std::size_t i = 0; i < label.size(); ++i)
        if (label[i] >= 0) got[std::size_t(label[i])] += measured.power[i], wanted[std::size_t(label[i])] += target.power[i];
    for (std::size_t s = 0; s < got.size(); ++s) got[s] = wanted[s] > 0 ? got[s] / wanted[s] : 0;
    return got;
}

double cross_correlation_peak(const std::vector<float>& patch, int patch_size, const std::vector<float>& reference,
                              int size)
{
    const std::size_t n = std::size_t(size) * size, m = std::size_t(patch_size) * patch_size;
    if (patch_size > size || patch.size() != m || reference.size() != n)
        throw Error("cross_correlation_peak: a " + std::to_string(patch_size) + "² patch and a " + std::to_string(size) +
                    "² reference expected");
    // The centred patch, zero-padded; a box of its size; the reference and its square.
    double mean = 0;
    for (float v : patch) mean += v;
    mean /= double(m);
    std::vector<float> padded(n, 0.0f), box(n, 0.0f), squared(n);
    double patch_norm = 0;
    for (int y = 0; y < patch_size; ++y)
        for (int x = 0; x < patch_size; ++x) {
            const double v = patch[std::size_t(y) * patch_size + x] - mean;
            padded[std::size_t(y) * size + x] = float(v);
            box[std::size_t(y) * size + x] = 1.0f;
            patch_norm += v * v;
        }
    for (std::size_t i = 0; i < n; ++i) squared[i] = reference[i] * reference[i];
    if (!(patch_norm > 0)) return 0;
    // Correlation theorem: IFFT(F_r · conj(F_p))(s) = n Σ_k r(k + s) p(k) for every shift s.
    const std::vector<std::complex<float>> r = real_fft_2d(reference, size, size);
    auto correlate = [&](const std::vector<std::complex<float>>& spectrum, const std::vector<float>& with) {
        std::vector<std::complex<float>> product = real_fft_2d(with, size, size);
        for (std::size_t i = 0; i < product.size(); ++i) product[i] = spectrum[i] * std::conj(product[i]);
        std::vector<float> result = real_inverse_fft_2d(product, size, size);
        for (float& v : result) v /= float(n);
        return result;
    };
    const std::vector<float> products = correlate(r, padded), sums = correlate(r, box),
                             square_sums = correlate(real_fft_2d(squared, size, size), box);
    double best = -1;
    for (std::size_t s = 0; s < n; ++s) {
        const double window_variance = square_sums[s] - double(sums[s]) * sums[s] / double(m);
        if (window_variance > 1e-12 * square_sums[s]) best = std::max(best, products[s] / std::sqrt(patch_norm * window_variance));
    }
    return best;
}

std::vector<std::complex<double>> full_fourier_coefficients(const std::vector<std::complex<float>>& half, int size)
{
    const int half_width = size / 2 + 1;
    const double scale = 1.0 / (double(size) * size);
    std::vector<std::complex<double>> full(std::size_t(size) * size);
    auto index = [size](int kx, int ky) { return std::size_t(ky + size / 2) * size + std::size_t(kx + size / 2); };
    for (int ky = 0; ky < size; ++ky)
        for (int kx = 0; kx < half_width; ++kx) {
            const std::complex<double> c = std::complex<double>(half[std::size_t(ky) * half_width + kx]) * scale;
            const int fx = centred_bin(kx, size), fy = centred_bin(ky, size);
            full[index(fx, fy)] = c;
            if (kx != 0 && kx != size / 2) full[index(-fx, fy == -size / 2 ? fy : -fy)] = std::conj(c);
        }
    return full;
}

}  // namespace stochtex
