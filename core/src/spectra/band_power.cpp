#include "spectra/band_power.h"

#include "spectra/fft.h"

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
    const std::vector<std::complex<float>> spectrum = estimator == PsdEstimator::periodic_smooth
                                                          ? periodic_component_fft_2d(plane, width, height)
                                                          : real_fft_2d(plane, width, height);

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
