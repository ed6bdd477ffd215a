// Crops of an image plane made periodic: what tiling's exemplar and the unbounded ptm's
// coefficient maps are cut from. Moisan's periodic component (spectra/fft.h) removes the jump
// between opposite edges, so the crop tiles without a seam (tiles are cut anywhere in an
// exemplar, with wrap: a seam would show inside tiles, notes P2.7 #6). In spectra/, below the
// models, because both of those models use it and models do not include each other.
#pragma once

#include <vector>

namespace stochtex {

/// Where a crop starts in its photo (pixels); x < 0: centred.
struct CropOrigin {
    int x = -1, y = -1;
};

/// The w × h part of a plane (`width` pixels per row) at (x0, y0), copied as it is.
std::vector<float> plane_region(const std::vector<float>& plane, int width, int x0, int y0, int w, int h);

/// The crop_width × crop_height part of a plane at origin (default: centred), made periodic
/// (Moisan's periodic component, which keeps the crop's mean).
std::vector<float> periodic_crop(const std::vector<float>& plane, int width, int height, int crop_width, int crop_height,
                                 CropOrigin origin = {});

}  // namespace stochtex
