#include "band_power.h"

#include "fft.h"

#include <algorithm>
#include <cmath>
#include <complex>

namespace stochtex {

int supported_band_count(int width, int height)
{
    int log2_min = 0;
    while ((2 << log2_min) <= std::min(width, height)) ++log2_min;
    return std::max(0, log2_min - 1);
}

int band_of_frequency(double nu)
{
    // ν = m·2^e with m in [1/2, 1): ν in [2^-(j+2), 2^-(j+1)) ⇔ e = −(j+1). frexp is exact on
    // powers of two, where a floating-point log2 may land on the wrong side.
    int exponent = 0;
    std::frexp(nu, &exponent);
    return -exponent - 1;
}

std::vector<double> band_powers(const std::vector<float>& plane, int width, int height, int band_count,
                                PsdEstimator estimator)
{
    const int half_width = width / 2 + 1;
    std::vector<std::complex<float>> spectrum = real_fft_2d(plane, width, height);

    if (estimator == PsdEstimator::periodic_smooth) {
        // Moisan (2011): u = p + s, s smooth, p periodic. The boundary image v holds the jumps
        // across the image's edges; s solves the discrete periodic Poisson equation Δs = v, so
        // ŝ = v̂ / (2cos(2πk/W) + 2cos(2πl/H) − 4) and p̂ = û − ŝ has no edge "+".
        std::vector<float> boundary(plane.size(), 0.0f);
        auto at = [&](int x, int y) { return plane[std::size_t(y) * width + x]; };
        for (int x = 0; x < width; ++x) {
            const float jump = at(x, height - 1) - at(x, 0);
            boundary[x] += jump;
            boundary[std::size_t(height - 1) * width + x] -= jump;
        }
        for (int y = 0; y < height; ++y) {
            const float jump = at(width - 1, y) - at(0, y);
            boundary[std::size_t(y) * width] += jump;
            boundary[std::size_t(y) * width + width - 1] -= jump;
        }
        const std::vector<std::complex<float>> boundary_spectrum = real_fft_2d(boundary, width, height);
        for (int ky = 0; ky < height; ++ky)
            for (int kx = 0; kx < half_width; ++kx) {
                if (kx == 0 && ky == 0) continue;
                const double denominator =
                    2 * std::cos(2 * M_PI * kx / width) + 2 * std::cos(2 * M_PI * ky / height) - 4;
                const std::size_t i = std::size_t(ky) * half_width + kx;
                spectrum[i] -= boundary_spectrum[i] / float(denominator);
            }
    }

    std::vector<double> power(band_count, 0.0);
    if (band_count == 0) return power;
    const double normalisation = 1.0 / (double(width) * height * double(width) * height);
    for (int ky = 0; ky < height; ++ky) {
        const int fy = ky <= height / 2 ? ky : ky - height;
        for (int kx = 0; kx < half_width; ++kx) {
            if (kx == 0 && ky == 0) continue;
            // The half spectrum stores each conjugate pair once, except the columns kx = 0 and
            // (even widths) kx = W/2, which are their own mirror images.
            const bool self_mirrored = kx == 0 || (width % 2 == 0 && kx == width / 2);
            const double multiplicity = self_mirrored ? 1.0 : 2.0;
            const double nu = std::max(double(kx) / width, std::abs(double(fy)) / height);
            const int band = std::clamp(band_of_frequency(nu), 0, band_count - 1);
            power[band] += multiplicity * std::norm(spectrum[std::size_t(ky) * half_width + kx]) * normalisation;
        }
    }
    return power;
}

}  // namespace stochtex
