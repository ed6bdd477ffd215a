// stochtex benchmarks — the photo crops (and rearrangements) they measure on.
#pragma once

#include <stochtex/image.h>

#include <algorithm>

namespace stochtex::bench {

/// The top-left size × size pixels of an RGB image (fewer where it is smaller).
inline Image top_left_crop(const Image& image, int size)
{
    const int w = std::min(size, image.width), h = std::min(size, image.height);
    Image out(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) out.at(x, y, c) = image.at(x, y, c);
    return out;
}

/// The square image mirrored about its diagonal: (x, y) takes (y, x). Paired with the photo
/// itself as a colour map's two noises, it gives a nearly uncorrelated pair with the same
/// statistics on both axes (the photo twice is a perfectly correlated one).
inline Image transposed(const Image& image)
{
    Image out = image;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < image.channels; ++c) out.at(x, y, c) = image.at(y, x, c);
    return out;
}

}  // namespace stochtex::bench
