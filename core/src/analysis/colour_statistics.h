// stochtex — colour statistics of an RGB image (the colour part of compare_images;
// docs/metrics.md).
#pragma once

#include <stochtex/image.h>

#include <array>
#include <vector>

namespace stochtex {

/// Throws Error, its message starting with `role`, unless `image` is a non-empty 3-channel image.
void require_rgb(const Image& image, const char* role);

/// ‖test − reference‖_F / ‖reference‖_F of two colour covariances; throws Error where the
/// reference is zero (a constant image).
double relative_frobenius_error(const std::array<std::array<double, 3>, 3>& reference,
                                const std::array<std::array<double, 3>, 3>& test);

/// The a*b* bins a test pixel may fall in without counting as false colour (false_colour_rate's
/// region of the reference), and the fraction of a test image's pixels outside such a region:
/// compare_images makes the photo's region once.
std::vector<char> held_chroma_region(const Image& reference);
double outside_region_rate(const std::vector<char>& region, const Image& test);

}  // namespace stochtex
