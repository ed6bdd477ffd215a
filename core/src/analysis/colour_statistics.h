// stochtex — colour statistics of an RGB image (the colour part of compare_images;
// docs/metrics.md).
#pragma once

#include <stochtex/image.h>

#include <array>
#include <vector>

namespace stochtex {

std::array<double, 3> channel_means(const Image& rgb);
std::array<std::array<double, 3>, 3> colour_covariance(const Image& rgb);
/// ‖cov(test) − cov(reference)‖_F / ‖cov(reference)‖_F.
double covariance_relative_error(const Image& reference, const Image& test);

/// Chroma of linear Rec.709 RGB as CIELAB a*, b* (D65 white): perceptually near-uniform, and a
/// dark pixel's chroma shrinks with its lightness as a person sees it.
std::array<double, 2> cielab_chroma(float r, float g, float b);

/// The fraction of test pixels whose chroma lies outside the region holding 99.5 % of the
/// reference's chroma: on a grid of a*b* bins of side 2.3 (one just-noticeable difference,
/// ΔE*ab ≈ 2.3) over [−128, 128]², the densest reference bins holding 99.5 % of its pixels,
/// dilated by one bin (8-neighbours). A photo's own other crop scores ≈ 0; flecks of a hue the
/// photo never has score their area.
double false_colour_rate(const Image& reference, const Image& test);

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
