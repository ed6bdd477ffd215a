#include "spectra/fft.h"

#include "numerics/constants.h"

#include <stochtex/error.h>

#include <fftw3.h>

#include <cmath>
#include <cstring>
#include <mutex>

namespace stochtex {

namespace {
std::mutex& planner_mutex()
{
    static std::mutex mutex;
    return mutex;
}
}  // namespace

std::vector<std::complex<float>> real_fft_2d(const std::vector<float>& plane, int width, int height)
{
    if (width <= 0 || height <= 0 || plane.size() != std::size_t(width) * height)
        throw Error("real_fft_2d: plane size does not match " + std::to_string(width) + "x" + std::to_string(height));
    const std::size_t half = std::size_t(width / 2 + 1);
    float* input = fftwf_alloc_real(plane.size());
    fftwf_complex* output = fftwf_alloc_complex(half * height);
    fftwf_plan plan;
    {
        std::lock_guard<std::mutex> lock(planner_mutex());
        plan = fftwf_plan_dft_r2c_2d(height, width, input, output, FFTW_ESTIMATE);
    }
    std::memcpy(input, plane.data(), plane.size() * sizeof(float));
    fftwf_execute(plan);
    std::vector<std::complex<float>> spectrum(half * height);
    std::memcpy(static_cast<void*>(spectrum.data()), output, spectrum.size() * sizeof(fftwf_complex));
    {
        std::lock_guard<std::mutex> lock(planner_mutex());
        fftwf_destroy_plan(plan);
    }
    fftwf_free(input);
    fftwf_free(output);
    return spectrum;
}

std::vector<std::complex<float>> periodic_component_fft_2d(const std::vector<float>& plane, int width, int height)
{
    std::vector<std::complex<float>> spectrum = real_fft_2d(plane, width, height);
    // Moisan (2011): u = p + s, s smooth, p periodic. The boundary image v holds the jumps
    // across the image's edges; s solves the discrete periodic Poisson equation Δs = v, so
    // ŝ = v̂ / (2cos(2πk/W) + 2cos(2πl/H) − 4) and p̂ = û − ŝ has no edge "+".
    const int half_width = width / 2 + 1;
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
            const double denominator = 2 * std::cos(2 * kPi * kx / width) + 2 * std::cos(2 * kPi * ky / height) - 4;
            const std::size_t i = std::size_t(ky) * half_width + kx;
            spectrum[i] -= boundary_spectrum[i] / float(denominator);
        }
    return spectrum;
}

std::vector<float> real_inverse_fft_2d(const std::vector<std::complex<float>>& half_spectrum, int width, int height)
{
    const std::size_t half = std::size_t(width / 2 + 1);
    if (width <= 0 || height <= 0 || half_spectrum.size() != half * height)
        throw Error("real_inverse_fft_2d: spectrum size does not match " + std::to_string(width) + "x" +
                    std::to_string(height));
    fftwf_complex* input = fftwf_alloc_complex(half * height);
    float* output = fftwf_alloc_real(std::size_t(width) * height);
    fftwf_plan plan;
    {
        std::lock_guard<std::mutex> lock(planner_mutex());
        plan = fftwf_plan_dft_c2r_2d(height, width, input, output, FFTW_ESTIMATE);
    }
    // (c2r overwrites its input, so it gets a copy.)
    std::memcpy(input, half_spectrum.data(), half_spectrum.size() * sizeof(fftwf_complex));
    fftwf_execute(plan);
    std::vector<float> plane(output, output + std::size_t(width) * height);
    {
        std::lock_guard<std::mutex> lock(planner_mutex());
        fftwf_destroy_plan(plan);
    }
    fftwf_free(input);
    fftwf_free(output);
    return plane;
}

void complex_fft_2d(std::vector<std::complex<float>>& data, int width, int height, bool inverse)
{
    if (width <= 0 || height <= 0 || data.size() != std::size_t(width) * height)
        throw Error("complex_fft_2d: array size does not match " + std::to_string(width) + "x" + std::to_string(height));
    fftwf_complex* buffer = fftwf_alloc_complex(data.size());
    fftwf_plan plan;
    {
        std::lock_guard<std::mutex> lock(planner_mutex());
        plan = fftwf_plan_dft_2d(height, width, buffer, buffer, inverse ? FFTW_BACKWARD : FFTW_FORWARD, FFTW_ESTIMATE);
    }
    std::memcpy(static_cast<void*>(buffer), data.data(), data.size() * sizeof(fftwf_complex));
    fftwf_execute(plan);
    std::memcpy(static_cast<void*>(data.data()), buffer, data.size() * sizeof(fftwf_complex));
    {
        std::lock_guard<std::mutex> lock(planner_mutex());
        fftwf_destroy_plan(plan);
    }
    fftwf_free(buffer);
}

}  // namespace stochtex
