#include "models/tiling/tiling_estimator_reference.h"

#include <stochtex/error.h>

#include <algorithm>
#include <cmath>

namespace stochtex {

NoiseRaster sample_noise(const TilingNoise& noise, double origin_x, double origin_y, int size)
{
    NoiseRaster raster;
    raster.size = size, raster.origin_x = origin_x, raster.origin_y = origin_y;
    raster.samples.reserve(std::size_t(size) * size);
    for (int j = 0; j < size; ++j)
        for (int i = 0; i < size; ++i) raster.samples.push_back(noise.point(origin_x + i + 0.5, origin_y + j + 0.5));
    return raster;
}

std::vector<NoiseBlock> noise_blocks(const NoiseRaster& raster, int k, const MomentColour& point_colour)
{
    if (k < 1 || raster.size % k) throw Error("noise blocks: the block size must divide the raster");
    const int per_side = raster.size / k;
    std::vector<Rgb> colours(raster.samples.size());
    for (std::size_t i = 0; i < colours.size(); ++i) colours[i] = point_colour(raster.samples[i]);
    std::vector<NoiseBlock> blocks;
    const double weight = 1.0 / (double(k) * k);
    for (int by = 0; by < per_side; ++by)
        for (int bx = 0; bx < per_side; ++bx) {
            NoiseBlock block;
            block.x = raster.origin_x + (bx + 0.5) * k, block.y = raster.origin_y + (by + 0.5) * k;
            MomentMixture mixture(raster.samples[0].channels);
            double sum[3] = {0, 0, 0};
            for (int j = 0; j < k; ++j)
                for (int i = 0; i < k; ++i) {
                    const std::size_t p = std::size_t(by * k + j) * raster.size + std::size_t(bx * k + i);
                    mixture.add(weight, raster.samples[p]);
                    for (int c = 0; c < 3; ++c) sum[c] += colours[p][c];
                }
            block.exact = mixture.result();
            for (int c = 0; c < 3; ++c) block.box_colour[c] = float(sum[c] * weight);
            blocks.push_back(block);
        }
    return blocks;
}

ErrorSummary summarise(std::vector<double> errors)
{
    ErrorSummary s;
    if (errors.empty()) return s;
    double sum = 0;
    for (double e : errors) sum += e;
    s.mean = sum / double(errors.size());
    const std::size_t at = std::min(errors.size() - 1, std::size_t(std::ceil(0.95 * double(errors.size()))) - 1);
    std::nth_element(errors.begin(), errors.begin() + std::ptrdiff_t(at), errors.end());
    s.p95 = errors[at];
    return s;
}

double colour_distance(const Rgb& a, const Rgb& b)
{
    const double d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
    return std::sqrt(d0 * d0 + d1 * d1 + d2 * d2);
}

std::vector<double> zoom_flicker(const std::function<Rgb(double x, double y, double pixel_size)>& render_pixel, double x,
                                 double y, int frame_size, int frames, double first_scale, double last_scale)
{
    std::vector<Rgb> previous, current(std::size_t(frame_size) * frame_size);
    std::vector<double> change;
    for (int t = 0; t < frames; ++t) {
        const double scale = first_scale * std::pow(last_scale / first_scale, frames > 1 ? double(t) / (frames - 1) : 0.0);
        for (int j = 0; j < frame_size; ++j)
            for (int i = 0; i < frame_size; ++i)
                current[std::size_t(j) * frame_size + i] =
                    render_pixel(x + (i + 0.5 - 0.5 * frame_size) * scale, y + (j + 0.5 - 0.5 * frame_size) * scale, scale);
        if (!previous.empty()) {
            double sum = 0;
            for (std::size_t p = 0; p < current.size(); ++p) sum += colour_distance(current[p], previous[p]);
            change.push_back(sum / double(current.size()));
        }
        previous = current;
    }
    return change;
}

}  // namespace stochtex
