#include "spectra/spectral_orientation.h"

#include <stochtex/error.h>

#include "spectra/fft.h"
#include "numerics/constants.h"

#include <cmath>
#include <complex>

namespace stochtex {

SpectralOrientation spectral_orientation(const std::vector<float>& plane, int width, int height)
{
    if (width < 2 || height < 2 || plane.size() != std::size_t(width) * height)
        throw Error("spectral_orientation: the plane does not match a " + std::to_string(width) + "x" +
                    std::to_string(height) + " image of at least 2x2");
    const std::vector<std::complex<float>> spectrum = periodic_component_fft_2d(plane, width, height);
    const int spectrum_width = width / 2 + 1;
    std::complex<double> moment = 0;
    double total = 0;
    for (int ky = 0; ky < height; ++ky) {
        // Rows go down: frequency towards y up is the negated row frequency.
        const double fy = -double(ky <= height / 2 ? ky : ky - height) / height;
        for (int kx = 0; kx < spectrum_width; ++kx) {
            if (kx == 0 && ky == 0) continue;  // the mean
            const double fx = double(kx) / width;
            // e^{2iθ} is the same for f and −f: the omitted mirror half counts twice.
            const double multiplicity = (kx == 0 || 2 * kx == width) ? 1.0 : 2.0;
            const double power = multiplicity * std::norm(spectrum[std::size_t(ky) * spectrum_width + kx]);
            const double theta = std::atan2(fy, fx);
            moment += power * std::polar(1.0, 2 * theta);
            total += power;
        }
    }
    SpectralOrientation result;
    if (total > 0) {
        result.strength = std::abs(moment) / total;
        result.angle_degrees = std::arg(moment) / 2 * 180 / kPi;
    }
    return result;
}

}  // namespace stochtex
