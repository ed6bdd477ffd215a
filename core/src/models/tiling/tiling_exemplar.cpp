#include "models/tiling/tiling_exemplar.h"

#include "spectra/fft.h"
#include "stex/quantised_image.h"
#include "models/tiling/tiling_parameters.h"

#include <stochtex/error.h>
#include <stochtex/models/tiling_parameters.h>

#include <algorithm>
#include <cmath>

namespace stochtex {

int power_of_two_floor(int n)
{
    int p = 1;
    while (p <= n / 2) p *= 2;
    return p;
}

std::vector<float> periodic_crop(const std::vector<float>& plane, int width, int height, int crop_width, int crop_height)
{
    const int x0 = (width - crop_width) / 2, y0 = (height - crop_height) / 2;
    std::vector<float> crop(std::size_t(crop_width) * crop_height);
    for (int y = 0; y < crop_height; ++y)
        std::copy_n(&plane[std::size_t(y0 + y) * width + x0], crop_width, &crop[std::size_t(y) * crop_width]);
    // The inverse transform is unnormalised: divide by the pixel count.
    std::vector<float> periodic = real_inverse_fft_2d(periodic_component_fft_2d(crop, crop_width, crop_height), crop_width, crop_height);
    const float scale = 1.0f / (float(crop_width) * float(crop_height));
    for (float& value : periodic) value *= scale;
    return periodic;
}

TilingParameters fit_tiling_exemplar(const std::array<std::vector<float>, 3>& channels, int width, int height,
                                     const std::array<HistogramMap, 3>& histograms, int max_side, int bits)
{
    if (max_side < min_tiling_exemplar_side || max_side > max_tiling_exemplar_side)
        throw Error("tiling exemplar size must be in [" + std::to_string(min_tiling_exemplar_side) + ", " +
                    std::to_string(max_tiling_exemplar_side) + "], got " + std::to_string(max_side));
    if (bits != 8 && bits != 16) throw Error("tiling exemplar bits must be 8 or 16, got " + std::to_string(bits));
    const int crop_width = power_of_two_floor(std::min(width, max_side));
    const int crop_height = power_of_two_floor(std::min(height, max_side));
    if (crop_width < min_tiling_exemplar_side || crop_height < min_tiling_exemplar_side)
        throw Error("image is " + std::to_string(width) + "x" + std::to_string(height) + ", too small for a tiling exemplar (at least " +
                    std::to_string(min_tiling_exemplar_side) + "x" + std::to_string(min_tiling_exemplar_side) + ")");
    std::vector<std::vector<float>> planes;
    for (int c = 0; c < 3; ++c) {
        planes.push_back(periodic_crop(channels[c], width, height, crop_width, crop_height));
        if (!histograms[c].enabled()) continue;
        double sum = 0, sum2 = 0;
        for (float v : channels[c]) sum += v, sum2 += double(v) * v;
        const double n = double(channels[c].size()), sigma = std::sqrt(std::max(0.0, sum2 / n - (sum / n) * (sum / n)));
        if (sigma > 0)
            for (float& v : planes.back()) v = float(v / sigma);
    }
    TilingParameters parameters;
    parameters.output = TilingOutput::colour;
    parameters.exemplar = quantise(planes, crop_width, crop_height, bits);
    return parameters;
}

}  // namespace stochtex
