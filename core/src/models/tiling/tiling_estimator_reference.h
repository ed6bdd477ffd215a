// Measuring the tiling estimators against brute force (paper 002 §6; notes P2.8): the one
// place that defines the reference used by the tests, `bench/tiling_report` and the tables of
// docs/models/tiling.md.
//
// Reference: N point-sampled at every exemplar pixel of a size × size window (pixel centres),
// split into k × k blocks. A block's exact moments are those of its k² samples; its filtered
// colour S̄ is the box mean of the colour of each sample (S(N) for a colour map).
#pragma once

#include "models/tiling/tiling_noise.h"

#include <stochtex/texture.h>

#include <functional>
#include <vector>

namespace stochtex {

/// The colour one sample (point moments: variance 0) or one footprint (filtered moments) shows.
using MomentColour = std::function<Rgb(const Moments&)>;

struct NoiseRaster {
    int size = 0;
    double origin_x = 0, origin_y = 0;  // exemplar pixels; pixel (i, j) is at origin + (i + ½, j + ½)
    std::vector<Moments> samples;      // N at each pixel (variance 0)
};
NoiseRaster sample_noise(const TilingNoise& noise, double origin_x, double origin_y, int size);

struct NoiseBlock {
    double x = 0, y = 0;  ///< centre, exemplar pixels
    Moments exact;        ///< mean and covariance of N over the block's samples
    Rgb box_colour{};     ///< S̄: mean of point_colour over the samples
};
/// size / k blocks per side (k divides size).
std::vector<NoiseBlock> noise_blocks(const NoiseRaster& raster, int k, const MomentColour& point_colour);

struct ErrorSummary {
    double mean = 0, p95 = 0;
};
ErrorSummary summarise(std::vector<double> errors);

double colour_distance(const Rgb& a, const Rgb& b);

/// A slow zoom: frames of `frame_size`² pixels around (x, y), the pixel size growing
/// geometrically from first_scale to last_scale exemplar pixels over `frames` frames. Returns
/// the mean frame-to-frame change ‖F_{t+1}(p) − F_t(p)‖ at fixed pixels p, per frame pair —
/// the flicker metric (content moves less than a pixel between frames, so a stable filter
/// changes little; an aliased one jumps to unrelated values).
std::vector<double> zoom_flicker(const std::function<Rgb(double x, double y, double pixel_size)>& render_pixel, double x,
                                 double y, int frame_size, int frames, double first_scale, double last_scale);

}  // namespace stochtex
