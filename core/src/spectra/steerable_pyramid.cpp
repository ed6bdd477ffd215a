#include "spectra/steerable_pyramid.h"

#include "spectra/fft.h"
#include "numerics/constants.h"

#include <stochtex/error.h>

#include <cmath>
#include <string>

namespace stochtex {

namespace {

// The log-radial masks of Portilla & Simoncelli's code, with ω in radians per sample (π at
// Nyquist): the high mask rises from 0 at ω = π/4 to 1 at ω = π/2 as a raised cosine in log2 ω,
// and low² + high² = 1, so a level splits its input into band and low-pass without loss, and the
// low-pass is 0 above π/2, where halving the resolution would alias.
double high_mask(double omega) {
    if (omega <= 0) return 0;
    const double x = std::log2(omega / kPi);
    if (x >= -1) return 1;
    if (x <= -2) return 0;
    return std::cos(kPi / 2 * (-1 - x));
}
double low_mask(double omega) {
    const double h = high_mask(omega);
    return std::sqrt(std::max(0.0, 1 - h * h));
}

/// Signed frequency index of FFT bin k of n.
int signed_index(int k, int n) { return k < n / 2 ? k : k - n; }

/// The analytic angular mask of orientation θ_k: 2α·cos(θ − θ_k)^(K−1) on the half-plane
/// cos(θ − θ_k) > 0, 0 on the other (P–S's normalisation α = 2^(K−1)(K−1)!/√(K·(2(K−1))!)).
struct AngularMask {
    int orientations;
    double alpha;
    explicit AngularMask(int k) : orientations(k) {
        double factorial = 1, double_factorial = 1;
        for (int i = 2; i <= k - 1; ++i) factorial *= i;
        for (int i = 2; i <= 2 * (k - 1); ++i) double_factorial *= i;
        alpha = std::pow(2.0, k - 1) * factorial / std::sqrt(k * double_factorial);
    }
    double operator()(double theta, int k) const {
        const double c = std::cos(theta - kPi * k / orientations);
        return c > 0 ? 2 * alpha * std::pow(c, orientations - 1) : 0;
    }
};

/// The frequency of every FFT bin of a width×height level: radius ω (radians per pixel) and angle θ.
struct FrequencyGrid {
    std::vector<double> omega, theta;
    FrequencyGrid(int width, int height) : omega(std::size_t(width) * height), theta(omega.size()) {
        for (int ky = 0; ky < height; ++ky)
            for (int kx = 0; kx < width; ++kx) {
                const double fx = double(signed_index(kx, width)) / width, fy = double(signed_index(ky, height)) / height;
                const std::size_t i = std::size_t(ky) * width + kx;
                omega[i] = 2 * kPi * std::hypot(fx, fy);
                theta[i] = std::atan2(fy, fx);
            }
    }
};

/// The image of spectrum × mask, at the spectrum's resolution (1/n of the unnormalised inverse).
std::vector<std::complex<float>> filtered(const std::vector<std::complex<float>>& spectrum, int width, int height,
                                          const std::vector<float>& mask) {
    std::vector<std::complex<float>> out(spectrum.size());
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = spectrum[i] * mask[i];
    complex_fft_2d(out, width, height, true);
    const float scale = 1.0f / float(std::size_t(width) * height);
    for (auto& v : out) v *= scale;
    return out;
}

std::vector<float> real_part(const std::vector<std::complex<float>>& values) {
    std::vector<float> out(values.size());
    for (std::size_t i = 0; i < values.size(); ++i) out[i] = values[i].real();
    return out;
}

}  // namespace

SteerablePyramid build_steerable_pyramid(const std::vector<float>& plane, int width, int height, int scales,
                                         int orientations) {
    const int step = 1 << scales;
    if (scales < 1 || orientations < 1 || width < step || height < step || width % step || height % step ||
        plane.size() != std::size_t(width) * height)
        throw Error("build_steerable_pyramid: a " + std::to_string(width) + "x" + std::to_string(height) +
                    " plane is not a multiple of 2^" + std::to_string(scales) + " on each side");
    // The full spectrum from the half one FFTW's r2c returns (Hermitian symmetry).
    const std::vector<std::complex<float>> half = periodic_component_fft_2d(plane, width, height);
    const int half_width = width / 2 + 1;
    std::vector<std::complex<float>> spectrum(std::size_t(width) * height);
    for (int ky = 0; ky < height; ++ky)
        for (int kx = 0; kx < width; ++kx)
            spectrum[std::size_t(ky) * width + kx] =
                kx < half_width ? half[std::size_t(ky) * half_width + kx]
                                : std::conj(half[std::size_t((height - ky) % height) * half_width + (width - kx)]);
    // The initial low-pass (P–S's L0: the low mask at ω/2) leaves out the corners past Nyquist.
    const FrequencyGrid full_grid(width, height);
    for (std::size_t i = 0; i < spectrum.size(); ++i) spectrum[i] *= float(low_mask(full_grid.omega[i] / 2));
    const AngularMask angular(orientations);
    SteerablePyramid pyramid;
    int w = width, h = height;
    for (int s = 0; s < scales; ++s) {
        SteerablePyramidLevel level;
        level.width = w, level.height = h;
        const FrequencyGrid grid(w, h);
        const std::size_t n = grid.omega.size();
        level.lowpass = real_part(filtered(spectrum, w, h, std::vector<float>(n, 1.0f)));
        std::vector<float> high(n), parent_radial(n), mask(n);
        for (std::size_t i = 0; i < n; ++i) {
            high[i] = float(high_mask(grid.omega[i]));
            parent_radial[i] = float(low_mask(grid.omega[i]) * high_mask(2 * grid.omega[i]));
        }
        for (int k = 0; k < orientations; ++k) {
            std::vector<float> orientation(n);
            for (std::size_t i = 0; i < n; ++i) orientation[i] = float(angular(grid.theta[i], k));
            for (std::size_t i = 0; i < n; ++i) mask[i] = high[i] * orientation[i];
            level.bands.push_back(filtered(spectrum, w, h, mask));
            if (s + 1 < scales) {
                for (std::size_t i = 0; i < n; ++i) mask[i] = parent_radial[i] * orientation[i];
                level.parent_bands.push_back(filtered(spectrum, w, h, mask));
            }
        }
        // The next level: low-pass, then the central half of the spectrum, which is the low-pass
        // sampled at every second pixel (÷4: the unnormalised DFT of a quarter as many samples).
        const int w2 = w / 2, h2 = h / 2;
        std::vector<std::complex<float>> next(std::size_t(w2) * h2);
        for (int ky = 0; ky < h2; ++ky)
            for (int kx = 0; kx < w2; ++kx) {
                const int sx = signed_index(kx, w2), sy = signed_index(ky, h2);
                const int source_x = (sx + w) % w, source_y = (sy + h) % h;
                const double omega = 2 * kPi * std::hypot(double(sx) / w, double(sy) / h);
                next[std::size_t(ky) * w2 + kx] = spectrum[std::size_t(source_y) * w + source_x] * float(low_mask(omega) / 4);
            }
        spectrum = std::move(next);
        w = w2, h = h2;
        pyramid.levels.push_back(std::move(level));
    }
    pyramid.residual_width = w, pyramid.residual_height = h;
    pyramid.residual_lowpass = real_part(filtered(spectrum, w, h, std::vector<float>(spectrum.size(), 1.0f)));
    return pyramid;
}

}  // namespace stochtex
