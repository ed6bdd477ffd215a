#include "fft.h"

#include <stochtex/error.h>

#include <fftw3.h>

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

}  // namespace stochtex
