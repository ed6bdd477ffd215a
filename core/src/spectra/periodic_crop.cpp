#include "spectra/periodic_crop.h"

#include "spectra/fft.h"

#include <algorithm>
#include <cstddef>

namespace stochtex {

std::vector<float> plane_region(const std::vector<float>& plane, int width, int x0, int y0, int w, int h)
{
    std::vector<float> crop(std::size_t(w) * h);
    for (int y = 0; y < h; ++y) std::copy_n(&plane[std::size_t(y0 + y) * width + x0], w, &crop[std::size_t(y) * w]);
    return crop;
}

std::vector<float> periodic_crop(const std::vector<float>& plane, int width, int height, int crop_width, int crop_height,
                                 CropOrigin origin)
{
    if (origin.x < 0) origin = {(width - crop_width) / 2, (height - crop_height) / 2};
    const std::vector<float> crop = plane_region(plane, width, origin.x, origin.y, crop_width, crop_height);
    // The inverse transform is unnormalised: divide by the pixel count.
    std::vector<float> periodic = real_inverse_fft_2d(periodic_component_fft_2d(crop, crop_width, crop_height), crop_width, crop_height);
    const float scale = 1.0f / (float(crop_width) * float(crop_height));
    for (float& value : periodic) value *= scale;
    return periodic;
}

}  // namespace stochtex
